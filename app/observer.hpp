// How a running job talks to whoever started it (the command line's terminal, a Python
// callback): progress, warnings and a request to stop. Each run is given its own observer; the
// application layer keeps no process-wide state.
#pragma once

#include <string>
#include <string_view>

#include "nocdyn/error.hpp"

namespace nocdyn::app {

/// The job was stopped by its observer (Ctrl-C in Python, a cancelled call).
class Cancelled : public Error {
public:
    Cancelled() : Error("stopped before the end") {}
};

/// Receives a job's progress and warnings; asked whether to stop. A job calls it only from the
/// thread that called it (worker threads report through that thread), so an implementation
/// needs no lock. Every method may throw to stop the job; the exception reaches the caller.
class Observer {
public:
    Observer() = default;
    Observer(const Observer&) = default;
    Observer& operator=(const Observer&) = default;
    Observer(Observer&&) = default;
    Observer& operator=(Observer&&) = default;
    virtual ~Observer() = default;

    /// Reached `done` of `total` in `unit` ("s" of motion, "designs", "frequencies"); total <= 0
    /// when the length is not known in advance. Called at most every few milliseconds.
    virtual void progress(double done, double total, std::string_view unit);
    /// Starts step `index` (1-based) of `total` of a job made of named steps.
    virtual void step(std::string_view what, int index, int total);
    /// One line the user must read that does not stop the job (no "warning:" prefix).
    virtual void warning(std::string_view text);
    /// Polled between items and with progress: true stops the job (it throws Cancelled).
    [[nodiscard]] virtual bool stopRequested();
};

/// An observer that shows nothing and never stops (tests, scripts).
[[nodiscard]] Observer& silent();

/// Progress of a per-sample loop at a price that does not show: every 1024th call reaches the
/// observer (progress, then stopRequested: a stop throws Cancelled).
class Meter {
public:
    Meter(Observer& observer, double total, std::string_view unit);
    void operator()(double done) {
        if ((++calls_ & 1023U) == 0) report(done);
    }
    /// Reports `done` now (the end of a job, a step between items).
    void report(double done);

private:
    Observer* observer_;
    double total_;
    std::string unit_;
    unsigned calls_ = 0;
};

/// Throws Cancelled when the observer asks to stop (between the items of a job).
void stopIfRequested(Observer& observer);

}  // namespace nocdyn::app
