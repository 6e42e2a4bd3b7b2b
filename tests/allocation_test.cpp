// The per-sample path allocates nothing: global operator new is replaced by a counting one
// in this test binary, and the whole inverse dynamics runs over a trajectory.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "nocdyn/batch.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

TEST(RealTime, PerSamplePathWithItsChecksAllocatesNothing) {
    for (const std::string& robot : io::exampleRobotNames()) {
        const Model model(io::exampleRobot(robot));
        Data data(model);
        const PoseTrajectory trajectory = paperTrajectory1();
        Pose p, dp, ddp;
        const long before = allocationCount();
        double checksum = 0.0;
        int solved = 0;
        for (int k = 0; k < 2000; ++k) {
            trajectory.evaluate(k * 1e-4, p, dp, ddp);
            const Status status = inverseDynamics(model, data, p, dp, ddp);
            solved += status.ok();
            checksum += status.ok() ? data.tau.sum() + data.I.trace() + data.C.sum() : 1e9;
            checksum += checkJointLimits(model, data).ok() + checkEffort(model, data).ok();
            checksum += kineticEnergy(model, data) + potentialEnergy(model, data) + frictionPower(model, data);
        }
        // Failure statuses take the same path: no allocation either.
        checksum += inverseDisplacement(model, data, Pose(0.0, 0.0, -0.3)).ok();
        checksum += inverseDisplacement(model, data, Pose(std::nan(""), 0.0, 0.0)).ok();
        const long after = allocationCount();
        EXPECT_EQ(after - before, 0) << robot;
        EXPECT_EQ(solved, 2000) << robot;
        EXPECT_TRUE(std::isfinite(checksum)) << robot;
    }
}

TEST(RealTime, TheModelAllocatesNothingPerSample) {
    for (const std::string robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        const Model model(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
        Data data(model);
        const PoseTrajectory trajectory = paperTrajectory1();
        const Eigen::Index N = 500;
        Eigen::ArrayX3d P(N, 3), dP(N, 3), ddP(N, 3);
        Eigen::ArrayXXd u(N, model.actuators), du(N, model.actuators), ddu(N, model.actuators), tau(N, model.actuators);
        Pose p, dp, ddp;
        for (Eigen::Index k = 0; k < N; ++k) {
            trajectory.evaluate(static_cast<double>(k) * 2e-4, p, dp, ddp);
            P.row(k) = p.transpose();
            dP.row(k) = dp.transpose();
            ddP.row(k) = ddp.transpose();
        }
        P(N / 2, 1) = std::nan("");  // a failing sample takes the full path, without allocating either
        const long before = allocationCount();
        double checksum = 0.0;
        for (Eigen::Index k = 0; k < N; ++k) {
            const Status lean =
                inverseDynamicsFast(model, data, P.row(k).transpose(), dP.row(k).transpose(), ddP.row(k).transpose());
            checksum += lean.ok() ? data.tau.sum() : 1.0;
            const Status full =
                inverseDynamics(model, data, P.row(k).transpose(), dP.row(k).transpose(), ddP.row(k).transpose());
            checksum += full.ok() ? data.tau.sum() + data.I.trace() : 1.0;
        }
        const BatchResult batch = inverseDynamicsBatch(model, P, dP, ddP, u, du, ddu, tau, 1);
        checksum += static_cast<double>(batch.failed);
        const long after = allocationCount();
        EXPECT_EQ(after - before, 0) << robot;
        EXPECT_EQ(batch.failed, 1) << robot;
        EXPECT_TRUE(std::isfinite(checksum)) << robot;
    }
}

TEST(RealTime, EnvelopeAllocatesPerSearchNotPerSample) {
    // A search allocates its buffers once: as many allocations with 16 times the samples
    for (const std::string robot : {"paper-3prr-general", "3-rrr"}) {
        const Model model(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
        const auto allocations = [&](int samples) {
            EnvelopeOptions options;
            options.samples_per_period = samples;
            const long before = allocationCount();
            const EnvelopePoint point = maximumAmplitude(model, EnvelopeAxis::x, 50.0, options);
            const long count = allocationCount() - before;
            EXPECT_GT(point.amplitude, 0.0) << robot;
            return count;
        };
        EXPECT_EQ(allocations(64), allocations(1024)) << robot;
    }
}

TEST(RealTime, JointReactionsAllocateNothingPerSampleNorInTheBatch) {
    for (const std::string robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        const Model model(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
        Data data(model);
        Reactions reactions;
        const PoseTrajectory trajectory = paperTrajectory1();
        const Eigen::Index N = 300;
        Eigen::ArrayX3d P(N, 3), dP(N, 3), ddP(N, 3);
        Eigen::ArrayXXd out(N, 9 * model.limbs);
        Pose p, dp, ddp;
        for (Eigen::Index k = 0; k < N; ++k) {
            trajectory.evaluate(static_cast<double>(k) * 2e-4, p, dp, ddp);
            P.row(k) = p.transpose();
            dP.row(k) = dp.transpose();
            ddP.row(k) = ddp.transpose();
        }
        P(N / 2, 1) = 1e3;  // far out of reach: the stages' path gives the Status, without allocating either
        const long before = allocationCount();
        double checksum = 0.0, difference = 0.0;
        int failed = 0;
        for (Eigen::Index k = 0; k < N; ++k) {
            const Status status = inverseDynamicsWithReactions(model, data, P.row(k).transpose(), dP.row(k).transpose(),
                                                               ddP.row(k).transpose(), reactions);
            failed += !status.ok();
            if (!status) continue;
            const Vector3 lean = reactions.joint[0][1];
            jointReactions(model, data, reactions);  // at the state the call left: the same
            difference = std::max(difference, (reactions.joint[0][1] - lean).cwiseAbs().maxCoeff());
            checksum += lean.sum();
        }
        const BatchResult batch = reactionsBatch(model, P, dP, ddP, out, 1);
        const long after = allocationCount();
        EXPECT_EQ(after - before, 0) << robot;
        EXPECT_EQ(failed, 1) << robot;
        EXPECT_LT(difference, 1e-9) << robot << ": jointReactions at the state left [N]";
        EXPECT_EQ(batch.failed, 1) << robot;
        EXPECT_EQ(batch.first_failure, N / 2) << robot;
        EXPECT_TRUE(std::isnan(out(N / 2, 0))) << robot;
        EXPECT_TRUE(std::isfinite(checksum + out.row(0).sum())) << robot;
    }
}

TEST(RealTime, CountingAllocatorSeesAllocations) {
    // Proves the counter works, so that the test above can fail.
    const long before = allocationCount();
    // A direct call of the allocation function cannot be elided (a new-expression can).
    void* p = ::operator new(64);
    ::operator delete(p);
    const long after_new = allocationCount();
    EXPECT_GE(after_new - before, 1);
    // Eigen allocates dynamic-size matrices with malloc, not operator new.
    Eigen::MatrixXd dynamic(7, 7);
    dynamic.setZero();
    EXPECT_EQ(dynamic.sum(), 0.0);
    if (kCountsMalloc) {
        EXPECT_GE(allocationCount() - after_new, 1);
    }
}

}  // namespace
}  // namespace nocdyn::test
