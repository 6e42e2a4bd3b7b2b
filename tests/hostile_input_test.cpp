// Hostile but finite input to the library's entry points: an ill-conditioned identification
// and an absurd thread count each end in a clear nocdyn::Error or a correct answer, never a
// crash.
#include <gtest/gtest.h>

#include <string>

#include "identification_support.hpp"
#include "nocdyn/batch.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/examples.hpp"

namespace nocdyn::test {
namespace {

const Payload kPayload{0.5, 8e-4, Vector2(0.012, -0.007)};

/// The paper's robot carrying kPayload along x(t) = 2 mm sin(2 pi 5 t) with theta = 1e-3 x: a
/// coupled motion whose rotation is too small to separate the payload's inertia from its mass.
Motion coupledMotion(const Model& robot, int samples) {
    PoseTrajectory trajectory;
    trajectory.x.harmonics = {{0.002, 5.0, 0.0}};
    trajectory.theta.harmonics = {{1e-3 * 0.002, 5.0, 0.0}};
    return exactMotion(robot, trajectory, samples, 0.002);
}

TEST(HostileIdentification, IllConditionedRegressorIsAClearErrorNotACrash) {
    const Model nominal(io::exampleRobot("paper-3prr-general"));
    const Model loaded(withPayload(io::exampleRobot("paper-3prr-general"), kPayload));
    for (const int samples : {12, 200}) {
        const Motion motion = coupledMotion(loaded, samples);
        ASSERT_EQ(static_cast<int>(motion.t.size()), samples);
        try {
            const PayloadResult r = identifyPayload(nominal, motion);
            ADD_FAILURE() << samples << " samples: a payload was reported from a motion that cannot separate it (mass "
                          << r.mass << ", inertia " << r.inertia << ")";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("not identifiable"), std::string::npos) << what;
        }
    }
}

TEST(HostileBatch, AHundredThousandThreadsAreCappedAndGiveTheOneThreadAnswer) {
    const Model robot(io::exampleRobot("3-rrr"));
    constexpr Eigen::Index n = 37;
    Eigen::ArrayXXd p = Eigen::ArrayXXd::Zero(n, 3), dp = p, ddp = p;
    for (Eigen::Index k = 0; k < n; ++k) {
        p(k, 1) = 1e-3 * static_cast<double>(k % 5);
        dp(k, 0) = 0.1;
        ddp(k, 2) = 1.0;
    }
    p.col(0) += robot.home(0);
    p.col(1) += robot.home(1);
    p.col(2) += robot.home(2);
    const int m = robot.actuators;
    Eigen::ArrayXXd u(n, m), du(n, m), ddu(n, m), tau(n, m), u1(n, m), du1(n, m), ddu1(n, m), tau1(n, m);
    const BatchResult many = inverseDynamicsBatch(robot, p, dp, ddp, u, du, ddu, tau, 100000);
    const BatchResult one = inverseDynamicsBatch(robot, p, dp, ddp, u1, du1, ddu1, tau1, 1);
    EXPECT_EQ(many.failed, 0);
    EXPECT_EQ(one.failed, 0);
    EXPECT_TRUE((tau == tau1).all()) << "the split batch differs from the one-thread batch";
    EXPECT_TRUE((u == u1).all());
}

}  // namespace
}  // namespace nocdyn::test
