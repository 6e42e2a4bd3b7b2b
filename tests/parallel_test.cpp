// The thread helper (parallel.hpp): the split covers [0, n) in contiguous chunks of a multiple
// of the grain, each worker runs once, and a worker's exception reaches the caller.
#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "nocdyn/parallel.hpp"

namespace nocdyn {
namespace {

TEST(Parallel, OneRequestedThreadOrOneGrainIsOneWorkerOverEverything) {
    for (const Eigen::Index n : {0, 1, 8, 1000}) {
        const ParallelSplit split = splitRange(n, 1, 8);
        EXPECT_EQ(split.workers, 1u);
        EXPECT_EQ(split.begin(0), 0);
        EXPECT_EQ(split.end(0), n);
    }
    EXPECT_EQ(splitRange(8, 0, 8).workers, 1u);
    EXPECT_EQ(splitRange(5, 4, 8).workers, 1u);
}

TEST(Parallel, SplitIsContiguousInMultiplesOfTheGrainAndCappedByHardwareAndGrains) {
    const unsigned hardware = hardwareThreads();
    for (const Eigen::Index n : {9, 17, 100, 1001, 100000}) {
        for (const unsigned requested : {0u, 2u, 3u, 64u}) {
            const ParallelSplit split = splitRange(n, requested, 8);
            const auto grains = static_cast<unsigned>((n + 7) / 8);
            const unsigned cap = std::min(hardware, grains);
            EXPECT_EQ(split.workers, requested == 0 ? cap : std::min(requested, cap)) << n << " " << requested;
            if (split.workers == 1) continue;
            EXPECT_EQ(split.per % 8, 0) << n;
            EXPECT_EQ(split.begin(0), 0);
            for (unsigned w = 1; w < split.workers; ++w) EXPECT_EQ(split.begin(w), split.end(w - 1));
            EXPECT_EQ(split.end(split.workers - 1), n) << n << " " << requested;
        }
    }
}

TEST(Parallel, EveryItemIsVisitedOnceByItsChunksWorker) {
    const Eigen::Index n = 1003;
    ParallelSplit split{n, 3, 336};  // a split of three workers whatever the hardware
    std::vector<int> visits(static_cast<std::size_t>(n), 0);
    std::vector<unsigned> owner(static_cast<std::size_t>(n), 99);
    parallelFor("test", split, [&](unsigned w, Eigen::Index begin, Eigen::Index end) {
        for (Eigen::Index k = begin; k < end; ++k) {
            ++visits[static_cast<std::size_t>(k)];
            owner[static_cast<std::size_t>(k)] = w;
        }
    });
    for (Eigen::Index k = 0; k < n; ++k) {
        EXPECT_EQ(visits[static_cast<std::size_t>(k)], 1) << k;
        EXPECT_EQ(owner[static_cast<std::size_t>(k)], static_cast<unsigned>(k / 336)) << k;
    }
}

TEST(Parallel, TheLowestThrowingWorkersExceptionReachesTheCallerAfterAllJoined) {
    std::atomic<int> finished{0};
    try {
        runWorkers("test", 4, [&](unsigned w) {
            if (w == 1 || w == 3) throw std::runtime_error("worker " + std::to_string(w));
            ++finished;
        });
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "worker 1");
    }
    EXPECT_EQ(finished.load(), 2);
}

}  // namespace
}  // namespace nocdyn
