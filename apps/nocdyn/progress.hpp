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
