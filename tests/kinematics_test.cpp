// Inverse displacement and velocity kinematics (Appendix A, eqs. 3-8) checked by
// geometry, by the paper's literal formulas and by finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "nocdyn/prr3/dynamics.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

constexpr int kPoses = 1000;
constexpr double pi = std::numbers::pi;

TEST(InverseDisplacement, ReferencePostureHasZeroDisplacementsAndSymmetricLimbs) {
    const prr3::Model model;
    prr3::Data data;
    ASSERT_TRUE(prr3::inverseDisplacement(model, data, Pose::Zero()).ok());
    const double d_ref = 0.5 * (model.R - model.r);
    for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(data.u(j), 0.0, 1e-16) << "limb " << j + 1;
        EXPECT_NEAR(data.d_M(j), d_ref, 1e-15) << "limb " << j + 1;
        EXPECT_NEAR(data.phi_A(j), std::asin(d_ref / model.l), 1e-15) << "limb " << j + 1;
        EXPECT_NEAR(data.phi_M(j), pi - data.phi_A(j), 1e-15) << "limb " << j + 1;
    }
    // Fig. 2: M_1 at the lower right vertex of the platform, C at O.
    EXPECT_NEAR(data.Mj[0].x(), 0.5 * model.parameters.platform_side, 1e-15);
    EXPECT_NEAR(data.Mj[0].y(), -0.5 * model.r, 1e-15);
}

TEST(InverseDisplacement, ClosesEveryLoopAcrossTheWorkspace) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data;
    for (int k = 0; k < kPoses; ++k) {
        const Pose p = sampler.next();
        ASSERT_TRUE(prr3::inverseDisplacement(model, data, p).ok());
        const Vector2 C = p.tail<2>();
        for (int j = 0; j < 3; ++j) {
            SCOPED_TRACE(describePose(p) + ", limb " + std::to_string(j + 1));
            EXPECT_NEAR((data.Mj[j] - data.A[j]).norm(), model.l, 1e-15);     // |A_j M_j| = l
            EXPECT_NEAR(model.n[j].dot(data.A[j] - model.B[j]), 0.0, 1e-15);  // A_j on L_j
            EXPECT_NEAR((data.Mj[j] - C).norm(), model.r, 1e-15);             // M_j on the MP
            EXPECT_NEAR(model.e[j].dot(data.A[j] - model.B[j]) - model.s_ref[j], data.u(j), 1e-15);
            EXPECT_GT(data.phi_A(j), 0.0);
            EXPECT_LT(data.phi_A(j), pi / 2);
            // eq. 41: p_Mj = r [cos, sin](phi_Aj + phi_Mj - pi/6 + phi_j)
            const double angle = data.phi_A(j) + data.phi_M(j) - pi / 6 + model.phi[j];
            EXPECT_NEAR(data.p_M[j].x(), model.r * std::cos(angle), 1e-15);
            EXPECT_NEAR(data.p_M[j].y(), model.r * std::sin(angle), 1e-15);
        }
    }
}

TEST(VelocityKinematics, ForwardJacobianMatchesEquation7) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data;
    for (int k = 0; k < kPoses; ++k) {
        const Pose p = sampler.next();
        ASSERT_TRUE(prr3::inverseDisplacement(model, data, p).ok());
        ASSERT_TRUE(prr3::velocityFromPlatformTwist(model, data, Twist::Zero()).ok());
        for (int j = 0; j < 3; ++j) {
            SCOPED_TRACE(describePose(p) + ", limb " + std::to_string(j + 1));
            EXPECT_NEAR(data.H(j, 0), model.r * std::sin(data.phi_M(j) - pi / 6), 1e-15);
            EXPECT_NEAR(data.H(j, 1), std::cos(data.phi_A(j) + model.phi[j]), 1e-15);
            EXPECT_NEAR(data.H(j, 2), std::sin(data.phi_A(j) + model.phi[j]), 1e-15);
            EXPECT_NEAR(data.D(j), std::cos(data.phi_A(j)), 1e-15);  // eq. 6
        }
    }
}

TEST(VelocityKinematics, ActuatorRatesMatchFiniteDifferencesOfInverseDisplacement) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data, plus, minus;
    constexpr double h = 1e-7;
    for (int k = 0; k < kPoses; ++k) {
        const Pose p = sampler.next();
        const Twist t = sampler.twist();
        ASSERT_TRUE(prr3::inverseDisplacement(model, data, p).ok());
        ASSERT_TRUE(prr3::velocityFromPlatformTwist(model, data, t).ok());
        ASSERT_TRUE(prr3::inverseDisplacement(model, plus, p + h * t).ok());
        ASSERT_TRUE(prr3::inverseDisplacement(model, minus, p - h * t).ok());
        const Vector3 du_fd = (plus.u - minus.u) / (2 * h);
        const Vector3 phi_A_fd = (plus.phi_A - minus.phi_A) / (2 * h);
        for (int j = 0; j < 3; ++j) {
            SCOPED_TRACE(describePose(p) + ", limb " + std::to_string(j + 1));
            EXPECT_NEAR(data.du(j), du_fd(j), 1e-7 * (1 + std::abs(du_fd(j))));
            EXPECT_NEAR(data.gamma_dot[j](0), data.du(j), 1e-13);  // eq. 4b: first limb rate is du_j
            EXPECT_NEAR(data.gamma_dot[j](1), phi_A_fd(j), 1e-7 * (1 + std::abs(phi_A_fd(j))));
            // eq. 3: t_M = J_j gamma_dot_j
            EXPECT_LT((data.J[j] * data.gamma_dot[j] - t).norm(), 1e-12 * (1 + t.norm()));
        }
    }
}

TEST(VelocityKinematics, PlatformTwistFromActuatorRatesInvertsEquation5) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data;
    for (int k = 0; k < kPoses; ++k) {
        const Pose p = sampler.next();
        const Twist t = sampler.twist();
        ASSERT_TRUE(prr3::inverseDisplacement(model, data, p).ok());
        ASSERT_TRUE(prr3::velocityFromPlatformTwist(model, data, t).ok());
        const prr3::JointVector du = data.du;
        ASSERT_TRUE(prr3::velocityFromActuatorRates(model, data, du).ok());
        EXPECT_LT((data.t_M - t).norm(), 1e-12 * (1 + t.norm())) << describePose(p);
    }
}

TEST(Messages, NonFiniteValuesAreNotCalledMeasurements) {
    // A NaN pose is not "beyond the link length by nan mm", a NaN force not "peak force exceeded".
    const prr3::Model model;
    prr3::Data data;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Status pose = prr3::inverseDisplacement(model, data, Pose(nan, 0.0, 0.0));
    ASSERT_FALSE(pose.ok());
    const std::string pose_message = describe(pose, model.parameters);
    EXPECT_EQ(pose_message.find("nan mm"), std::string::npos) << pose_message;
    EXPECT_EQ(pose_message.find("beyond the link length"), std::string::npos) << pose_message;
    EXPECT_NE(pose_message.find("not a number"), std::string::npos) << pose_message;

    ASSERT_TRUE(prr3::inverseDynamics(model, data, Pose::Zero(), Twist::Zero(), Twist::Zero()).ok());
    data.tau(1) = nan;
    const Status force = prr3::checkForce(model, data);
    ASSERT_EQ(force.code, StatusCode::force_exceeded);
    EXPECT_EQ(force.limb, 1);
    const std::string force_message = describe(force, model.parameters);
    EXPECT_EQ(force_message.find("peak force exceeded"), std::string::npos) << force_message;
    EXPECT_NE(force_message.find("not finite: limb 2"), std::string::npos) << force_message;
}

TEST(Workspace, PoseBeyondARailIsRejectedNamingTheLimb) {
    const prr3::Model model;
    prr3::Data data;
    // C far below: M_1 crosses the lower base side L_1.
    const Status below = prr3::inverseDisplacement(model, data, Pose(0.0, 0.0, -0.09));
    EXPECT_EQ(below.code, StatusCode::outside_workspace);
    EXPECT_EQ(below.limb, 0);
    EXPECT_LT(below.value, 0.0);
    EXPECT_NE(describe(below, model.parameters).find("limb 1"), std::string::npos);
    // C far above: M_1 is farther from L_1 than the link can reach.
    const Status above = prr3::inverseDisplacement(model, data, Pose(0.0, 0.0, 0.08));
    EXPECT_EQ(above.code, StatusCode::outside_workspace);
    EXPECT_EQ(above.limb, 0);
    EXPECT_GT(above.value, model.l);
    EXPECT_NE(describe(above, model.parameters).find("beyond the link length"), std::string::npos);
    // NaN never passes as a pose.
    EXPECT_FALSE(prr3::inverseDisplacement(model, data, Pose(std::nan(""), 0.0, 0.0)).ok());
}

TEST(Workspace, LinkNormalToItsRailIsASingularPostureNotANaN) {
    const prr3::Model model;
    prr3::Data data;
    // Raise C until d_1^M = l (1 - 1e-10): cos phi_A1 ~ 1.4e-5.
    const double y = model.l * (1 - 1e-10) - 0.5 * (model.R - model.r);
    ASSERT_TRUE(prr3::inverseDisplacement(model, data, Pose(0.0, 0.0, y)).ok());
    const Status status = prr3::velocityFromPlatformTwist(model, data, Twist(0.0, 0.0, 1.0));
    EXPECT_EQ(status.code, StatusCode::singular_inverse_jacobian);
    EXPECT_EQ(status.limb, 0);
    EXPECT_GT(status.value, model.parameters.max_condition);
    EXPECT_NE(describe(status, model.parameters).find("limb 1"), std::string::npos);
}

TEST(Workspace, ConcurrentLinkLinesAreAForwardSingularity) {
    // Rotating the platform about O, the three link lines meet at C when h_j1 = 0 (eq. 7):
    // the first column of H vanishes (near theta = -2.08 rad for the paper's robot, where
    // phi_Mj = pi/6).
    prr3::Data data;
    const double lo = concurrentLinkLinesRotation();
    const prr3::Model model;
    ASSERT_TRUE(prr3::inverseDisplacement(model, data, Pose(lo, 0.0, 0.0)).ok());
    const Status status = prr3::velocityFromPlatformTwist(model, data, Twist(1.0, 0.0, 0.0));
    EXPECT_EQ(status.code, StatusCode::singular_forward_jacobian) << "theta = " << lo;
    EXPECT_GT(status.value, model.parameters.max_condition);
    // Away from it the same rotation direction is fine.
    ASSERT_TRUE(prr3::inverseDisplacement(model, data, Pose(lo + 0.3, 0.0, 0.0)).ok());
    EXPECT_TRUE(prr3::velocityFromPlatformTwist(model, data, Twist(1.0, 0.0, 0.0)).ok());
}

TEST(Workspace, StrokeBeyondTheActuatorIsReportedForTheRightLimb) {
    const prr3::Model model;
    prr3::Data data;
    ASSERT_TRUE(prr3::inverseDisplacement(model, data, Pose(0.0, 0.0, 0.0)).ok());
    EXPECT_TRUE(prr3::checkStroke(model, data).ok());
    ASSERT_TRUE(prr3::inverseDisplacement(model, data, Pose(0.0, 0.03, 0.0)).ok());
    const Status status = prr3::checkStroke(model, data);
    ASSERT_EQ(status.code, StatusCode::stroke_exceeded);
    // The first limb (in the paper's order) beyond +-stroke/2 is named, with its u_j.
    ASSERT_GE(status.limb, 0);
    EXPECT_EQ(status.value, data.u(status.limb));
    EXPECT_GT(std::abs(status.value), 0.5 * model.parameters.stroke);
    for (int j = 0; j < status.limb; ++j) EXPECT_LE(std::abs(data.u(j)), 0.5 * model.parameters.stroke);
    EXPECT_NE(describe(status, model.parameters).find("stroke"), std::string::npos);
}

}  // namespace
}  // namespace nocdyn::test
