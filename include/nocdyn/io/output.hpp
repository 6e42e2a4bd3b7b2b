// Output files written safely: all or nothing, never through a planted link, every write checked.
//
// A regular file (or a name that does not exist yet) is written to a new temporary file in the
// same directory, created exclusively under a random name (O_CREAT | O_EXCL | O_NOFOLLOW, so a
// link planted at that name is refused, never followed), then flushed to disk and renamed over
// the target: readers see the old file or the complete new one, two writers of the same target
// each leave a complete file (the last rename wins), and a failure removes the temporary file.
// A target that is a symbolic link to a regular file (or a dangling one) is replaced by the
// new file: the link itself is renamed over, the file it pointed to is left untouched.
// A target that exists and is not a regular file (a device such as /dev/null, a FIFO, or a
// link to one, such as /dev/stdout) is opened and written straight through.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace nocdyn::io {

/// A buffered output that is either a safely replaced file, a special file written straight
/// through, or the process's standard output. Errors throw nocdyn::Error naming the path
/// and the system's reason. Dropping an OutputFile without commit() removes its temporary
/// file, so an exception on the way leaves the target as it was.
class OutputFile {
public:
    /// Prepares to write `path` (see the file comment). Throws when it cannot be created.
    explicit OutputFile(std::string path);
    /// Standard output (file descriptor 1); written straight through, never closed.
    [[nodiscard]] static OutputFile standardOutput();

    OutputFile(OutputFile&& other) noexcept;
    OutputFile& operator=(OutputFile&&) = delete;
    OutputFile(const OutputFile&) = delete;
    OutputFile& operator=(const OutputFile&) = delete;
    ~OutputFile();

    /// Appends bytes (buffered; a full buffer is written out and checked).
    void write(std::string_view bytes);
    /// Room for at least `n` more bytes in the buffer, for formatting in place.
    [[nodiscard]] char* reserve(std::size_t n);
    /// Marks `n` bytes written at reserve()'s pointer as part of the output.
    void commitReserved(std::size_t n) { used_ += n; }
    /// Writes out the buffer and returns the file descriptor, for a child process (e.g.
    /// gnuplot) to write the rest directly.
    [[nodiscard]] int descriptor();
    /// Writes out the buffer, syncs the file to disk and renames it over the target (or, for
    /// a special file or standard output, just writes out). Throws on any failure.
    void commit();

    /// The target path ("standard output" for standard output), for messages.
    [[nodiscard]] const std::string& path() const { return path_; }

private:
    OutputFile() = default;
    void flushBuffer();
    void discard() noexcept;

    std::string path_;       ///< the target
    std::string temporary_;  ///< the temporary file renamed over the target; empty when written through
    int fd_ = -1;
    bool owns_fd_ = false;  ///< false for standard output
    bool committed_ = false;
    std::string buffer_;
    std::size_t used_ = 0;
    int pending_ = -1;  ///< slot of the temporary in the signal handler's list, -1 when not listed
};

/// Installs handlers of SIGINT, SIGTERM and SIGHUP that remove the temporary files of every
/// OutputFile not yet committed (so that an interrupted run leaves no hidden `.NAME.HEX.tmp`
/// behind; the target is only ever created by the rename of a complete file), then end the
/// process by the same signal. For programs (the command line), not for a library's host.
void removeTemporariesOnSignals();

/// Called with the path of every file an OutputFile has written (a regular file, after its
/// rename; not standard output or a device): the command line names each file it writes on
/// standard error through it. nullptr (the default, for a library's host): nothing.
using CommitObserver = void (*)(const std::string& path);
void setCommitObserver(CommitObserver observer);

/// Creates `path` as a new file, exclusively (O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode
/// 0666 less the umask), and returns its descriptor. Throws nocdyn::Error when anything, even
/// a dangling symbolic link, already exists under that name.
[[nodiscard]] int createNewFile(const std::string& path);

}  // namespace nocdyn::io
