// Progress of a job made of named steps or counted items, for a person at a terminal: one line
// of standard error, rewritten in place and cleared at the end. Nothing is written when
// standard error is not a terminal (a log, a pipe, a test) or when the user asked for quiet.
#pragma once

#include <string>

namespace nocdyn::cli {

class Steps {
public:
    /// `job` heads the line ("nocdyn reproduce"); `total` steps are expected.
    Steps(std::string job, int total, bool quiet = false);
    ~Steps();
    Steps(const Steps&) = delete;
    Steps& operator=(const Steps&) = delete;

    /// Starts the next step: "nocdyn reproduce: 3 of 9, closed-loop control (12 s so far)".
    void next(const std::string& what);
    /// Reports `done` of `total` items of the current step ("frequency 12 of 123"), at most
    /// five times a second (cheap to call per item).
    void count(int done, int total, const char* item);
    /// Clears the line (also when dropped).
    void finish();

    [[nodiscard]] bool shown() const { return terminal_; }

private:
    void show(const std::string& text);

    std::string job_, step_;
    int total_ = 0, index_ = 0;
    bool terminal_ = false, written_ = false;
    double start_ = 0.0, last_ = 0.0;
};

}  // namespace nocdyn::cli
