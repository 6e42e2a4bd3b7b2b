// Safe input files and strict numbers (see file_util.hpp).
#include "file_util.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>

#include "nocdyn/error.hpp"

namespace nocdyn::io::detail {

namespace {

/// Closes a file descriptor on every path out of readRegularFile.
struct FileDescriptor {
    int fd = -1;
    ~FileDescriptor() {
        if (fd >= 0) ::close(fd);
    }
};

std::string describeSize(std::size_t bytes) {
    if (bytes >= (std::size_t{1} << 20)) return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

}  // namespace

std::string readRegularFile(const std::string& path, const char* what, std::size_t max_bytes) {
    const std::string name = std::string(what) + " '" + path + "'";
    // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused just below.
    FileDescriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY)};
    if (file.fd < 0) throw Error("cannot open " + name + ": " + std::strerror(errno));
    struct stat info {};
    if (::fstat(file.fd, &info) != 0) throw Error("cannot read " + name + ": " + std::strerror(errno));
    if (!S_ISREG(info.st_mode)) throw Error(name + " is not a regular file");
    const std::string limit = "larger than the " + describeSize(max_bytes) + " accepted";
    if (info.st_size < 0 || static_cast<unsigned long long>(info.st_size) > max_bytes) {
        throw Error(name + " is " + limit);
    }
    std::string text;
    text.resize(static_cast<std::size_t>(info.st_size));
    std::size_t used = 0;
    char probe = 0;
    for (;;) {
        // Read into the buffer, then one byte more to see whether the file grew past the cap.
        char* into = used < text.size() ? text.data() + used : &probe;
        const std::size_t room = used < text.size() ? text.size() - used : 1;
        const ssize_t got = ::read(file.fd, into, room);
        if (got < 0) {
            if (errno == EINTR) continue;
            throw Error("cannot read " + name + ": " + std::strerror(errno));
        }
        if (got == 0) break;
        if (into == &probe) {
            if (text.size() >= max_bytes) throw Error(std::string(name).append(" is ").append(limit));
            text.push_back(probe);
            ++used;
            continue;
        }
        used += static_cast<std::size_t>(got);
    }
    text.resize(used);
    return text;
}

bool stripByteOrderMark(std::string_view& text) {
    constexpr std::string_view bom = "\xEF\xBB\xBF";
    if (text.substr(0, bom.size()) != bom) return false;
    text.remove_prefix(bom.size());
    return true;
}

bool isDecimal(std::string_view text) {
    if (text.empty()) return false;
    std::string_view body = text;
    if (body.front() == '+' || body.front() == '-') body.remove_prefix(1);
    // digits, at most one '.', then optionally e/E, a sign and digits
    std::size_t k = 0, digits = 0;
    while (k < body.size() && body[k] >= '0' && body[k] <= '9') ++k, ++digits;
    if (k < body.size() && body[k] == '.') {
        ++k;
        while (k < body.size() && body[k] >= '0' && body[k] <= '9') ++k, ++digits;
    }
    if (digits == 0) return false;
    if (k < body.size() && (body[k] == 'e' || body[k] == 'E')) {
        ++k;
        if (k < body.size() && (body[k] == '+' || body[k] == '-')) ++k;
        const std::size_t exponent_start = k;
        while (k < body.size() && body[k] >= '0' && body[k] <= '9') ++k;
        if (k == exponent_start) return false;
    }
    return k == body.size();
}

std::optional<double> parseDecimal(std::string_view text) {
    if (!isDecimal(text)) return std::nullopt;
    std::string_view body = text;
    if (body.front() == '+' || body.front() == '-') body.remove_prefix(1);
    // from_chars takes no sign; isDecimal admits only what chars_format::general reads.
    const bool negative = text.front() == '-';
    double value = 0.0;
    const auto result = std::from_chars(body.data(), body.data() + body.size(), value, std::chars_format::general);
    if (result.ptr != body.data() + body.size()) return std::nullopt;
    // result_out_of_range: beyond the largest double, or below the smallest subnormal
    if (result.ec != std::errc{}) return std::nullopt;
    if (!std::isfinite(value)) return std::nullopt;
    return negative ? -value : value;
}

std::string numberProblem(std::string_view text) {
    if (isDecimal(text)) return "is beyond the range of a double (magnitude 4.9e-324 to 1.8e308, or 0)";
    return "is not a finite decimal number (e.g. 0.25 or -2.5e-3; no hex, inf or nan)";
}

}  // namespace nocdyn::io::detail
