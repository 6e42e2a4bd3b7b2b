// The thread helper (parallel.hpp).
#include "nocdyn/parallel.hpp"

#include <algorithm>
#include <exception>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "nocdyn/error.hpp"

namespace nocdyn {

unsigned hardwareThreads() { return std::max(1u, std::thread::hardware_concurrency()); }

ParallelSplit splitRange(Eigen::Index n, unsigned requested, Eigen::Index grain) {
    grain = std::max<Eigen::Index>(grain, 1);
    ParallelSplit split{n, 1, n};
    // one worker needs no count of the hardware's threads: asking costs microseconds (a system
    // call), more than a short batch such as a chunk of an envelope's period
    if (requested == 1 || n <= grain) return split;
    const auto chunks = static_cast<unsigned>(std::min<Eigen::Index>((n + grain - 1) / grain, hardwareThreads()));
    const unsigned workers = requested == 0 ? chunks : std::min(requested, chunks);
    if (workers <= 1) return split;
    split.workers = workers;
    split.per = ((n + workers - 1) / workers + grain - 1) / grain * grain;
    return split;
}

void runWorkers(const char* what, unsigned workers, const std::function<void(unsigned)>& work) {
    workers = std::max(workers, 1u);
    std::vector<std::exception_ptr> failures(workers);
    const auto guarded = [&](unsigned w) {
        try {
            work(w);
        } catch (...) {
            failures[w] = std::current_exception();
        }
    };
    std::vector<std::thread> threads;
    threads.reserve(workers - 1);
    try {
        for (unsigned w = 1; w < workers; ++w) threads.emplace_back(guarded, w);
    } catch (const std::system_error& e) {
        // a thread that cannot start: join those that did, and say so
        for (std::thread& t : threads) t.join();
        throw Error(std::string(what) + ": cannot start a worker thread: " + e.what());
    }
    guarded(0);
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& failure : failures)
        if (failure) std::rethrow_exception(failure);
}

void parallelFor(const char* what, const ParallelSplit& split,
                 const std::function<void(unsigned, Eigen::Index, Eigen::Index)>& chunk) {
    runWorkers(what, split.workers, [&](unsigned w) { chunk(w, split.begin(w), split.end(w)); });
}

}  // namespace nocdyn
