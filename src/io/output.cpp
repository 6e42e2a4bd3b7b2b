// Safe output files (see output.hpp): exclusive temporary file, checked writes, fsync, rename.
#include "nocdyn/io/output.hpp"

#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <random>
#include <utility>

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::io {

namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 16;

std::atomic<CommitObserver> commit_observer{nullptr};

[[noreturn]] void fail(const std::string& what, const std::string& path, int error) {
    throw Error(what + " '" + path + "': " + std::strerror(error));
}

/// The temporaries in progress, for the signal handler: fixed storage (no allocation in the
/// handler), each slot claimed by `used`, readable by the handler once `ready`.
struct PendingSlot {
    std::atomic<bool> used{false};
    std::atomic<bool> ready{false};
    std::array<char, PATH_MAX> path{};
};
constexpr int kPendingSlots = 64;
std::array<PendingSlot, kPendingSlots> g_pending;

/// Lists a temporary (its slot, or -1 when every slot is taken: then only the destructor
/// removes it).
int listPending(const std::string& path) {
    if (path.size() >= PATH_MAX) return -1;
    for (int i = 0; i < kPendingSlots; ++i) {
        PendingSlot& slot = g_pending[static_cast<std::size_t>(i)];
        bool expected = false;
        if (!slot.used.compare_exchange_strong(expected, true)) continue;
        std::memcpy(slot.path.data(), path.c_str(), path.size() + 1);
        slot.ready.store(true);
        return i;
    }
    return -1;
}

void unlistPending(int& index) noexcept {
    if (index < 0) return;
    PendingSlot& slot = g_pending[static_cast<std::size_t>(index)];
    slot.ready.store(false);
    slot.used.store(false);
    index = -1;
}

extern "C" void removeTemporariesAndExit(int signal_number) {
    for (PendingSlot& slot : g_pending) {
        if (slot.ready.load()) (void)::unlink(slot.path.data());
    }
    ::signal(signal_number, SIG_DFL);
    ::raise(signal_number);
}

/// 16 hexadecimal digits from the kernel's random source (std::random_device as a fallback).
std::string randomSuffix() {
    unsigned long long bits = 0;
    if (getrandom(&bits, sizeof bits, 0) != static_cast<ssize_t>(sizeof bits)) {
        std::random_device device;
        bits = (static_cast<unsigned long long>(device()) << 32) ^ device();
    }
    return text::format("%016llx", bits);
}

void writeAll(int fd, const char* data, std::size_t size, const std::string& path) {
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail("cannot write", path, errno);
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
}

/// A new file opened exclusively, never through a link; the descriptor, or -errno.
int openExclusive(const std::string& path) {
    const int fd = ::open(path.c_str(), O_CREAT | O_EXCL | O_NOFOLLOW | O_WRONLY | O_CLOEXEC, 0666);
    return fd >= 0 ? fd : -errno;
}

}  // namespace

int createNewFile(const std::string& path) {
    const int fd = openExclusive(path);
    if (fd < 0) fail("cannot create", path, -fd);
    return fd;
}

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
    buffer_.resize(kBufferBytes);
    struct stat entry {};
    if (::lstat(path_.c_str(), &entry) == 0) {
        struct stat target = entry;
        const bool link = S_ISLNK(entry.st_mode);
        const bool resolved = !link || ::stat(path_.c_str(), &target) == 0;
        if (resolved && !S_ISREG(target.st_mode)) {
            // A device, FIFO, directory or a link to one: write through, never replace it.
            fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
            if (fd_ < 0) fail("cannot write", path_, errno);
            owns_fd_ = true;
            return;
        }
    } else if (errno != ENOENT) {
        fail("cannot write", path_, errno);
    }
    // A new file beside the target; a long name is shortened to stay within NAME_MAX.
    const std::filesystem::path target(path_);
    std::string stem = target.filename().string().substr(0, 200);
    for (int attempt = 0;; ++attempt) {
        const std::string name = "." + stem + "." + randomSuffix() + ".tmp";
        temporary_ = (target.parent_path() / name).string();
        fd_ = openExclusive(temporary_);
        if (fd_ >= 0) break;
        const int error = -fd_;
        fd_ = -1;
        temporary_.clear();
        if (error != EEXIST || attempt == 16) fail("cannot write", path_, error);
    }
    owns_fd_ = true;
    pending_ = listPending(temporary_);
    // Replacing a regular file keeps its permission bits.
    if (S_ISREG(entry.st_mode)) (void)::fchmod(fd_, entry.st_mode & 07777);
}

OutputFile OutputFile::standardOutput() {
    std::cout.flush();
    std::fflush(stdout);
    OutputFile out;
    out.path_ = "standard output";
    out.fd_ = STDOUT_FILENO;
    out.buffer_.resize(kBufferBytes);
    return out;
}

OutputFile::OutputFile(OutputFile&& other) noexcept
    : path_(std::move(other.path_)),
      temporary_(std::exchange(other.temporary_, {})),
      fd_(std::exchange(other.fd_, -1)),
      owns_fd_(std::exchange(other.owns_fd_, false)),
      committed_(std::exchange(other.committed_, true)),
      buffer_(std::move(other.buffer_)),
      used_(std::exchange(other.used_, 0)),
      pending_(std::exchange(other.pending_, -1)) {}

OutputFile::~OutputFile() { discard(); }

void OutputFile::discard() noexcept {
    if (committed_) return;
    committed_ = true;
    if (owns_fd_ && fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
    unlistPending(pending_);
}

void OutputFile::flushBuffer() {
    if (committed_) throw Error("write to '" + path_ + "' after it was committed");
    writeAll(fd_, buffer_.data(), used_, path_);
    used_ = 0;
}

void OutputFile::write(std::string_view bytes) {
    if (used_ + bytes.size() > buffer_.size()) flushBuffer();
    if (bytes.size() > buffer_.size()) {
        writeAll(fd_, bytes.data(), bytes.size(), path_);
        return;
    }
    std::memcpy(buffer_.data() + used_, bytes.data(), bytes.size());
    used_ += bytes.size();
}

char* OutputFile::reserve(std::size_t n) {
    if (used_ + n > buffer_.size()) flushBuffer();
    if (n > buffer_.size()) buffer_.resize(n);
    return buffer_.data() + used_;
}

int OutputFile::descriptor() {
    flushBuffer();
    return fd_;
}

void OutputFile::commit() {
    flushBuffer();
    if (!temporary_.empty()) {
        if (::fsync(fd_) != 0) fail("cannot write", path_, errno);
    }
    if (owns_fd_) {
        const int fd = std::exchange(fd_, -1);
        if (::close(fd) != 0) fail("cannot write", path_, errno);
    }
    if (!temporary_.empty()) {
        if (::rename(temporary_.c_str(), path_.c_str()) != 0) fail("cannot write", path_, errno);
        temporary_.clear();
        unlistPending(pending_);
        // Make the rename itself durable (best effort: not every file system syncs directories).
        const std::filesystem::path parent = std::filesystem::path(path_).parent_path();
        const std::filesystem::path directory = parent.empty() ? std::filesystem::path(".") : parent;
        if (const int dir = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
            (void)::fsync(dir);
            ::close(dir);
        }
        if (const CommitObserver observer = commit_observer.load()) observer(path_);
    }
    committed_ = true;
}

void setCommitObserver(CommitObserver observer) { commit_observer.store(observer); }

void removeTemporariesOnSignals() {
    struct sigaction action {};
    action.sa_handler = removeTemporariesAndExit;
    sigemptyset(&action.sa_mask);
    for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signal_number, &action, nullptr);
}

}  // namespace nocdyn::io
