// Two-DOF planar robots (motion: translation) against the independent Simbody and MuJoCo
// models generated from the same robot description: the platform a point mass at the tool
// point on the engines' planar mobilizer with its angle prescribed at home (every limb's last R
// joint at the point: the angle moves no body and takes no moment), the loops closed as for
// three-DOF robots, and the actuator forces from the x, y columns of the balance (the task map
// E). The shipped five-bar and biglide, as given and standing in a vertical plane with joint
// damping and friction, and random five-bars, biglides and three-armed (redundant) point
// robots, along smooth tool motions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/validation/mujoco_mechanism.hpp"
#include "nocdyn/validation/simbody_mechanism.hpp"
#include "point_robots.hpp"

namespace nocdyn::test {
namespace {

constexpr double kForceOfPeak = 1e-9;  // largest force difference, relative to the peak force
constexpr double kMotion = 1e-9;       // u, du, ddu, relative to their peaks

struct Agreement {
    double force = 0.0;   ///< largest |tau_ours - tau_engine| / peak |tau|
    double motion = 0.0;  ///< largest of the same for u, du, ddu
    double peak = 0.0;    ///< peak |tau| [N or N m]
};

/// Our series against one engine's along a tool motion (the pose's theta at home throughout).
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
        EXPECT_EQ(p(0), model.home(0));
        EXPECT_EQ(dp(0), 0.0);
        const Status status = inverseDynamics(model, data, p, dp, ddp);
        EXPECT_TRUE(status.ok()) << describe(status, model);
        if (!status) return {1.0, 1.0, 0.0};
        const auto& s = samples[k];
        EXPECT_EQ(s.tau.size(), model.actuators);
        if (s.tau.size() != model.actuators) return {1.0, 1.0, 0.0};
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
    return {d_tau / peak_tau, std::max({d_u / peak_u, d_du / peak_du, d_ddu / peak_ddu}), peak_tau};
}

std::vector<double> sampleTimes(double duration, int count) {
    std::vector<double> times(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k) times[static_cast<std::size_t>(k)] = duration * k / count;
    return times;
}

/// A tool motion about home: theta held at home, x and y two harmonics each of amplitude up to
/// `amplitude` [m], frequencies 2-12 rad/s.
PoseTrajectory toolMotion(const Vector3& home, std::mt19937& rng, double amplitude) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0), frequency(2.0, 12.0);
    PoseTrajectory trajectory;
    trajectory.name = "tool motion";
    trajectory.theta.offset = home(0);
    AxisMotion* axes[2] = {&trajectory.x, &trajectory.y};
    for (int i = 0; i < 2; ++i) {
        axes[i]->offset = home(i + 1);
        for (int h = 0; h < 2; ++h) {
            axes[i]->harmonics.push_back({amplitude * unit(rng), frequency(rng), std::numbers::pi * unit(rng)});
        }
    }
    return trajectory;
}

RobotDescription shipped(const std::string& name) {
    return io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml");
}

/// Gravity in the plane and damping and friction on every joint but the last (which takes none).
void loadRobot(RobotDescription& robot) {
    robot.gravity = Vector2(0.0, -9.81);
    for (LimbDescription& limb : robot.limbs) {
        for (std::size_t k = 0; k < 2; ++k) {
            limb.joints[k].damping = 0.05;
            limb.joints[k].friction = 0.02;
        }
    }
}

/// Largest |reaction_ours - reaction_Simbody| / peak |reaction_Simbody| along a trajectory.
double reactionAgreement(const Model& model, validation::SimbodyMechanism& simbody, const PoseTrajectory& trajectory,
                         const std::vector<double>& times) {
    const auto samples = simbody.inverseDynamics(trajectory, times);
    Data data(model);
    Reactions ours;
    double peak = 0.0, difference = 0.0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        Pose p, dp, ddp;
        trajectory.evaluate(times[k], p, dp, ddp);
        const Status status = inverseDynamicsWithReactions(model, data, p, dp, ddp, ours);
        EXPECT_TRUE(status.ok()) << describe(status, model);
        if (!status) return 1.0;
        const auto& theirs = samples[k].reactions;
        EXPECT_EQ(theirs.size(), 3U * static_cast<std::size_t>(model.limbs));
        if (theirs.size() != 3U * static_cast<std::size_t>(model.limbs)) return 1.0;
        for (std::size_t j = 0; j < static_cast<std::size_t>(model.limbs); ++j) {
            for (std::size_t jk = 0; jk < 3; ++jk) {
                const Eigen::Vector3d& r = theirs[3 * j + jk];
                peak = std::max(peak, r.cwiseAbs().maxCoeff());
                difference = std::max(difference, (ours.joint[j][jk] - r).cwiseAbs().maxCoeff());
            }
        }
    }
    EXPECT_GT(peak, 0.0);
    return difference / peak;
}

TEST(TwoDofEngines, ShippedRobotsAgreeWithSimbodyAndMujoco) {
    for (const char* name : {"five-bar", "biglide"}) {
        for (const bool loaded : {false, true}) {
            RobotDescription robot = shipped(name);
            if (loaded) loadRobot(robot);
            const Model model(robot);
            ASSERT_EQ(model.task_dimension, 2);
            validation::SimbodyMechanism simbody(robot);
            validation::MujocoMechanism mujoco(robot);
            std::mt19937 rng(7);
            const PoseTrajectory trajectory = toolMotion(robot.home, rng, 0.03);
            const auto times = sampleTimes(0.5, 150);
            const Agreement s = compare(model, simbody, trajectory, times);
            const Agreement m = compare(model, mujoco, trajectory, times);
            const std::string what = std::string(name) + (loaded ? " with gravity and friction" : "");
            EXPECT_GT(s.peak, 0.01) << what << ": the motion must load the actuators";
            EXPECT_LT(s.force, kForceOfPeak) << what << " Simbody";
            EXPECT_LT(m.force, kForceOfPeak) << what << " MuJoCo";
            EXPECT_LT(s.motion, kMotion) << what << " Simbody";
            EXPECT_LT(m.motion, kMotion) << what << " MuJoCo";
            const double reactions = reactionAgreement(model, simbody, trajectory, times);
            EXPECT_LT(reactions, kForceOfPeak) << what << " Simbody reactions";
            std::printf(
                "%s: peak %.3g, difference / peak: forces Simbody %.2g, MuJoCo %.2g; motion Simbody %.2g, "
                "MuJoCo %.2g; reactions Simbody %.2g\n",
                what.c_str(), s.peak, s.force, m.force, s.motion, m.motion, reactions);
        }
    }
}

// The engines' forward-dynamics plants free the platform's angle, which has no inertia for a
// point tool: they refuse a two-DOF robot in words rather than integrate a singular system.
TEST(TwoDofEngines, PlantsRefuseTwoDofRobots) {
    const RobotDescription robot = shipped("five-bar");
    validation::SimbodyMechanism simbody(robot);
    validation::MujocoMechanism mujoco(robot);
    for (const auto& reset : {std::function<void()>([&] { simbody.resetPlant(robot.home); }),
                              std::function<void()>([&] { mujoco.resetPlant(robot.home); })}) {
        try {
            reset();
            ADD_FAILURE() << "a two-DOF plant accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("does not take a two-DOF robot"), std::string::npos) << e.what();
        }
    }
}

TEST(TwoDofEngines, RandomPointRobotsAgreeWithSimbodyAndMujoco) {
    std::mt19937 rng(41);
    // per kind: five-bars, biglides, three-armed (redundant) point robots of R or P arms
    std::array<int, 3> checked{};
    constexpr int kPerKind = 3;
    double worst_simbody = 0.0, worst_mujoco = 0.0;
    for (int r = 0; r < 300 && *std::min_element(checked.begin(), checked.end()) < kPerKind; ++r) {
        const int kind = r % 3;
        const int limbs = kind == 2 ? 3 : 2;
        const bool prismatic = kind == 1 || (kind == 2 && r % 2 == 1);
        if (checked[static_cast<std::size_t>(kind)] >= kPerKind) continue;
        RobotDescription robot = randomPointRobot(rng, limbs, prismatic);
        if (r % 2 == 0) loadRobot(robot);
        std::unique_ptr<Model> model;
        try {
            model = std::make_unique<Model>(robot);
        } catch (const Error&) {
            continue;  // singular at home: another draw
        }
        const PoseTrajectory trajectory = toolMotion(robot.home, rng, 0.01);
        const auto times = sampleTimes(0.3, 60);
        // regular along the whole motion (our model's test; the engines' is theirs)
        Data data(*model);
        bool regular = true;
        for (const double t : times) {
            Pose p, dp, ddp;
            trajectory.evaluate(t, p, dp, ddp);
            regular = regular && inverseDynamics(*model, data, p, dp, ddp).ok() && data.cond_A < 1e3;
        }
        if (!regular) continue;
        ++checked[static_cast<std::size_t>(kind)];
        validation::SimbodyMechanism simbody(robot);
        validation::MujocoMechanism mujoco(robot);
        const Agreement s = compare(*model, simbody, trajectory, times);
        const Agreement m = compare(*model, mujoco, trajectory, times);
        const std::string what = robot.name + " " + std::to_string(r) + " (" + std::to_string(limbs) + " limbs)";
        EXPECT_LT(s.force, kForceOfPeak) << what << " Simbody";
        EXPECT_LT(m.force, kForceOfPeak) << what << " MuJoCo";
        EXPECT_LT(s.motion, kMotion) << what << " Simbody";
        EXPECT_LT(m.motion, kMotion) << what << " MuJoCo";
        worst_simbody = std::max(worst_simbody, s.force);
        worst_mujoco = std::max(worst_mujoco, m.force);
        std::printf("%s%s: peak %.3g, force difference / peak: Simbody %.2g, MuJoCo %.2g\n", what.c_str(),
                    r % 2 == 0 ? ", gravity, friction" : "", s.peak, s.force, m.force);
    }
    std::printf(
        "random point robots (five-bars, biglides, three-armed): %d, %d, %d; worst force difference / peak: "
        "Simbody %.2g, MuJoCo %.2g\n",
        checked[0], checked[1], checked[2], worst_simbody, worst_mujoco);
    for (const int count : checked) EXPECT_EQ(count, kPerKind);
}

}  // namespace
}  // namespace nocdyn::test
