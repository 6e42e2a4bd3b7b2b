// The simulated identification experiment's pieces: the sensors' log of a closed-loop run holds
// what the sensors measured (the encoder readings the controller used), and the payload is
// identified from such a log within the experiment's goal where the plant is cheap.
#include <cmath>

#include <gtest/gtest.h>

#include "nocdyn/sim/excitation.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/sim/shake.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn {
namespace {

const Payload kPayload{0.5, 8e-4, Vector2(0.012, -0.007)};

/// Computed torque along paper trajectory 2 (about home) with `robot` as the controller's model.
PoseLoopResult closedLoop(const RobotDescription& robot, RobotPlant& plant, double duration, bool encoders,
                          double noise_u = 1e-6) {
    const Model model(robot);
    PoseController controller(model, ControlLaw::computed_torque, taskCriticallyDamped(50.0));
    PoseLoopOptions loop;
    loop.duration = duration;
    loop.encoders = encoders;
    loop.noise_u = noise_u;
    loop.seed = 7;
    return runPoseLoop(controller, plant, aboutHome(model, paperTrajectory2()), loop);
}

/// The experiment's goal: mass 0.5 %, c.o.m. 0.2 mm, inertia 1 %.
void expectWithinGoal(const PayloadResult& r) {
    EXPECT_NEAR(r.mass, kPayload.mass, 0.005 * kPayload.mass);
    EXPECT_NEAR(r.com.x(), kPayload.com.x(), 2e-4);
    EXPECT_NEAR(r.com.y(), kPayload.com.y(), 2e-4);
    EXPECT_NEAR(r.inertia, kPayload.inertia, 0.01 * kPayload.inertia);
}

TEST(IdentificationExperiment, EncoderLogHoldsTheReadingsTheControllerUsed) {
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    SimulatorRobotPlant plant{Model(withPayload(robot, kPayload))};
    const PoseLoopResult run = closedLoop(robot, plant, 0.02, true);
    ASSERT_EQ(run.u_measured.size(), run.t.size());
    const Measurements log = sensorLog(run, 1e-6, 0.5, 8);
    double noise_u = 0.0, noise_tau = 0.0;
    int count = 0;
    for (std::size_t k = 0; k < run.t.size(); ++k) {
        for (int a = 0; a < 3; ++a) {
            const auto kk = static_cast<Eigen::Index>(k);
            // the very readings, not another draw
            EXPECT_EQ(log.u(kk, a), run.u_measured[k](a));
            noise_u += std::pow(log.u(kk, a) - run.u[k](a), 2);
            noise_tau += std::pow(log.tau(kk, a) - run.tau[k](a), 2);
            ++count;
        }
    }
    // 600 draws: RMS within 15 % of the standard deviation asked
    EXPECT_NEAR(std::sqrt(noise_u / count), 1e-6, 0.15e-6);
    EXPECT_NEAR(std::sqrt(noise_tau / count), 0.5, 0.075);
    // a pose sensor instead: no encoder readings, the log draws the encoder noise itself
    SimulatorRobotPlant other{Model(withPayload(robot, kPayload))};
    const PoseLoopResult pose_run = closedLoop(robot, other, 0.005, false);
    EXPECT_TRUE(pose_run.u_measured.empty());
    const Measurements pose_log = sensorLog(pose_run, 1e-6, 0.0, 8);
    EXPECT_NE(pose_log.u(10, 0), pose_run.u[10](0));
    EXPECT_NEAR(pose_log.u(10, 0), pose_run.u[10](0), 6e-6);
}

// The experiment of `nocdyn reproduce` on nocdyn's RK4 plant (cheap) along paper trajectory 2,
// noise-free sensors, 0.4 s: the payload within the goal (mass 0.5 %, c.o.m. 0.2 mm, inertia 1 %).
TEST(IdentificationExperiment, NoiseFreeClosedLoopIdentifiesThePayloadWithinTheGoal) {
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    const Model model(robot);
    RungeKuttaRobotPlant plant{Model(withPayload(robot, kPayload))};
    const PoseLoopResult run = closedLoop(robot, plant, 0.4, true, 0.0);
    IdentificationOptions options;
    options.held_forces = true;
    expectWithinGoal(identifyPayload(model, reconstructMotion(model, sensorLog(run, 0.0, 0.0), options), options));
}

// Slider damping and Coulomb friction on the plant only, identified alongside from u filtered
// and differentiated: the Coulomb columns are filtered as tau is (parallel filtering); without
// that the friction came out about 25 % low and the c.o.m. off by up to 1 mm.
TEST(IdentificationExperiment, FrictionIdentifiedAlongsideFromFilteredEncoders) {
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    const Model model(robot);
    RobotDescription plant_robot = withPayload(robot, kPayload);
    for (LimbDescription& limb : plant_robot.limbs) {
        limb.joints[0].damping = 20.0;
        limb.joints[0].friction = 2.0;
    }
    RungeKuttaRobotPlant plant{Model(plant_robot)};
    const PoseLoopResult run = closedLoop(robot, plant, 0.6, true, 0.0);
    IdentificationOptions options;
    options.held_forces = true;
    options.friction = true;
    const PayloadResult r =
        identifyPayload(model, reconstructMotion(model, sensorLog(run, 0.0, 0.0), options), options);
    expectWithinGoal(r);
    ASSERT_EQ(r.friction.size(), 6U);
    for (const Estimate& e : r.friction) {
        const bool damping = e.name.find("damping") != std::string::npos;
        EXPECT_NEAR(e.value, damping ? 20.0 : 2.0, damping ? 1.0 : 0.1) << e.name;
    }
}

}  // namespace
}  // namespace nocdyn
