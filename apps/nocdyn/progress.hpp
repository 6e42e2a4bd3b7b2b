// Progress of a job made of named steps or counted items, for a person: on a terminal one line
// of standard error, rewritten in place and cleared at the end; otherwise (a log, a pipe) one
// line of its own every kProgressLogSeconds, the first only after that long, so that a long
// run is never silent and a short one writes nothing. Nothing when the user asked for quiet.
#pragma once

#include <string>
#include <string_view>

#include "app/observer.hpp"

namespace nocdyn::cli {

/// Seconds between two progress lines when standard error is not a terminal.
inline constexpr double kProgressLogSeconds = 5.0;

/// --quiet of the command running: no progress and no "wrote FILE" lines on standard error.
void setQuiet(bool quiet);
[[nodiscard]] bool quiet();

/// The command line's rule for files: every file written is named on standard error as
/// "nocdyn: wrote PATH" when written (unless quiet). Installed by runCommandLine.
void announceWrittenFiles();

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
    bool terminal_ = false, written_ = false, quiet_ = false;
    double start_ = 0.0, last_ = 0.0, logged_ = 0.0;
};

/// Progress of a run whose length is known only as it goes (a replay, its passes): "JOB: t =
/// 12.3 s (8 s so far)", on a terminal rewritten at most once a second, else a line of its own
/// every kProgressLogSeconds; nothing when quiet. at() is cheap (the clock every 1024 calls).
class Heartbeat {
public:
    explicit Heartbeat(std::string job);
    ~Heartbeat();
    Heartbeat(const Heartbeat&) = delete;
    Heartbeat& operator=(const Heartbeat&) = delete;
    void at(double t);
    void finish();

private:
    std::string job_;
    bool terminal_ = false, shown_ = false;
    unsigned calls_ = 0;
    double start_ = 0.0, last_ = 0.0;
};

/// The command line's observer of a job (app/observer.hpp): its progress on standard error as
/// Progress and Steps show it (a terminal line rewritten at most once a second, else a line of
/// its own every kProgressLogSeconds; nothing when quiet), and its warnings as "nocdyn: warning:
/// TEXT" lines. It never asks to stop: Ctrl-C ends the process.
class TerminalObserver final : public app::Observer {
public:
    /// `job` heads the lines ("nocdyn shake").
    explicit TerminalObserver(std::string job = "nocdyn");
    ~TerminalObserver() override;
    TerminalObserver(const TerminalObserver&) = delete;
    TerminalObserver& operator=(const TerminalObserver&) = delete;
    TerminalObserver(TerminalObserver&&) = delete;
    TerminalObserver& operator=(TerminalObserver&&) = delete;

    void progress(double done, double total, std::string_view unit) override;
    void step(std::string_view what, int index, int total) override;
    void warning(std::string_view text) override;
    /// Clears the progress line (also when dropped).
    void finish();

private:
    void show(const std::string& text);

    std::string job_, step_;
    bool terminal_ = false, shown_ = false;
    double start_ = 0.0, last_ = 0.0;
};

}  // namespace nocdyn::cli
