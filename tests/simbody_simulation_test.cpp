// Our forward dynamics of the paper's prototype against the independent Simbody model generated
// from the same robot file, under the same forces, and the computed-torque loop closed on the
// Simbody plant (ctest label: validation).
#include <gtest/gtest.h>

#include <algorithm>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/validation/simbody_mechanism.hpp"
#include "nocdyn/validation/simbody_plant.hpp"

namespace nocdyn::test {
namespace {

TEST(SimbodyForwardDynamics, SameForcesGiveTheSameMotionAsSimbody) {
    // Forces of the paper trajectories' inverse dynamics, held for 0.1 ms each (zero-order
    // hold, as Simbody's plant applies them), 0.1 s from the trajectory's initial state.
    const RobotDescription robot = io::exampleRobot("paper-3prr");
    const Model model(robot);
    for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
        Data data(model);
        Pose p, dp, ddp;
        trajectory.evaluate(0.0, p, dp, ddp);
        Simulator ours(model);
        ASSERT_TRUE(ours.reset(p, dp).ok());
        validation::SimbodyMechanism simbody(robot);
        simbody.setIntegratorAccuracy(1e-10);
        simbody.resetPlant(p, dp);
        EXPECT_LE((simbody.u() - Eigen::VectorXd(ours.u())).cwiseAbs().maxCoeff(), 1e-12);
        double u_difference = 0.0, pose_difference = 0.0;
        const double h = 1e-4;
        for (int k = 0; k < 1000; ++k) {
            trajectory.evaluate((k + 0.5) * h, p, dp, ddp);
            ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
            ASSERT_TRUE(ours.advance(h, data.tau).ok()) << "t = " << k * h;
            simbody.setActuatorForces(Eigen::VectorXd(data.tau));
            simbody.advance(h);
            u_difference = std::max(u_difference, (simbody.u() - Eigen::VectorXd(ours.u())).cwiseAbs().maxCoeff());
            pose_difference = std::max(pose_difference, (simbody.pose() - ours.pose()).cwiseAbs().maxCoeff());
        }
        // The motion spans several millimetres; both integrators run at ~1e-10 accuracy.
        EXPECT_LE(u_difference, 1e-8) << trajectory.name;
        EXPECT_LE(pose_difference, 1e-7) << trajectory.name;
        EXPECT_NEAR(simbody.kineticEnergy(), ours.kineticEnergy(), 1e-7 * ours.kineticEnergy()) << trajectory.name;
    }
}

TEST(SimbodyForwardDynamics, ComputedTorqueOnTheSimbodyPlantBeatsPd) {
    const RobotDescription robot = io::exampleRobot("paper-3prr");
    const Model model(robot);
    PoseLoopOptions options;
    options.duration = 0.1;
    PoseController computed_torque(model, ControlLaw::computed_torque, taskCriticallyDamped(50.0));
    PoseController pd(model, ControlLaw::pd, taskCriticallyDamped(50.0));
    validation::SimbodyPlant plant_a(robot), plant_b(robot);
    const auto ct = runPoseLoop(computed_torque, plant_a, paperTrajectory1(), options);
    const auto pd_result = runPoseLoop(pd, plant_b, paperTrajectory1(), options);
    const double ct_rms = *std::max_element(ct.rms_error.begin(), ct.rms_error.end());
    const double pd_rms = *std::max_element(pd_result.rms_error.begin(), pd_result.rms_error.end());
    EXPECT_LT(ct_rms, 1e-6);
    EXPECT_LT(ct_rms, pd_rms / 50.0);
}

}  // namespace
}  // namespace nocdyn::test
