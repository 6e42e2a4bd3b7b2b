// Closed-loop control of the paper's prototype (the default robot: the short form, expanded by
// io to the general model) by the one controller (control.hpp) on nocdyn's own forward
// dynamics: computed torque tracks both paper trajectories to a fraction of a micrometre and
// beats PD by orders of magnitude; its error shrinks with the control rate; a payload unknown
// to the controller degrades it; saturation and encoder noise do what they say; on the
// trajectory the command is the inverse dynamics (eq. 20).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn::test {
namespace {

constexpr double kNaturalFrequency = 50.0;  // [Hz], the CLI's default

RobotDescription prototype() { return io::exampleRobot("paper-3prr"); }

double largest(const std::vector<double>& values) { return *std::max_element(values.begin(), values.end()); }

PoseLoopResult run(const RobotDescription& controller_robot, const RobotDescription& plant_robot, ControlLaw law,
                   const PoseTrajectory& trajectory, const PoseLoopOptions& options = {}) {
    PoseController controller(Model(controller_robot), law, taskCriticallyDamped(kNaturalFrequency));
    SimulatorRobotPlant plant{Model(plant_robot)};
    return runPoseLoop(controller, plant, trajectory, options);
}

TEST(PrototypeControl, ComputedTorqueBeatsPdOnRmsErrorForBothPaperTrajectories) {
    const RobotDescription robot = prototype();
    for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
        const auto ct = run(robot, robot, ControlLaw::computed_torque, trajectory);
        const auto pd = run(robot, robot, ControlLaw::pd, trajectory);
        ASSERT_EQ(ct.actuators, 3);
        for (std::size_t j = 0; j < 3; ++j) {
            EXPECT_LT(ct.rms_error[j], 1e-6) << trajectory.name << " actuator " << j + 1;
            EXPECT_LT(ct.rms_error[j], pd.rms_error[j] / 50.0) << trajectory.name << " actuator " << j + 1;
        }
        EXPECT_LT(ct.pose_peak_error.tail<2>().maxCoeff(), 5e-6) << trajectory.name;
        EXPECT_EQ(ct.saturated_ticks, 0U);
    }
}

TEST(PrototypeControl, ComputedTorqueErrorShrinksWithTheControlRate) {
    // With a perfect model the only error source is the zero-order hold of the forces.
    const RobotDescription robot = prototype();
    PoseLoopOptions slow, fast;
    slow.rate = 2500.0;
    fast.rate = 20000.0;
    const auto a = run(robot, robot, ControlLaw::computed_torque, paperTrajectory1(), slow);
    const auto b = run(robot, robot, ControlLaw::computed_torque, paperTrajectory1(), fast);
    EXPECT_LT(largest(b.rms_error), largest(a.rms_error) / 4.0)
        << largest(a.rms_error) << " vs " << largest(b.rms_error);
}

TEST(PrototypeControl, UnknownPayloadDegradesComputedTorqueWhichStillBeatsPd) {
    const RobotDescription robot = prototype();
    const RobotDescription heavy = withPayload(robot, Payload{0.5, 1e-3, Vector2::Zero()});
    const auto perfect = run(robot, robot, ControlLaw::computed_torque, paperTrajectory1());
    const auto mismatched = run(robot, heavy, ControlLaw::computed_torque, paperTrajectory1());
    const auto pd_mismatched = run(robot, heavy, ControlLaw::pd, paperTrajectory1());
    EXPECT_GT(largest(mismatched.rms_error), 5.0 * largest(perfect.rms_error));
    EXPECT_LT(largest(mismatched.rms_error), largest(pd_mismatched.rms_error) / 5.0);
}

TEST(PrototypeControl, SaturationClipsTheForcesAtThePeak) {
    RobotDescription weak = prototype();
    for (LimbDescription& limb : weak.limbs) limb.joints[0].limits.effort = 60.0;  // paper1 needs up to ~140 N
    const auto clipped = run(weak, weak, ControlLaw::computed_torque, paperTrajectory1());
    EXPECT_GT(clipped.saturated_ticks, 100U);
    double peak = 0.0;
    for (const ActuatorVector& tau : clipped.tau) peak = std::max(peak, tau.cwiseAbs().maxCoeff());
    EXPECT_DOUBLE_EQ(peak, 60.0);
    EXPECT_DOUBLE_EQ(largest(clipped.peak_tau), 60.0);
    const RobotDescription robot = prototype();
    const auto free = run(robot, robot, ControlLaw::computed_torque, paperTrajectory1());
    EXPECT_GT(largest(clipped.rms_error), 10.0 * largest(free.rms_error));
}

TEST(PrototypeControl, EncoderNoiseRaisesTheErrorBoundedly) {
    // Measured through the encoders (u, du) and the direct-kinematics tracker, as the
    // prototype's sensors are.
    const RobotDescription robot = prototype();
    PoseLoopOptions clean, noisy;
    clean.encoders = noisy.encoders = true;
    noisy.noise_u = 1e-5;
    noisy.noise_du = 1e-3;
    const auto a = run(robot, robot, ControlLaw::computed_torque, paperTrajectory1(), clean);
    const auto b = run(robot, robot, ControlLaw::computed_torque, paperTrajectory1(), noisy);
    EXPECT_LT(largest(a.rms_error), 1e-6);
    EXPECT_GT(largest(b.rms_error), 2.0 * largest(a.rms_error));
    EXPECT_LT(largest(b.rms_error), 1e-5) << largest(b.rms_error);
}

TEST(PrototypeControl, ComputedTorqueOnTheTrajectoryIsTheInverseDynamics) {
    // With zero error the command is the inverse dynamics at the reference (eq. 20).
    const Model model(prototype());
    Data data(model), reference_data(model);
    PoseController controller(model, ControlLaw::computed_torque, taskCriticallyDamped(kNaturalFrequency));
    const PoseTrajectory trajectory = paperTrajectory2();
    PoseReference reference;
    ActuatorVector tau;
    for (int k = 0; k < 200; ++k) {
        const double t = k * 1e-3;
        ASSERT_TRUE(poseReference(model, reference_data, trajectory, t, reference).ok());
        ASSERT_TRUE(controller.compute(reference.p, reference.dp, reference, tau).ok());
        ASSERT_TRUE(inverseDynamics(model, data, reference.p, reference.dp, reference.ddp).ok());
        EXPECT_LE((tau - data.tau).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + data.tau.cwiseAbs().maxCoeff())) << "t = " << t;
    }
}

}  // namespace
}  // namespace nocdyn::test
