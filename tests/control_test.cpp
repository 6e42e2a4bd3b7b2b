// Closed-loop control in actuator space on nocdyn's own forward dynamics, on the general model
// of the paper's 3-PRR (the short form expanded): computed torque tracks the paper's
// trajectories to a fraction of a micrometre and beats PD by orders of magnitude; a payload
// unknown to the controller degrades it; saturation and noise do what they say; one
// controller tick allocates nothing.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"

#include "nocdyn/control.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/model.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

using control::JointVector;

constexpr double kNaturalFrequency = 50.0;  // [Hz], the CLI's default

control::ClosedLoopResult run(const Model& controller_model, const Model& plant_model, control::Controller& controller,
                              const PoseTrajectory& trajectory, const control::ClosedLoopOptions& options = {}) {
    control::SimulatorPlant plant(plant_model);
    return control::runClosedLoop(controller, controller_model, plant, trajectory, options);
}

TEST(Control, ComputedTorqueBeatsPdOnRmsErrorForBothPaperTrajectories) {
    const Model model{RobotParameters{}};
    const control::Gains gains = control::criticallyDamped(kNaturalFrequency);
    for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
        control::ComputedTorqueController computed_torque(model, gains);
        control::PdController pd(control::equivalentPdGains(model, gains));
        const auto ct = run(model, model, computed_torque, trajectory);
        const auto pd_result = run(model, model, pd, trajectory);
        // measured (10 kHz, f_n = 50 Hz): CT ~2e-7..6e-7 m RMS, PD ~7e-5..2e-4 m RMS
        for (int j = 0; j < 3; ++j) {
            EXPECT_LT(ct.rms_error(j), 1e-6) << trajectory.name << " actuator " << j + 1;
            EXPECT_LT(ct.rms_error(j), pd_result.rms_error(j) / 50.0) << trajectory.name << " actuator " << j + 1;
        }
        EXPECT_LT(ct.pose_peak_error.tail<2>().maxCoeff(), 5e-6) << trajectory.name;
        EXPECT_EQ(ct.saturated_ticks, 0u);
    }
}

TEST(Control, ComputedTorqueErrorShrinksWithTheControlRate) {
    // With a perfect model the only error source is the zero-order hold of the forces.
    const Model model{RobotParameters{}};
    const control::Gains gains = control::criticallyDamped(kNaturalFrequency);
    control::ComputedTorqueController controller(model, gains);
    control::ClosedLoopOptions slow, fast;
    slow.rate = 2500.0;
    fast.rate = 20000.0;
    const auto a = run(model, model, controller, paperTrajectory1(), slow);
    const auto b = run(model, model, controller, paperTrajectory1(), fast);
    EXPECT_LT(b.rms_error.maxCoeff(), a.rms_error.maxCoeff() / 4.0)
        << a.rms_error.maxCoeff() << " vs " << b.rms_error.maxCoeff();
}

TEST(Control, UnknownPayloadDegradesComputedTorqueWhichStillBeatsPd) {
    const Model model{RobotParameters{}};
    const Model heavy(control::withPayload(RobotParameters{}, 0.5, 1e-3));
    const control::Gains gains = control::criticallyDamped(kNaturalFrequency);
    control::ComputedTorqueController computed_torque(model, gains);
    control::PdController pd(control::equivalentPdGains(model, gains));
    const auto perfect = run(model, model, computed_torque, paperTrajectory1());
    const auto mismatched = run(model, heavy, computed_torque, paperTrajectory1());
    const auto pd_mismatched = run(model, heavy, pd, paperTrajectory1());
    EXPECT_GT(mismatched.rms_error.maxCoeff(), 5.0 * perfect.rms_error.maxCoeff());
    EXPECT_LT(mismatched.rms_error.maxCoeff(), pd_mismatched.rms_error.maxCoeff() / 5.0);
}

TEST(Control, SaturationClipsTheForcesAtThePeak) {
    const Model model{RobotParameters{}};
    control::ComputedTorqueController controller(model, control::criticallyDamped(kNaturalFrequency));
    control::ClosedLoopOptions options;
    options.peak_force = 60.0;  // paper1 needs up to ~140 N
    const auto clipped = run(model, model, controller, paperTrajectory1(), options);
    EXPECT_GT(clipped.saturated_ticks, 100u);
    double largest = 0.0;
    for (const JointVector& tau : clipped.tau) largest = std::max(largest, tau.cwiseAbs().maxCoeff());
    EXPECT_LE(largest, 60.0);
    EXPECT_DOUBLE_EQ(largest, 60.0);
    const auto free = run(model, model, controller, paperTrajectory1());
    EXPECT_GT(clipped.rms_error.maxCoeff(), 10.0 * free.rms_error.maxCoeff());
}

TEST(Control, SensorNoiseRaisesTheErrorBoundedly) {
    const Model model{RobotParameters{}};
    control::ComputedTorqueController controller(model, control::criticallyDamped(kNaturalFrequency));
    control::ClosedLoopOptions noisy;
    noisy.noise_u = 1e-5;
    noisy.noise_du = 1e-3;
    const auto clean = run(model, model, controller, paperTrajectory1());
    const auto with_noise = run(model, model, controller, paperTrajectory1(), noisy);
    EXPECT_GT(with_noise.rms_error.maxCoeff(), 2.0 * clean.rms_error.maxCoeff());
    EXPECT_LT(with_noise.rms_error.maxCoeff(), 1e-5) << with_noise.rms_error.maxCoeff();
}

TEST(Control, ComputedTorqueReproducesInverseDynamicsOnTheTrajectory) {
    // On the trajectory (zero error) the command is the inverse dynamics (eq. 20).
    const Model model{RobotParameters{}};
    Data data(model), reference_data(model);
    control::ComputedTorqueController controller(model, control::criticallyDamped(kNaturalFrequency));
    const PoseTrajectory trajectory = paperTrajectory2();
    control::Reference reference;
    JointVector tau;
    for (int k = 0; k < 200; ++k) {
        const double t = k * 1e-3;
        ASSERT_TRUE(control::desiredMotion(model, reference_data, trajectory, t, reference).ok());
        controller.reset(reference.p);
        ASSERT_TRUE(controller.compute(reference.u, reference.du, reference, tau).ok());
        ASSERT_TRUE(inverseDynamics(model, data, reference.p, reference.dp, reference.ddp).ok());
        EXPECT_LE((tau - data.tau).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + data.tau.cwiseAbs().maxCoeff())) << "t = " << t;
    }
}

TEST(Control, ActuatorSpaceControlRefusesARobotWithoutExactlyThreeActuators) {
    const Model redundant(io::exampleRobot("4-rrr"));
    ASSERT_EQ(redundant.actuators, 4);
    EXPECT_THROW(control::ComputedTorqueController(redundant, control::criticallyDamped(kNaturalFrequency)), Error);
    EXPECT_THROW(control::SimulatorPlant{redundant}, Error);
    EXPECT_THROW((void)control::equivalentPdGains(redundant, control::criticallyDamped(kNaturalFrequency)), Error);
}

TEST(Control, ControllerTickAllocatesNothing) {
    const Model model{RobotParameters{}};
    Data data(model);
    control::ComputedTorqueController controller(model, control::criticallyDamped(kNaturalFrequency));
    const PoseTrajectory trajectory = paperTrajectory1();
    control::Reference reference;
    JointVector tau;
    ASSERT_TRUE(control::desiredMotion(model, data, trajectory, 0.0, reference).ok());
    controller.reset(reference.p);
    const long before = allocationCount();
    double checksum = 0.0;
    for (int k = 0; k < 1000; ++k) {
        checksum += control::desiredMotion(model, data, trajectory, k * 1e-4, reference).ok();
        checksum += controller.compute(reference.u + JointVector::Constant(1e-6), reference.du, reference, tau).ok();
        checksum += tau.sum();
    }
    EXPECT_EQ(allocationCount() - before, 0);
    EXPECT_TRUE(std::isfinite(checksum));
}

}  // namespace
}  // namespace nocdyn::test
