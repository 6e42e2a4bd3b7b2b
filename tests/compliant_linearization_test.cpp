// The compliant (lumped) linearised model (analysis/linearization.hpp, linearizeCompliant)
// against the lumped model of analysis/stiffness.hpp: at rest with gravity off its static
// stiffness -M_p A_21 is cartesianStiffness' K and its free eigenfrequencies are lumpedModes';
// a robot whose drives are all force actuators (stiffness 0) keeps the rigid model's inputs; a
// robot without compliance gets the rigid model; the plant from the commanded drive positions
// to the platform acceleration peaks at the lumped frequencies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/io/robot_file.hpp"

namespace nocdyn::test {
namespace {

RobotDescription robotFile(const std::string& name) {
    RobotDescription robot = io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml");
    robot.gravity.setZero();
    return robot;
}

/// The compliant model at rest at p, with K and the lumped modes at the same pose.
struct AtRest {
    StateSpace system;
    StiffnessData stiffness;
    LumpedModes modes;
};

AtRest atRest(const Model& model, const Pose& p) {
    const StiffnessModel compliance(model);
    Data data(model);
    AtRest r;
    const ActuatorVector tau0 = ActuatorVector::Zero(model.actuators);
    EXPECT_TRUE(linearizeCompliant(model, compliance, data, p, Twist::Zero(), tau0, LinearOutput::platform_acceleration,
                                   r.system)
                    .ok());
    Data fresh(model);
    EXPECT_TRUE(stiffnessAndModes(model, compliance, fresh, p, r.stiffness, r.modes).ok());
    return r;
}

/// The undamped frequencies of A [Hz], ascending: |lambda| of its oscillating eigenvalues (the
/// modal damping puts them at w (-zeta +- j sqrt(1 - zeta^2))), each checked to carry the robot
/// file's damping ratio zeta = -Re lambda / |lambda|.
std::vector<double> eigenfrequencies(const Eigen::MatrixXd& A, double zeta) {
    const Eigen::VectorXcd lambda = A.eigenvalues();
    const double largest = lambda.cwiseAbs().maxCoeff();
    std::vector<double> f;
    for (Eigen::Index i = 0; i < lambda.size(); ++i) {
        if (!(lambda(i).imag() > 1e-6 * largest)) continue;  // a free direction's 0 is no mode
        f.push_back(std::abs(lambda(i)) / (2.0 * std::numbers::pi));
        EXPECT_NEAR(-lambda(i).real() / std::abs(lambda(i)), zeta, 1e-9) << lambda(i);
    }
    std::sort(f.begin(), f.end());
    return f;
}

std::vector<Pose> poses(const Model& model) { return {model.home, model.home + Pose(0.02, 0.003, -0.002)}; }

TEST(CompliantLinearization, StaticStiffnessIsTheLumpedKAtRest) {
    const Model model(robotFile("paper-3prr-compliant"));
    for (const Pose& p : poses(model)) {
        const AtRest r = atRest(model, p);
        // d(generalized force)/dp = -M_p d(ddp)/dp
        Data data(model);
        const Eigen::MatrixXd M = r.modes.M;
        const Eigen::MatrixXd K = -M * r.system.A.block(3, 0, 3, 3);
        EXPECT_LT((K - r.stiffness.K).norm(), 1e-9 * r.stiffness.K.norm()) << K << "\nvs\n" << r.stiffness.K;
    }
}

TEST(CompliantLinearization, FreeEigenfrequenciesAreTheLumpedModes) {
    const Model model(robotFile("paper-3prr-compliant"));
    for (const Pose& p : poses(model)) {
        const AtRest r = atRest(model, p);
        const std::vector<double> f = eigenfrequencies(r.system.A, model.description.damping_ratio);
        ASSERT_EQ(f.size(), 3U);
        for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(f[static_cast<std::size_t>(i)], r.modes.frequency(i), 1e-9 * r.modes.frequency(i)) << i;
        }
        // every input is a commanded drive position (the drives have a stiffness)
        for (const LinearInput input : r.system.inputs) EXPECT_EQ(input, LinearInput::commanded_position);
    }
}

TEST(CompliantLinearization, MixedDrivesKeepTheIdentitiesAndNameTheirInputs) {
    RobotDescription robot = robotFile("paper-3prr-compliant");
    robot.limbs[0].joints[0].stiffness = 0.0;  // limb 1: a force actuator (voice coil)
    const Model model(robot);
    const AtRest r = atRest(model, model.home);
    ASSERT_EQ(r.system.inputs.size(), 3U);
    EXPECT_EQ(r.system.inputs[0], LinearInput::force);
    EXPECT_EQ(r.system.inputs[1], LinearInput::commanded_position);
    EXPECT_EQ(r.system.inputs[2], LinearInput::commanded_position);
    const Eigen::MatrixXd K = -Eigen::MatrixXd(r.modes.M) * r.system.A.block(3, 0, 3, 3);
    EXPECT_LT((K - r.stiffness.K).norm(), 1e-9 * r.stiffness.K.norm());
    // the free direction (limb 1 carries no spring load) is a zero eigenvalue, the others the modes
    ASSERT_EQ(r.stiffness.free_directions, 1);
    const std::vector<double> f = eigenfrequencies(r.system.A, model.description.damping_ratio);
    ASSERT_EQ(f.size(), 2U);
    EXPECT_NEAR(f[0], r.modes.frequency(1), 1e-9 * r.modes.frequency(1));
    EXPECT_NEAR(f[1], r.modes.frequency(2), 1e-9 * r.modes.frequency(2));
}

TEST(CompliantLinearization, AllForceDrivesGiveTheRigidInputsThroughElasticLinks) {
    // every drive a force actuator: each limb's free joints fix its wrench, its beams carry it
    // unchanged, so B is the rigid M_p^-1 A_p^T and K = 0
    RobotDescription robot = robotFile("paper-3prr-compliant");
    for (LimbDescription& limb : robot.limbs) limb.joints[0].stiffness = 0.0;
    const Model model(robot);
    const StiffnessModel compliance(model);
    ASSERT_TRUE(compliance.any);
    Data data(model);
    const ActuatorVector tau0 = ActuatorVector::Constant(model.actuators, 3.0);
    const Pose p = model.home + Pose(0.01, 0.002, 0.001);
    StateSpace compliant, rigid;
    ASSERT_TRUE(linearizeCompliant(model, compliance, data, p, Twist::Zero(), tau0, LinearOutput::platform_acceleration,
                                   compliant)
                    .ok());
    ASSERT_TRUE(linearize(model, data, p, Twist::Zero(), tau0, LinearOutput::platform_acceleration, rigid).ok());
    EXPECT_LT((compliant.B - rigid.B).norm(), 1e-12 * rigid.B.norm()) << compliant.B << "\nvs\n" << rigid.B;
    EXPECT_LT((compliant.A - rigid.A).norm(), 1e-9 * rigid.A.norm());
    for (const LinearInput input : compliant.inputs) EXPECT_EQ(input, LinearInput::force);
}

TEST(CompliantLinearization, AForceInputIsTheLimitOfAVanishingDriveSpringDrivenByItsOffset) {
    // a force tau on a free drive is a spring k -> 0 at rest offset tau / k: B_force = lim B_position / k;
    // limb 1's passive pivot a spring too, so that the limb carries spring load ((I - K_j C_j) acts)
    RobotDescription robot = robotFile("paper-3prr-compliant");
    robot.limbs[0].joints[1].stiffness = 50.0;  // [N m/rad]
    robot.limbs[0].joints[0].stiffness = 0.0;
    const Model force_model(robot);
    constexpr double k = 1e-5;  // [N/m]
    robot.limbs[0].joints[0].stiffness = k;
    const Model spring_model(robot);
    const AtRest force = atRest(force_model, force_model.home);
    const AtRest spring = atRest(spring_model, spring_model.home);
    ASSERT_EQ(force.system.inputs[0], LinearInput::force);
    ASSERT_EQ(spring.system.inputs[0], LinearInput::commanded_position);
    const Eigen::VectorXd b_force = force.system.B.col(0), b_limit = spring.system.B.col(0) / k;
    EXPECT_GT(b_force.norm(), 0.0);
    EXPECT_LT((b_force - b_limit).norm(), 1e-6 * b_force.norm()) << b_force.transpose() << "\nvs\n"
                                                                 << b_limit.transpose();
}

TEST(CompliantLinearization, WithoutComplianceItIsTheRigidModel) {
    const Model model(robotFile("paper-3prr"));
    const StiffnessModel compliance(model);
    ASSERT_FALSE(compliance.any);
    Data data(model);
    const ActuatorVector tau0 = ActuatorVector::Constant(model.actuators, 5.0);
    StateSpace compliant, rigid;
    ASSERT_TRUE(linearizeCompliant(model, compliance, data, model.home, Twist(0.1, 0.01, 0.0), tau0,
                                   LinearOutput::actuator_variables, compliant)
                    .ok());
    ASSERT_TRUE(
        linearize(model, data, model.home, Twist(0.1, 0.01, 0.0), tau0, LinearOutput::actuator_variables, rigid).ok());
    EXPECT_EQ(compliant.A, rigid.A);
    EXPECT_EQ(compliant.B, rigid.B);
    EXPECT_EQ(compliant.C, rigid.C);
    EXPECT_EQ(compliant.D, rigid.D);
}

TEST(CompliantLinearization, PlantFromCommandedPositionsPeaksAtTheLumpedFrequencies) {
    // lightly damped, so that the modes at 41.0 and 45.2 Hz are two peaks (at the default 2 %
    // their half-power widths, 2 zeta f, make |H|_F one)
    RobotDescription robot = robotFile("paper-3prr-compliant");
    robot.damping_ratio = 1e-3;
    const Model model(robot);
    const AtRest r = atRest(model, model.home);
    const std::vector<double> grid = logGrid(10.0, 1000.0, 400);
    const double step = grid[1] / grid[0];
    // |H|_F over every channel, and its local maxima
    std::vector<double> gain;
    for (const double f : grid) gain.push_back(frequencyResponse(r.system, f).norm());
    std::vector<double> peaks;
    for (std::size_t k = 1; k + 1 < grid.size(); ++k) {
        if (gain[k] > gain[k - 1] && gain[k] > gain[k + 1]) peaks.push_back(grid[k]);
    }
    // the distinct lumped frequencies (at home the symmetric robot's x and y modes are one)
    std::vector<double> lumped;
    for (int i = 0; i < 3; ++i) {
        const double f = r.modes.frequency(i);
        if (lumped.empty() || f > lumped.back() * (1.0 + 1e-6)) lumped.push_back(f);
    }
    ASSERT_EQ(peaks.size(), lumped.size()) << r.modes.frequency.transpose();
    for (std::size_t i = 0; i < peaks.size(); ++i) {
        EXPECT_LE(std::max(peaks[i] / lumped[i], lumped[i] / peaks[i]), step)
            << "peak " << peaks[i] << " Hz vs lumped " << lumped[i] << " Hz";
    }
    // the first resonance of the paper robot with its drive loops is near 41 Hz
    EXPECT_NEAR(r.modes.frequency(0), 41.0, 1.0);
}

TEST(CompliantLinearization, BandwidthOfACommandedPositionIsWhereTheMotionFallsThreeDecibelsBelowTheCommand) {
    // at home the x axis moves on the translation modes alone (41.04 Hz, a double mode on the
    // symmetric robot), so ddx/uc1 = -w^2 (motion per command) with the motion per command
    // 1 / (1 - r^2 + 2 j zeta r), r = f / f_1: its asymptote |H(f_min)| (f / f_min)^2 (slope
    // 40 dB/decade) is the rigid follower's, and |H| falls 3 dB below it where
    // (1 - r^2)^2 + (2 zeta r)^2 = 10^0.3, r^2 = u: u^2 - (2 - 4 zeta^2) u + 1 - 10^0.3 = 0
    const Model model(robotFile("paper-3prr-compliant"));
    const AtRest r = atRest(model, model.home);
    const FrequencyResponse response = frequencyResponse(r.system, logGrid(1.0, 1000.0, 4001));
    const int x = 1;                                            // output ddx (core order theta, x, y), input uc1
    EXPECT_NEAR(lowFrequencySlope(response, x, 0), 2.0, 3e-3);  // 2 + 2 r^2 / (1 - r^2) at r = 1 / 41
    const double zeta = model.description.damping_ratio, b = 2.0 - 4.0 * zeta * zeta;
    const double u = 0.5 * (b + std::sqrt(b * b - 4.0 * (1.0 - std::pow(10.0, 0.3))));
    const double expected = r.modes.frequency(0) * std::sqrt(u);
    EXPECT_NEAR(bandwidth3dB(response, x, 0), expected, 1e-3 * expected);
    EXPECT_NEAR(expected, 63.75, 0.05);
    // every channel from a commanded position has a bandwidth in the grid, above the first mode
    for (int o = 0; o < 3; ++o) {
        for (int i = 0; i < 3; ++i) {
            const double bw = bandwidth3dB(response, o, i);
            EXPECT_TRUE(bw > r.modes.frequency(0) && bw < 1000.0) << "channel " << o << "/" << i << ": " << bw;
        }
    }
    // a grid that starts on the resonance has no asymptote there: no number
    const FrequencyResponse late = frequencyResponse(r.system, logGrid(30.0, 1000.0, 100));
    EXPECT_GT(std::abs(lowFrequencySlope(late, x, 0) - std::round(lowFrequencySlope(late, x, 0))), kSlopeTolerance);
    EXPECT_TRUE(std::isnan(bandwidth3dB(late, x, 0)));
    // a grid that ends below the fall: beyond the grid
    EXPECT_TRUE(std::isnan(bandwidth3dB(frequencyResponse(r.system, logGrid(1.0, 60.0, 400)), x, 0)));
}

}  // namespace
}  // namespace nocdyn::test
