#include "progress.hpp"

#include "common.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/output.hpp"
#include "nocdyn/text.hpp"

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <utility>

namespace nocdyn::cli {

namespace {
double secondsNow() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool quiet_run = false;

void wrote(const std::string& path) {
    if (!quiet_run) std::fprintf(stderr, "nocdyn: wrote %s\n", io::terminalText(path).c_str());
}
}  // namespace

void setQuiet(bool quiet) { quiet_run = quiet; }

bool quiet() { return quiet_run; }

void announceWrittenFiles() { io::setCommitObserver(&wrote); }

TerminalObserver::TerminalObserver(std::string job)
    : job_(std::move(job)), terminal_(!quiet_run && ::isatty(STDERR_FILENO) == 1) {
    start_ = secondsNow();
    last_ = start_;
}

TerminalObserver::~TerminalObserver() { finish(); }

void TerminalObserver::show(const std::string& text) {
    if (terminal_) {
        // \r and "erase to the end of the line": the new text replaces the old in place
        std::fprintf(stderr, "\r\033[K%s", text.c_str());
        shown_ = true;
    } else {
        std::fprintf(stderr, "%s\n", text.c_str());
    }
    std::fflush(stderr);
}

void TerminalObserver::progress(double done, double total, std::string_view unit) {
    if (quiet_run) return;
    const double now = secondsNow();
    if (now - last_ < (terminal_ ? 1.0 : kProgressLogSeconds)) return;
    last_ = now;
    const std::string head = job_ + ": " + (step_.empty() ? std::string() : step_ + ", ");
    const std::string name(unit);
    std::string text;
    if (total > 0.0) {
        const double fraction = std::clamp(done / total, 0.0, 1.0);
        const double left = fraction > 0.0 ? (now - start_) * (1.0 - fraction) / fraction : 0.0;
        text = text::format("%s%.4g of %.4g %s (%.0f %%), %.0f s so far, about %.0f s left", name == "s" ? "t = " : "",
                            done, total, name.c_str(), 100.0 * fraction, now - start_, left);
    } else {
        text = text::format("%s%.4g %s (%.0f s so far)", name == "s" ? "t = " : "", done, name.c_str(), now - start_);
    }
    show(head + text);
}

void TerminalObserver::step(std::string_view what, int index, int total) {
    step_ = std::string(what);
    if (quiet_run) return;
    const double now = secondsNow();
    if (!terminal_ && now - last_ < kProgressLogSeconds) return;
    last_ = now;
    std::string text;
    text = text::format("%d of %d, ", index, total);
    std::string tail;
    tail = text::format(" (%.0f s so far)", now - start_);
    show(job_ + ": " + (total > 1 ? std::string(text) : std::string()) + step_ + tail);
}

void TerminalObserver::warning(std::string_view text) {
    finish();
    std::fprintf(stderr, "nocdyn: warning: %s\n", io::terminalText(std::string(text)).c_str());
    std::fflush(stderr);
}

void TerminalObserver::finish() {
    if (!shown_) return;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    shown_ = false;
}

}  // namespace nocdyn::cli
