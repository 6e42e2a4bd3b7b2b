// The forward dynamics of any robot against the independent Simbody plant (SimbodyMechanism's
// resetPlant / setActuatorForces / advance) under the same held forces, on the example robots
// with gravity, damping and Coulomb friction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/validation/simbody_mechanism.hpp"

namespace nocdyn::test {
namespace {

// Both integrators run at 1e-10 (relative) accuracy and Simbody projects its constraints to
// 1e-12: over 50 force periods their states differ by accumulated truncation error, some
// 1e-9 of the motion's peaks; 1e-6 leaves room for the Coulomb terms' sign changes, which the
// two integrators locate with their own steps, and still fails on any modelling difference
// (a wrong inertia, gravity, friction sign or actuator direction gives 1e-3 or more).
constexpr double kStateOfPeak = 1e-6;

RobotDescription withGravityAndFriction(RobotDescription robot) {
    robot.gravity = Vector2(0.0, -9.81);
    for (LimbDescription& limb : robot.limbs) {
        for (JointDescription& joint : limb.joints) {
            const bool revolute = joint.type == JointType::revolute;
            joint.damping = revolute ? 2e-3 : 0.5;
            joint.friction = revolute ? 1e-3 : 0.2;
        }
    }
    return robot;
}

class ExampleRobot : public ::testing::TestWithParam<std::string> {};

TEST_P(ExampleRobot, FollowsTheSimbodyPlantUnderTheSameHeldForces) {
    const RobotDescription robot = withGravityAndFriction(io::exampleRobot(GetParam()));
    const Model model(robot);
    validation::SimbodyMechanism plant(robot);
    Simulator simulator(model);
    Data data(model);
    const PoseTrajectory trajectory = paperTrajectory1();
    Pose p, dp, ddp;
    trajectory.evaluate(0.0, p, dp, ddp);
    ASSERT_TRUE(simulator.reset(p, dp).ok());
    plant.resetPlant(p, dp);
    constexpr double kPeriod = 1e-3;  // forces held over each period, as a DAC would
    double peak_u = 0.0, peak_du = 0.0, d_u = 0.0, d_du = 0.0, d_pose = 0.0, d_kinetic = 0.0, peak_kinetic = 0.0;
    const ActuatorVector u0 = simulator.u();
    for (int k = 0; k < 50; ++k) {
        trajectory.evaluate(k * kPeriod, p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
        const Status status = simulator.advance(kPeriod, data.tau);
        ASSERT_TRUE(status.ok()) << describe(status, model);
        plant.setActuatorForces(Eigen::VectorXd(data.tau));
        plant.advance(kPeriod);
        ASSERT_NEAR(plant.time(), simulator.time(), 1e-12);
        const Eigen::VectorXd u = plant.u(), du = plant.du();
        for (int a = 0; a < model.actuators; ++a) {
            peak_u = std::max(peak_u, std::abs(simulator.u()(a) - u0(a)));
            peak_du = std::max(peak_du, std::abs(simulator.du()(a)));
            d_u = std::max(d_u, std::abs(simulator.u()(a) - u(a)));
            d_du = std::max(d_du, std::abs(simulator.du()(a) - du(a)));
        }
        d_pose = std::max(d_pose, (simulator.pose() - plant.pose()).cwiseAbs().maxCoeff());
        peak_kinetic = std::max(peak_kinetic, simulator.kineticEnergy());
        d_kinetic = std::max(d_kinetic, std::abs(simulator.kineticEnergy() - plant.kineticEnergy()));
    }
    ASSERT_GT(peak_u, 1e-4);
    EXPECT_LT(d_u, kStateOfPeak * peak_u) << GetParam();
    EXPECT_LT(d_du, kStateOfPeak * peak_du) << GetParam();
    EXPECT_LT(d_kinetic, kStateOfPeak * peak_kinetic) << GetParam();
    std::printf(
        "%s: 50 ms of held forces: max |u - u_Simbody| / peak = %.3g, |du - du_Simbody| / peak = %.3g, "
        "|pose - pose_Simbody| = %.3g, |KE - KE_Simbody| / peak = %.3g; Simbody steps %ld, ours %zu\n",
        GetParam().c_str(), d_u / peak_u, d_du / peak_du, d_pose, d_kinetic / peak_kinetic, plant.plantSteps(),
        simulator.acceptedSteps());
}

INSTANTIATE_TEST_SUITE_P(Robots, ExampleRobot, ::testing::Values("paper-3prr", "3-rrr", "3-rpr", "4-rrr"),
                         [](const auto& info) {
                             std::string name = info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace nocdyn::test
