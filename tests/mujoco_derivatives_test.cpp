// The exact forward-dynamics derivatives d ddp/d(p, dp, tau) (derivatives.hpp) against
// MuJoCo's own linearisation of the independent model generated from the same robot file
// (validation/mujoco: mjd_transitionFD of one mj_step, mapped to the platform through the
// loop-consistent states; MujocoMechanism::platformDerivatives).
//
// MuJoCo closes the loops with soft equality constraints, a1 + d (b v + k r) = (1 - d) a0 for
// the constraint acceleration a1 = J qacc (MuJoCo's soft-constraint model): with impedance d
// the loop is compliant by about (1 - d) / d, and a1 has no velocity-product term dJ/dt qvel,
// which the rigid loop has (J qacc + dJ/dt qvel = 0; the stabilisation b v + k r restores it
// over a few steps). So at rest (dp = 0, where dJ/dt qvel = 0) MuJoCo's ddp, d ddp/d p and
// d ddp/d tau approach ours as (1 - d) / d, while moving its ddp misses a term quadratic in
// dp, and its d ddp/d dp (made only of velocity-product terms here: no joint damping) is not
// the rigid robot's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "nocdyn/derivatives.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/validation/mujoco_mechanism.hpp"

namespace nocdyn::test {
namespace {

// MuJoCo's largest impedance: the loops compliant by (1 - d) / d = 1e-4.
constexpr double kStiff = 0.9999;
// the measured differences at rest are 2e-5 to 1.4e-4 (the compliance times the conditioning of
// the constraint-space inertia); 1e-3 bounds them, while a wrong derivative differs by O(1)
constexpr double kAtRest = 1e-3;

double relative(const Eigen::MatrixXd& ours, const Eigen::MatrixXd& theirs) {
    return (ours - theirs).cwiseAbs().maxCoeff() / ours.cwiseAbs().maxCoeff();
}

struct Errors {
    double ddp = 0.0, d_p = 0.0, d_dp = 0.0, d_tau = 0.0;
    double ddp_absolute = 0.0;   ///< max |ddp_ours - ddp_MuJoCo| [rad/s^2, m/s^2]
    double d_dp_absolute = 0.0;  ///< max |d ddp/d dp of MuJoCo - ours| [1/s]
};

/// Ours against MuJoCo's at three poses of the paper's trajectory 1 under the forces of its
/// motion there, the pose rate scaled by `speed` (0: at rest), the worst of each.
Errors compare(const std::string& file, double impedance, double speed) {
    const RobotDescription robot = io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + file);
    const Model model(robot);
    Data data(model);
    validation::MujocoMechanism plant(robot);
    const PoseTrajectory trajectory = paperTrajectory1();
    Errors e;
    for (const double t : {0.013, 0.041, 0.077}) {
        Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        EXPECT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
        const ActuatorVector tau = data.tau;
        dp *= speed;
        ForwardDynamicsDerivatives ours;
        EXPECT_TRUE(forwardDynamicsDerivatives(model, data, p, dp, tau, ours).ok());
        plant.resetPlant(p, dp, t);
        plant.setActuatorForces(Eigen::VectorXd(tau));
        const auto theirs = plant.platformDerivatives(1e-6, 1e-6, impedance);
        e.ddp = std::max(e.ddp, relative(ours.ddp, theirs.ddp));
        e.ddp_absolute = std::max(e.ddp_absolute, (ours.ddp - theirs.ddp).cwiseAbs().maxCoeff());
        e.d_p = std::max(e.d_p, relative(ours.d_p, theirs.d_p));
        e.d_dp_absolute = std::max(e.d_dp_absolute, (ours.d_dp - theirs.d_dp).cwiseAbs().maxCoeff());
        if (speed > 0.0) e.d_dp = std::max(e.d_dp, relative(ours.d_dp, theirs.d_dp));
        e.d_tau = std::max(e.d_tau, relative(Eigen::MatrixXd(ours.d_tau), theirs.d_tau));
    }
    std::printf(
        "%s, speed %g, loop impedance %g: relative difference to MuJoCo: ddp %.2e, d ddp/d p %.2e, "
        "d ddp/d dp %.2e (absolute %.2e /s), d ddp/d tau %.2e\n",
        file.c_str(), speed, impedance, e.ddp, e.d_p, e.d_dp, e.d_dp_absolute, e.d_tau);
    return e;
}

class MujocoDerivatives : public ::testing::TestWithParam<std::string> {};

TEST_P(MujocoDerivatives, AtRestTheyAgreeToTheStiffestLoopsCompliance) {
    const Errors e = compare(GetParam(), kStiff, 0.0);
    EXPECT_LE(e.ddp, kAtRest);
    EXPECT_LE(e.d_p, kAtRest);
    EXPECT_LE(e.d_tau, kAtRest);
    // ours is 0 at rest (no damping); MuJoCo's is its difference quotient's noise
    EXPECT_LE(e.d_dp_absolute, 1e-2);
    // MuJoCo's default impedance 0.9: compliant by about (1 - 0.9) / 0.9 = 0.11
    const Errors soft = compare(GetParam(), 0.9, 0.0);
    EXPECT_LE(std::max({soft.ddp, soft.d_p, soft.d_tau}), 0.25);
}

TEST_P(MujocoDerivatives, MovingTheForceDerivativeAgreesAndTheAccelerationMissesAVelocityProduct) {
    const Errors full = compare(GetParam(), kStiff, 1.0);
    const Errors half = compare(GetParam(), kStiff, 0.5);
    // d ddp/d tau = M_p^-1 A_p^T does not depend on the rates
    EXPECT_LE(full.d_tau, kAtRest);
    // MuJoCo's ddp misses dJ/dt qvel, quadratic in the rates: half the speed, a quarter of the
    // difference (to the compliance's share)
    const double ratio = full.ddp_absolute / half.ddp_absolute;
    std::printf("%s: |ddp - ddp_MuJoCo| at full over half speed: %.3f\n", GetParam().c_str(), ratio);
    EXPECT_NEAR(ratio, 4.0, 0.2);
    // and its d ddp/d dp misses that term's derivative, linear in the rates: half of it
    EXPECT_NEAR(full.d_dp_absolute / half.d_dp_absolute, 2.0, 0.1);
}

INSTANTIATE_TEST_SUITE_P(Robots, MujocoDerivatives, ::testing::Values("paper-3prr.yaml", "3-rrr.yaml", "4-rrr.yaml"),
                         [](const auto& info) {
                             std::string name = info.param.substr(0, info.param.find('.'));
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace nocdyn::test
