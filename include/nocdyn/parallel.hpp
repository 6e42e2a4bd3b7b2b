// One thread helper: [0, n) split into contiguous chunks over std::threads, or a fixed number
// of workers pulling work themselves. The calling thread is worker 0; every thread is joined
// before the call returns, and an exception thrown by a worker reaches the caller.
#pragma once

#include <algorithm>
#include <functional>

#include <Eigen/Core>

namespace nocdyn {

/// The hardware's thread count, at least 1 (a system call: microseconds).
[[nodiscard]] unsigned hardwareThreads();

/// A split of [0, n) into `workers` contiguous chunks of `per` items (the last one shorter or
/// empty); worker w holds [begin(w), end(w)).
struct ParallelSplit {
    Eigen::Index n = 0;
    unsigned workers = 1;
    Eigen::Index per = 0;
    [[nodiscard]] Eigen::Index begin(unsigned w) const { return std::min(n, static_cast<Eigen::Index>(w) * per); }
    [[nodiscard]] Eigen::Index end(unsigned w) const { return std::min(n, (static_cast<Eigen::Index>(w) + 1) * per); }
};

/// The split of n items over min(requested, hardware threads, ceil(n / grain)) workers
/// (requested 0: as many as the hardware has), in chunks of a multiple of `grain` items (so that
/// no two threads write the same cache line when an item fills `grain` doubles' share of one).
/// requested 1 or n <= grain: one worker, without asking the hardware.
[[nodiscard]] ParallelSplit splitRange(Eigen::Index n, unsigned requested, Eigen::Index grain);

/// Runs work(w) for w = 0 .. workers - 1: w = 0 on the calling thread, the others on their own
/// std::thread; joins them all, then rethrows the exception of the lowest worker that threw.
/// A thread that cannot start: those started are joined and nocdyn::Error says
/// "<what>: cannot start a worker thread".
void runWorkers(const char* what, unsigned workers, const std::function<void(unsigned)>& work);

/// Runs chunk(w, split.begin(w), split.end(w)) for every worker of `split`, as runWorkers.
void parallelFor(const char* what, const ParallelSplit& split,
                 const std::function<void(unsigned, Eigen::Index, Eigen::Index)>& chunk);

}  // namespace nocdyn
