// The frozen 3-PRR kernel against the paper's literal formulas: the inverse displacement of
// Appendix A (eqs. 35-42) closes every loop, and H and D are eqs. 7 and 6 written with the
// paper's angles. (The general model's kinematics are checked on every limb type by
// tests/kinematics_test.cpp and tests/model_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "baseline_support.hpp"

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
    BaselineSampler sampler(model);
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
    BaselineSampler sampler(model);
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

}  // namespace
}  // namespace nocdyn::test
