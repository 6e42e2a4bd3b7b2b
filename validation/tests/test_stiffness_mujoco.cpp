// The lumped natural frequencies (analysis/stiffness.hpp) against MuJoCo's linearisation of the
// same robot with its joint springs: the generated MJCF (validation/mujoco) carries each joint's
// stiffness, at rest at the pose (springref), gravity off; mjd_transitionFD differentiates one
// semi-implicit Euler step, whose velocity rows give the continuous-time state matrix exactly.
// MuJoCo closes the loops with soft connect constraints (solref [2 h, 1], default solimp: a
// critically damped constraint of time constant 2 h); they add a compliance in series with the
// springs, of relative size (omega / omega_c)^2 with omega_c ~ 1 / (2 h), so the difference falls
// as h^2: measured, 1.5e-4 at the plant's h = 1e-4 s, 1.3e-6 at h = 1e-5 s, and extrapolated to
// h = 0 (Richardson) under 1e-6.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/validation/mujoco_mechanism.hpp"

namespace nocdyn {
namespace {

namespace fs = std::filesystem;

RobotDescription robotDescription(const std::string& robot) {
    return io::loadRobotDescription((fs::path(NOCDYN_SOURCE_DIR) / "robots" / (robot + ".yaml")).string());
}

/// The relative differences of the three lowest MuJoCo modes from nocdyn's lumped ones.
std::vector<double> differences(const RobotDescription& robot, const Pose& p, double timestep) {
    const Model model(robot);
    const StiffnessModel compliance(model);
    Data data(model);
    StiffnessData K;
    LumpedModes lumped;
    EXPECT_TRUE(stiffnessAndModes(model, compliance, data, p, K, lumped).ok());
    validation::MujocoMechanism mujoco(robot);
    const std::vector<validation::MujocoMechanism::LinearMode> modes = mujoco.linearModes(p, timestep);
    EXPECT_GE(modes.size(), 3U);
    std::vector<double> out;
    for (std::size_t i = 0; i < std::min<std::size_t>(3, modes.size()); ++i) {
        const double d = modes[i].frequency / lumped.frequency(static_cast<Eigen::Index>(i)) - 1.0;
        std::printf("h = %g s, mode %zu: MuJoCo %.9g Hz (damping ratio %.3g), nocdyn lumped %.9g Hz, relative %.3g\n",
                    timestep, i + 1, modes[i].frequency, modes[i].damping_ratio,
                    lumped.frequency(static_cast<Eigen::Index>(i)), d);
        out.push_back(d);
    }
    return out;
}

RobotDescription prrWithDriveSprings() {
    RobotDescription robot = robotDescription("paper-3prr-general");
    const double k[3] = {1.0e5, 2.0e5, 3.0e5};
    for (std::size_t j = 0; j < 3; ++j) robot.limbs[j].joints[0].stiffness = k[j];
    return robot;
}

// At h = 1e-4 s (the plant's) and 1e-5 s; below, the finite differences' round-off (the constraint
// forces grow as 1 / h^2) outgrows the constraints' compliance: at h = 1e-6 s the difference was
// 1.4e-5, with damping ratios of either sign.
void expectAgreementOnceTheConstraintsSoftnessIsRemoved(const RobotDescription& robot, const Pose& p) {
    const std::vector<double> coarse = differences(robot, p, 1e-4);
    const std::vector<double> fine = differences(robot, p, 1e-5);
    ASSERT_EQ(coarse.size(), 3U);
    ASSERT_EQ(fine.size(), 3U);
    for (std::size_t i = 0; i < 3; ++i) {
        // the soft constraints lower every frequency, by O(h^2): a factor 100 per decade of h
        EXPECT_LT(coarse[i], 0.0);
        EXPECT_LT(std::abs(coarse[i]), 2e-4);
        EXPECT_NEAR(coarse[i] / fine[i], 100.0, 15.0);  // measured 100.4, 109.6, 111.4
        EXPECT_LT(std::abs(fine[i]), 2e-6);
        // Richardson's extrapolation to h = 0: d = d_0 + c h^2
        const double rigid = (100.0 * fine[i] - coarse[i]) / 99.0;
        std::printf("mode %zu: extrapolated to rigid constraints %.3g\n", i + 1, rigid);
        EXPECT_LT(std::abs(rigid), 1e-6);
    }
}

TEST(StiffnessMujoco, A3PrrWithDriveSpringsLumpedFrequenciesAgreeTo1e6OnceTheConstraintsSoftnessIsRemoved) {
    expectAgreementOnceTheConstraintsSoftnessIsRemoved(prrWithDriveSprings(), Pose(0.02, 0.002, -0.001));
}

// The loops closed at the elbows (MuJoCo's connect), the motors' springs in the trees. The
// springs are weak (modes near 6 Hz), so the constraints' share is small already at the plant's
// step, and at h = 1e-5 s the finite differences' round-off (measured 1e-6 to 2e-5 with eps 1e-6
// to 1e-7) hides its h^2 decrease: asserted at the plant's step only.
TEST(StiffnessMujoco, A3RrrWithMotorSpringsLumpedFrequenciesAgreeTo1e5AtThePlantsStep) {
    RobotDescription robot = robotDescription("3-rrr");
    for (std::size_t j = 0; j < 3; ++j) robot.limbs[j].joints[0].stiffness = 20.0 + 2.0 * static_cast<double>(j);
    const std::vector<double> d = differences(robot, Pose(0.01, 0.002, 0.003), 1e-4);
    ASSERT_EQ(d.size(), 3U);
    for (const double di : d) {
        EXPECT_LT(di, 0.0);  // measured -7.6e-6, -8.4e-6, -8.6e-6
        EXPECT_GT(di, -1e-5);
    }
}

}  // namespace
}  // namespace nocdyn
