// The general NOC model against the independent Simbody and MuJoCo models generated from the
// same robot description: the example robots along the paper's trajectories, and random
// robots of every limb type and actuation choice with gravity, friction and redundancy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/validation/mujoco_mechanism.hpp"
#include "nocdyn/validation/simbody_mechanism.hpp"
#include "random_robots.hpp"

namespace nocdyn::test {
namespace {

constexpr double kForceOfPeak = 1e-9;  // largest force difference, relative to the peak force
constexpr double kMotion = 1e-10;      // u, du, ddu, relative to their peaks

struct Agreement {
    double force = 0.0;  ///< largest |tau_ours - tau_engine| / peak |tau|
    double motion = 0.0;
};

/// Our series against one engine's along a trajectory.
template <typename Engine>
Agreement compare(const Model& model, Engine& engine, const PoseTrajectory& trajectory,
                  const std::vector<double>& times) {
    const auto samples = engine.inverseDynamics(trajectory, times);
    EXPECT_EQ(samples.size(), times.size());
    Data data(model);
    double peak_tau = 0.0, peak_u = 0.0, peak_du = 0.0, peak_ddu = 0.0;
    double d_tau = 0.0, d_u = 0.0, d_du = 0.0, d_ddu = 0.0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        Pose p, dp, ddp;
        trajectory.evaluate(times[k], p, dp, ddp);
        const Status status = inverseDynamics(model, data, p, dp, ddp);
        EXPECT_TRUE(status.ok()) << describe(status, model);
        if (!status) return {1.0, 1.0};
        const auto& s = samples[k];
        for (int a = 0; a < model.actuators; ++a) {
            peak_tau = std::max(peak_tau, std::abs(s.tau(a)));
            peak_u = std::max(peak_u, std::abs(s.u(a)));
            peak_du = std::max(peak_du, std::abs(s.du(a)));
            peak_ddu = std::max(peak_ddu, std::abs(s.ddu(a)));
            d_tau = std::max(d_tau, std::abs(data.tau(a) - s.tau(a)));
            d_u = std::max(d_u, std::abs(data.u(a) - s.u(a)));
            d_du = std::max(d_du, std::abs(data.du(a) - s.du(a)));
            d_ddu = std::max(d_ddu, std::abs(data.ddu(a) - s.ddu(a)));
        }
    }
    return {d_tau / peak_tau, std::max({d_u / peak_u, d_du / peak_du, d_ddu / peak_ddu})};
}

std::vector<double> sampleTimes(double duration, int count) {
    std::vector<double> times(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) times[static_cast<std::size_t>(k)] = duration * k / count;
    return times;
}

class ExampleRobot : public ::testing::TestWithParam<std::string> {};

TEST_P(ExampleRobot, AgreesWithSimbodyAndMujocoAlongThePaperTrajectories) {
    const RobotDescription robot = io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + GetParam());
    const Model model(robot);
    validation::SimbodyMechanism simbody(robot);
    validation::MujocoMechanism mujoco(robot);
    for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
        const auto times = sampleTimes(0.2, 200);
        const Agreement s = compare(model, simbody, trajectory, times);
        const Agreement m = compare(model, mujoco, trajectory, times);
        EXPECT_LT(s.force, kForceOfPeak) << GetParam() << " " << trajectory.name << " Simbody";
        EXPECT_LT(m.force, kForceOfPeak) << GetParam() << " " << trajectory.name << " MuJoCo";
        EXPECT_LT(s.motion, kMotion) << GetParam() << " " << trajectory.name << " Simbody";
        EXPECT_LT(m.motion, kMotion) << GetParam() << " " << trajectory.name << " MuJoCo";
        std::printf("%s %s: difference / peak: forces Simbody %.2g, MuJoCo %.2g; motion Simbody %.2g, MuJoCo %.2g\n",
                    GetParam().c_str(), trajectory.name.c_str(), s.force, m.force, s.motion, m.motion);
    }
}

// MuJoCo's plant (semi-implicit Euler at 0.1 ms, soft loop closures) under the inverse-dynamics
// forces of trajectory 1, held per 1 ms, against our forward dynamics: its loops stay closed to
// well under 1 um, and its pose follows ours to its step's error (about 21 um, 0.35 % of the
// 6 mm peak motion, over these 50 ms; 2 % bounds it, while a reversed actuator drives the
// platform the wrong way, a difference of the order of the motion itself).
TEST_P(ExampleRobot, MujocoPlantFollowsOurForwardDynamicsToItsStepError) {
    const RobotDescription robot = io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + GetParam());
    const Model model(robot);
    validation::MujocoMechanism plant(robot);
    Simulator simulator(model);
    Data data(model);
    const PoseTrajectory trajectory = paperTrajectory1();
    Pose p, dp, ddp;
    trajectory.evaluate(0.0, p, dp, ddp);
    const Pose p0 = p;
    ASSERT_TRUE(simulator.reset(p, dp).ok());
    plant.resetPlant(p, dp);
    double peak = 0.0, difference = 0.0, loop = 0.0;
    for (int k = 0; k < 50; ++k) {
        trajectory.evaluate(k * 1e-3, p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
        ASSERT_TRUE(simulator.advance(1e-3, data.tau).ok());
        plant.setActuatorForces(Eigen::VectorXd(data.tau));
        plant.advance(1e-3);
        ASSERT_NEAR(plant.time(), simulator.time(), 1e-9);
        peak = std::max(peak, (simulator.pose() - p0).tail<2>().cwiseAbs().maxCoeff());
        difference = std::max(difference, (simulator.pose() - plant.pose()).tail<2>().cwiseAbs().maxCoeff());
        loop = std::max(loop, plant.loopError());
    }
    ASSERT_GT(peak, 1e-4) << GetParam();
    EXPECT_LT(difference, 0.02 * peak) << GetParam();
    EXPECT_LT(loop, 1e-6) << GetParam();
    std::printf("%s: MuJoCo plant, 50 ms: max |C - C_ours| = %.3g um (peak motion %.3g um), loop error %.3g um\n",
                GetParam().c_str(), 1e6 * difference, 1e6 * peak, 1e6 * loop);
}

TEST(MujocoPlant, RefusesJointFrictionItDoesNotModel) {
    RobotDescription robot = io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rrr.yaml");
    robot.limbs[1].joints[2].damping = 0.1;
    validation::MujocoMechanism plant(robot);
    try {
        plant.resetPlant(robot.home);
        FAIL() << "friction accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("limb 2, joint 3"), std::string::npos) << e.what();
    }
}

INSTANTIATE_TEST_SUITE_P(Robots, ExampleRobot,
                         ::testing::Values("paper-3prr.yaml", "3-rrr.yaml", "3-rpr.yaml", "4-rrr.yaml"),
                         [](const auto& info) {
                             std::string name = info.param.substr(0, info.param.find('.'));
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

/// Largest |reaction_ours - reaction_Simbody| / peak |reaction_Simbody| along a trajectory, and
/// the peak [N or N m]; every component of every joint.
std::pair<double, double> reactionAgreement(const Model& model, validation::SimbodyMechanism& simbody,
                                            const PoseTrajectory& trajectory, const std::vector<double>& times) {
    const auto samples = simbody.inverseDynamics(trajectory, times);
    Data data(model);
    Reactions ours;
    double peak = 0.0, difference = 0.0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        Pose p, dp, ddp;
        trajectory.evaluate(times[k], p, dp, ddp);
        const Status status = inverseDynamicsWithReactions(model, data, p, dp, ddp, ours);
        EXPECT_TRUE(status.ok()) << describe(status, model);
        if (!status) return {1.0, 0.0};
        const auto& theirs = samples[k].reactions;
        EXPECT_EQ(theirs.size(), 3U * static_cast<std::size_t>(model.limbs));
        if (theirs.size() != 3U * static_cast<std::size_t>(model.limbs)) return {1.0, 0.0};
        for (std::size_t j = 0; j < static_cast<std::size_t>(model.limbs); ++j) {
            for (std::size_t jk = 0; jk < 3; ++jk) {
                const Eigen::Vector3d& r = theirs[3 * j + jk];
                peak = std::max(peak, r.cwiseAbs().maxCoeff());
                difference = std::max(difference, (ours.joint[j][jk] - r).cwiseAbs().maxCoeff());
            }
        }
    }
    return {difference / peak, peak};
}

// Simbody's mobilizer reaction forces (calcMobilizerReactionForces, the applied mobility forces
// included) and loop-closure constraint forces, with our inverse dynamics' forces applied, in
// our convention (base frame, inboard on outboard, effort and friction taken out): every example
// robot along trajectory 1, as given and with gravity and joint damping and friction.
TEST(SimbodyReactions, AgreeOnEveryExampleRobotWithinOneBillionthOfThePeak) {
    for (const char* name : {"paper-3prr.yaml", "paper-3prr-general.yaml", "3-rrr.yaml", "3-rpr.yaml", "4-rrr.yaml"}) {
        for (const bool loaded : {false, true}) {
            RobotDescription robot = io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name);
            if (loaded) {
                robot.gravity = Vector2(0.0, -9.81);
                for (LimbDescription& limb : robot.limbs) {
                    for (JointDescription& joint : limb.joints) {
                        joint.damping = 0.05;
                        joint.friction = 0.02;
                    }
                }
            }
            const Model model(robot);
            validation::SimbodyMechanism simbody(robot);
            const auto [agreement, peak] = reactionAgreement(model, simbody, paperTrajectory1(), sampleTimes(0.2, 100));
            EXPECT_GT(peak, 1.0) << name;
            EXPECT_LT(agreement, kForceOfPeak) << name << (loaded ? " with gravity and friction" : "");
            std::printf("%s%s: reactions, difference / peak (%.4g): Simbody %.2g\n", name,
                        loaded ? " with gravity and friction" : "", peak, agreement);
        }
    }
}

class RandomRobotOfType : public ::testing::TestWithParam<std::string> {};

// Per limb type: three-actuator robots with gravity and friction, and a redundant one.
TEST_P(RandomRobotOfType, AgreesWithSimbodyAndMujocoWithGravityFrictionAndRedundancy) {
    std::mt19937 rng(31);
    const std::string type = GetParam();
    const std::vector<RandomRobotSpec> specs{{{type, type, type}, 3, true, true},
                                             {{type, type, type}, 3, false, false},
                                             {{type, type, type, type}, 5, true, true}};
    for (const RandomRobotSpec& spec : specs) {
        int kept = 0;
        for (int attempt = 0; attempt < 100 && kept < 1; ++attempt) {
            const auto robot = randomRobot(spec, rng);
            if (!robot) continue;
            const Model model(*robot);
            const PoseTrajectory trajectory = trajectoryAround(robot->home, rng, 0.5);
            const auto times = sampleTimes(0.1, 60);
            // regular along the whole trajectory (our model's test, the engines' is theirs)
            Data data(model);
            bool regular = true;
            for (double t : times) {
                Pose p, dp, ddp;
                trajectory.evaluate(t, p, dp, ddp);
                regular = regular && inverseDynamics(model, data, p, dp, ddp).ok() && data.cond_A < 1e3;
            }
            if (!regular) continue;
            ++kept;
            validation::SimbodyMechanism simbody(*robot);
            validation::MujocoMechanism mujoco(*robot);
            const Agreement s = compare(model, simbody, trajectory, times);
            const Agreement m = compare(model, mujoco, trajectory, times);
            EXPECT_LT(s.force, kForceOfPeak) << type << " x" << spec.limb_types.size() << " Simbody";
            EXPECT_LT(m.force, kForceOfPeak) << type << " x" << spec.limb_types.size() << " MuJoCo";
            EXPECT_LT(s.motion, 1e-9) << type << " Simbody";
            EXPECT_LT(m.motion, 1e-9) << type << " MuJoCo";
            // every joint's reaction against Simbody's (loops closed at another joint than the
            // examples' for some limb types: reversed mobilizers)
            const auto [reactions, peak] = reactionAgreement(model, simbody, trajectory, times);
            EXPECT_LT(reactions, kForceOfPeak) << type << " x" << spec.limb_types.size() << " Simbody reactions";
            std::printf(
                "%s x%zu, %d actuators%s: force difference / peak: Simbody %.2g, MuJoCo %.2g; reactions "
                "(peak %.3g): Simbody %.2g\n",
                type.c_str(), spec.limb_types.size(), spec.actuators, spec.gravity ? ", gravity, friction" : "",
                s.force, m.force, peak, reactions);
        }
        EXPECT_EQ(kept, 1) << type << ": no regular random robot";
    }
}

INSTANTIATE_TEST_SUITE_P(EveryLimbType, RandomRobotOfType, ::testing::ValuesIn(limbTypes()));

}  // namespace
}  // namespace nocdyn::test
