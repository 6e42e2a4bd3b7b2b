#include "progress.hpp"

#include "common.hpp"

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
}  // namespace

Steps::Steps(std::string job, int total, bool quiet)
    : job_(std::move(job)), total_(total), terminal_(!quiet && ::isatty(STDERR_FILENO) == 1) {
    start_ = last_ = secondsNow();
}

Steps::~Steps() { finish(); }

void Steps::next(const std::string& what) {
    ++index_;
    step_ = what;
    // the Python package's progress callback, when set, hears the steps instead of the terminal
    if (const auto& observer = progressObserver()) {
        observer(index_ - 1, total_);
        return;
    }
    if (!terminal_) return;
    char head[64];
    std::snprintf(head, sizeof head, ": %d of %d, ", index_, total_);
    char tail[48];
    std::snprintf(tail, sizeof tail, " (%.0f s so far)", secondsNow() - start_);
    show(job_ + (total_ > 1 ? std::string(head) : std::string(": ")) + step_ + tail);
}

void Steps::count(int done, int total, const char* item) {
    const auto& observer = progressObserver();
    if (!terminal_ && !observer) return;
    const double now = secondsNow();
    if (now - last_ < 0.2 && done < total) return;
    last_ = now;
    if (observer) {
        observer(std::max(index_ - 1, 0) + (total > 0 ? static_cast<double>(done) / total : 0.0), std::max(total_, 1));
        return;
    }
    char text[96];
    std::snprintf(text, sizeof text, "%s %d of %d", item, done, total);
    show(job_ + ": " + (step_.empty() ? std::string() : step_ + ", ") + text);
}

void Steps::show(const std::string& text) {
    // \r and "erase to the end of the line": the new text replaces the old in place
    std::fprintf(stderr, "\r\033[K%s", text.c_str());
    std::fflush(stderr);
    written_ = true;
}

void Steps::finish() {
    if (!written_) return;
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    written_ = false;
}

}  // namespace nocdyn::cli
