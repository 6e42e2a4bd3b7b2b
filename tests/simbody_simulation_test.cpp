// Our forward dynamics against the independent Simbody model under the same forces, and the
// computed-torque loop closed on the Simbody plant (ctest label: validation).
#include <gtest/gtest.h>

#include "nocdyn/control.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/forward_dynamics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/validation/simbody_robot.hpp"
#include "simbody_plant.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

TEST(SimbodyForwardDynamics, SameForcesGiveTheSameMotionAsSimbody) {
    // Forces of the paper trajectories' inverse dynamics, held for 0.1 ms each (zero-order
    // hold, as Simbody's plant applies them), 0.1 s from the trajectory's initial state.
    const RobotParameters robot;
    const Model model(robot);  // the short form, expanded to the general model
    for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
        Data data(model);
        Pose p, dp, ddp;
        trajectory.evaluate(0.0, p, dp, ddp);
        Simulator ours(model);
        ASSERT_TRUE(ours.reset(p, dp).ok());
        validation::SimbodyRobot simbody(robot);
        simbody.setIntegratorAccuracy(1e-10);
        simbody.resetPlant(p, dp);
        EXPECT_LE((simbody.u() - ours.u()).cwiseAbs().maxCoeff(), 1e-12);
        double u_difference = 0.0, pose_difference = 0.0;
        const double h = 1e-4;
        for (int k = 0; k < 1000; ++k) {
            trajectory.evaluate((k + 0.5) * h, p, dp, ddp);
            ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
            ASSERT_TRUE(ours.advance(h, data.tau).ok()) << "t = " << k * h;
            simbody.setActuatorForces(Vector3(data.tau));
            simbody.advance(h);
            u_difference = std::max(u_difference, (simbody.u() - ours.u()).cwiseAbs().maxCoeff());
            pose_difference = std::max(pose_difference, (simbody.pose() - ours.pose()).cwiseAbs().maxCoeff());
        }
        // The motion spans several millimetres; both integrators run at ~1e-10 accuracy.
        EXPECT_LE(u_difference, 1e-8) << trajectory.name;
        EXPECT_LE(pose_difference, 1e-7) << trajectory.name;
        EXPECT_NEAR(simbody.kineticEnergy(), ours.kineticEnergy(), 1e-7 * ours.kineticEnergy()) << trajectory.name;
    }
}

TEST(SimbodyForwardDynamics, ComputedTorqueOnTheSimbodyPlantBeatsPd) {
    const RobotParameters robot;
    const Model model(robot);
    const control::Gains gains = control::criticallyDamped(50.0);
    control::ComputedTorqueController computed_torque(model, gains);
    control::PdController pd(control::equivalentPdGains(model, gains));
    control::ClosedLoopOptions options;
    options.duration = 0.1;
    cli::SimbodyPlant plant_a(robot), plant_b(robot);
    const auto ct = control::runClosedLoop(computed_torque, model, plant_a, paperTrajectory1(), options);
    const auto pd_result = control::runClosedLoop(pd, model, plant_b, paperTrajectory1(), options);
    EXPECT_LT(ct.rms_error.maxCoeff(), 1e-6);
    EXPECT_LT(ct.rms_error.maxCoeff(), pd_result.rms_error.maxCoeff() / 50.0);
}

}  // namespace
}  // namespace nocdyn::test
