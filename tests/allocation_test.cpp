// The per-sample path allocates nothing: global operator new is replaced by a counting one
// in this test binary, and the whole inverse dynamics runs over a trajectory.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"
#include "nocdyn/trajectory.hpp"

namespace {
std::atomic<long> allocations{0};
}

void* operator new(std::size_t size) {
    ++allocations;
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace nocdyn::test {
namespace {

TEST(RealTime, PerSamplePathAllocatesNothing) {
    const prr3::Model model;
    prr3::Data data;
    const PoseTrajectory trajectory = paperTrajectory1();
    Pose p, dp, ddp;
    const long before = allocations.load();
    double checksum = 0.0;
    for (int k = 0; k < 2000; ++k) {
        trajectory.evaluate(k * 1e-4, p, dp, ddp);
        const Status status = prr3::inverseDynamics(model, data, p, dp, ddp);
        checksum += status.ok() ? data.tau.sum() + data.I.trace() + data.C.sum() : 1e9;
        checksum += prr3::checkStroke(model, data).ok() + prr3::checkForce(model, data).ok();
        checksum += prr3::kineticEnergy(model, data);
    }
    // Failure statuses take the same path: no allocation either.
    checksum += prr3::inverseDisplacement(model, data, Pose(0.0, 0.0, -0.2)).ok();
    const long after = allocations.load();
    EXPECT_EQ(after - before, 0);
    EXPECT_TRUE(std::isfinite(checksum));
}

TEST(RealTime, CountingAllocatorSeesAllocations) {
    // Proves the counter works, so that the test above can fail.
    const long before = allocations.load();
    auto* p = new std::vector<double>(100);
    delete p;
    EXPECT_GE(allocations.load() - before, 2);
}

}  // namespace
}  // namespace nocdyn::test
