// Direct kinematics of the general model (direct_kinematics.hpp) against an independent
// brute-force search: the unknowns are the platform pose and every passive joint variable,
// the equations are the limbs' loop closures by the product of exponentials (written here
// with Eigen's Isometry2d, not with the library's constraint equations or polynomial), solved
// by Levenberg-Marquardt from a grid of angles times random joint values. Every pose the
// search finds must be among the library's modes, and every mode must give back u by inverse
// displacement on its branches. Random robots of every limb type and actuation choice, the
// example robots, constructed 3-RPR and 3-RRR configurations with six real modes, and the
// tracker along the paper's trajectory.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/trajectory.hpp"
#include "random_robots.hpp"

namespace nocdyn::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRoundTrip = 1e-12;  // |u(p) - u| of every mode [m or rad]

double wrap(double a) {
    a = std::remainder(a, 2.0 * kPi);
    return a <= -kPi ? a + 2.0 * kPi : a;
}

/// u of the working mode at pose p.
ActuatorVector actuatorsAt(const Model& model, const Pose& p) {
    Data data(model);
    EXPECT_TRUE(inverseDisplacement(model, data, p).ok());
    return data.u;
}

// --- the independent search -----------------------------------------------------------

/// exp of a joint's home screw times q, from the description.
Eigen::Isometry2d jointMotion(const JointDescription& joint, double q) {
    Eigen::Isometry2d g = Eigen::Isometry2d::Identity();
    if (joint.type == JointType::prismatic) {
        g.translate(q * joint.direction);
    } else {
        g.translate(joint.point);
        g.rotate(Eigen::Rotation2Dd(q));
        g.translate(-joint.point);
    }
    return g;
}

/// Loop-closure residuals of every limb for unknowns z = [theta, x, y, passive q...].
struct Closure {
    const Model& model;
    ActuatorVector u;
    int unknowns = 3;

    Closure(const Model& m, const ActuatorVector& u_) : model(m), u(u_) {
        for (const auto& limb : model.description.limbs)
            for (const auto& joint : limb.joints) unknowns += joint.actuated ? 0 : 1;
    }

    [[nodiscard]] Eigen::VectorXd residual(const Eigen::VectorXd& z) const {
        Eigen::VectorXd r(3 * model.limbs);
        const double phi = z(0) - model.home(0);
        const Eigen::Vector2d C_home = model.home.tail<2>();
        int next = 3, actuator = 0;
        for (int j = 0; j < model.limbs; ++j) {
            Eigen::Isometry2d g = Eigen::Isometry2d::Identity();
            for (const auto& joint : model.description.limbs[static_cast<std::size_t>(j)].joints) {
                const double q = joint.actuated ? u(actuator++) : z(next++);
                g = g * jointMotion(joint, q);
            }
            const Eigen::Rotation2Dd rotation(g.rotation());
            r(3 * j) = wrap(rotation.angle() - phi);
            r.segment<2>(3 * j + 1) = g * C_home - z.segment<2>(1);
        }
        return r;
    }
};

/// Levenberg-Marquardt with a forward-difference Jacobian; true when the closures hold to 1e-11.
bool solveClosure(const Closure& closure, Eigen::VectorXd& z) {
    double lambda = 1e-3;
    Eigen::VectorXd r = closure.residual(z);
    for (int it = 0; it < 100; ++it) {
        if (r.cwiseAbs().maxCoeff() <= 1e-13) break;
        Eigen::MatrixXd J(r.size(), z.size());
        for (int i = 0; i < z.size(); ++i) {
            Eigen::VectorXd zh = z;
            const double h = 1e-7 * (1.0 + std::abs(z(i)));
            zh(i) += h;
            J.col(i) = (closure.residual(zh) - r) / h;
        }
        const Eigen::MatrixXd JtJ = J.transpose() * J;
        Eigen::MatrixXd M = JtJ;
        M.diagonal() += lambda * (JtJ.diagonal().array() + 1e-12).matrix();
        const Eigen::VectorXd step = M.fullPivLu().solve(J.transpose() * r);
        const Eigen::VectorXd trial = z - step;
        const Eigen::VectorXd r_trial = closure.residual(trial);
        if (r_trial.allFinite() && r_trial.squaredNorm() < r.squaredNorm()) {
            z = trial;
            r = r_trial;
            lambda = std::max(lambda * 0.1, 1e-12);
        } else {
            lambda *= 10.0;
            if (lambda > 1e8) return false;
        }
        if (z.segment<2>(1).norm() > 10.0) return false;
    }
    return r.cwiseAbs().maxCoeff() <= 1e-11;
}

/// Every pose the search finds: angles on a grid times random joint values.
std::vector<Pose> bruteForce(const Model& model, const ActuatorVector& u, int angles = 48, int per_angle = 8) {
    const Closure closure(model, u);
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<Pose> found;
    for (int a = 0; a < angles; ++a) {
        for (int s = 0; s < per_angle; ++s) {
            Eigen::VectorXd z(closure.unknowns);
            z(0) = model.home(0) - kPi + 2.0 * kPi * (a + 0.5) / angles;
            z(1) = 0.05 * unit(rng);
            z(2) = 0.05 * unit(rng);
            int next = 3;
            for (const auto& limb : model.description.limbs) {
                for (const auto& joint : limb.joints) {
                    if (joint.actuated) continue;
                    z(next++) = joint.type == JointType::revolute ? kPi * unit(rng) : 0.2 * unit(rng);
                }
            }
            if (!solveClosure(closure, z)) continue;
            const Pose p(wrap(z(0)), z(1), z(2));
            const bool known = std::any_of(found.begin(), found.end(), [&](const Pose& o) {
                return std::abs(wrap(o(0) - p(0))) < 1e-7 && (o.tail<2>() - p.tail<2>()).norm() < 1e-7;
            });
            if (!known) found.push_back(p);
        }
    }
    return found;
}

bool hasPose(const AssemblyModes& modes, const Pose& p, double tol) {
    return std::any_of(modes.begin(), modes.end(), [&](const AssemblyMode& m) {
        return std::abs(wrap(m.p(0) - p(0))) < tol && (m.p.tail<2>() - p.tail<2>()).norm() < tol;
    });
}

/// Every mode gives back u by inverse displacement on its branches, and `working` says
/// whether they are the home ones.
void expectRoundTrip(const Model& model, const ActuatorVector& u, const AssemblyModes& modes, const std::string& what) {
    Data data(model);
    for (const AssemblyMode& mode : modes) {
        ASSERT_TRUE(inverseDisplacement(model, data, mode.p, mode.branch).ok()) << what;
        double err = 0.0;
        for (int a = 0; a < model.actuators; ++a) err = std::max(err, std::abs(wrap(data.u(a) - u(a))));
        // round-off of u(p), amplified near a singularity by the conditioning
        EXPECT_LE(err, kRoundTrip * std::max(1.0, 1e-2 * mode.condition)) << what;
        EXPECT_NEAR(err, mode.u_error, 1e-15) << what;
        bool home = true;
        for (int j = 0; j < model.limbs; ++j)
            home = home && mode.branch[static_cast<std::size_t>(j)] == model.limb[static_cast<std::size_t>(j)].branch;
        EXPECT_EQ(mode.working, home) << what;
    }
}

struct Tally {
    int robots = 0, problems = 0, modes = 0, max_modes = 0, brute = 0, non_working = 0;
};

/// The library's modes against the search at u(p0), p0 a pose near home (a working mode).
void compareWithSearch(const Model& model, const Pose& p0, const std::string& what, Tally& tally) {
    const ActuatorVector u = actuatorsAt(model, p0);
    Data data(model);
    AssemblyModes modes;
    ASSERT_TRUE(directKinematics(model, data, u, modes).ok());
    EXPECT_FALSE(modes.degenerate) << what;
    EXPECT_FALSE(modes.truncated) << what;
    expectRoundTrip(model, u, modes, what);
    // p0 itself, on the home branches
    const auto it = std::find_if(modes.begin(), modes.end(), [&](const AssemblyMode& m) {
        return std::abs(wrap(m.p(0) - p0(0))) < 1e-9 && (m.p.tail<2>() - p0.tail<2>()).norm() < 1e-9;
    });
    ASSERT_NE(it, modes.end()) << what << ": the pose u was computed at is not among the modes";
    EXPECT_TRUE(it->working) << what;
    const std::vector<Pose> found = bruteForce(model, u);
    for (const Pose& p : found) {
        EXPECT_TRUE(hasPose(modes, p, 1e-6))
            << what << ": the search found theta = " << p(0) << ", x = " << p(1) << ", y = " << p(2)
            << " which the solver missed (" << modes.count << " modes, search " << found.size() << ")";
    }
    ++tally.problems;
    tally.modes += modes.count;
    tally.brute += static_cast<int>(found.size());
    tally.max_modes = std::max(tally.max_modes, modes.count);
    for (const AssemblyMode& m : modes) tally.non_working += m.working ? 0 : 1;
}

/// Random robots of the given limb types, each at one random pose within `reach` times
/// (0.05 rad, 3 mm) of home.
void randomRobots(const std::vector<std::string>& types, int actuators, int robots, Tally& tally, unsigned seed,
                  double reach = 1.0) {
    robots = sweepSize(robots);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int made = 0;
    for (int attempt = 0; attempt < 50 * robots && made < robots; ++attempt) {
        RandomRobotSpec spec;
        spec.actuators = actuators;
        for (const std::string& type : types) {
            spec.limb_types.push_back(type == "*" ? limbTypes()[rng() % limbTypes().size()] : type);
        }
        const auto description = randomRobot(spec, rng);
        if (!description) continue;
        const Model model(*description);
        const Pose p0 = model.home + reach * Pose(0.05 * unit(rng), 0.003 * unit(rng), 0.003 * unit(rng));
        Data data(model);
        if (!inverseDisplacement(model, data, p0) || !velocityFromPlatformTwist(model, data, Twist::Zero())) continue;
        ++made;
        std::string what;
        for (const auto& limb : description->limbs) {
            what += limb.type() + "(";
            for (const auto& joint : limb.joints) what += joint.actuated ? "a" : "-";
            what += ") ";
        }
        compareWithSearch(model, p0, what + "seed " + std::to_string(seed) + " attempt " + std::to_string(attempt),
                          tally);
    }
    tally.robots += made;
    EXPECT_EQ(made, robots);
}

TEST(DirectKinematicsRobots, RandomRobotsOfEveryTypeMatchTheSearch) {
    Tally tally;
    unsigned seed = 100;
    for (const std::string& type : limbTypes()) randomRobots({type, type, type}, 3, 6, tally, seed++);
    randomRobots({"*", "*", "*"}, 3, 20, tally, seed++);
    // farther from home: more modes, more of them off the home branches
    for (const std::string& type : limbTypes()) randomRobots({type, type, type}, 3, 4, tally, seed++, 6.0);
    randomRobots({"*", "*", "*"}, 3, 20, tally, seed++, 6.0);
    std::printf("%d robots, %d problems: %d modes (%d off the home branches), search %d, at most %d\n", tally.robots,
                tally.problems, tally.modes, tally.non_working, tally.brute, tally.max_modes);
    EXPECT_GE(tally.modes, tally.brute);
    EXPECT_GT(tally.non_working, 0);
}

TEST(DirectKinematicsRobots, RedundantRobotsMatchTheSearch) {
    Tally tally;
    randomRobots({"*", "*", "*"}, 4, 8, tally, 300);
    randomRobots({"*", "*", "*", "*"}, 4, 8, tally, 301);
    randomRobots({"*", "*", "*", "*"}, 5, 4, tally, 302);
    randomRobots({"RRR", "RRR", "RRR", "RRR"}, 4, 4, tally, 303);
    std::printf("%d redundant robots: %d modes, search %d, at most %d\n", tally.robots, tally.modes, tally.brute,
                tally.max_modes);
    EXPECT_GE(tally.modes, tally.brute);
}

TEST(DirectKinematicsRobots, ExampleRobotsHomeIsAWorkingMode) {
    for (const std::string& name : io::exampleRobotNames()) {
        const Model model(io::exampleRobot(name));
        Tally tally;
        compareWithSearch(model, model.home, name, tally);
        std::printf("%s: %d modes at u(home), search %d\n", name.c_str(), tally.modes, tally.brute);
    }
}

/// A 3-RPR (actuated P) or 3-RRR (actuated first R) with random anchors; scans random
/// poses for u with six real modes. Deterministic: the seed is fixed.
void sixModes(const std::string& type, int actuated_joint, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int attempt = 0; attempt < 4000; ++attempt) {
        RobotDescription robot;
        robot.name = "six";
        robot.platform = {1.0, 0.01, Eigen::Vector2d::Zero(), 0};
        for (int j = 0; j < 3; ++j) {
            const double phi = 2.0 * kPi * j / 3.0;
            const Eigen::Vector2d base =
                0.3 * Eigen::Vector2d(std::cos(phi), std::sin(phi)) + 0.1 * Eigen::Vector2d(unit(rng), unit(rng));
            const Eigen::Vector2d anchor = 0.15 * Eigen::Vector2d(unit(rng), unit(rng));
            const Eigen::Vector2d mid = 0.5 * (base + anchor) + 0.1 * Eigen::Vector2d(unit(rng), unit(rng));
            LimbDescription limb;
            limb.name = "limb" + std::to_string(j + 1);
            const std::array<Eigen::Vector2d, 3> points{base, mid, anchor};
            for (std::size_t k = 0; k < 3; ++k) {
                JointDescription& joint = limb.joints[k];
                joint.type = type[k] == 'R' ? JointType::revolute : JointType::prismatic;
                joint.point = points[k];
                joint.direction = (anchor - base).normalized();
                joint.actuated = static_cast<int>(k) == actuated_joint;
            }
            limb.bodies[0] = {0.5, 1e-3, 0.5 * (base + mid), 0, {}};
            limb.bodies[1] = {0.5, 1e-3, 0.5 * (mid + anchor), 0, {}};
            robot.limbs.push_back(limb);
        }
        std::optional<Model> model;
        try {
            model.emplace(robot);
        } catch (const Error&) {
            continue;
        }
        const Pose p0(0.3 * unit(rng), 0.05 * unit(rng), 0.05 * unit(rng));
        Data data(*model);
        if (!inverseDisplacement(*model, data, p0)) continue;
        const ActuatorVector u = data.u;
        AssemblyModes modes;
        ASSERT_TRUE(directKinematics(*model, data, u, modes).ok());
        if (modes.count < 6) continue;
        EXPECT_EQ(modes.count, 6) << type;
        expectRoundTrip(*model, u, modes, type + " six modes");
        const std::vector<Pose> found = bruteForce(*model, u, 72, 12);
        EXPECT_EQ(found.size(), 6U) << type;
        for (const Pose& p : found) EXPECT_TRUE(hasPose(modes, p, 1e-6)) << type;
        std::printf("%s: six real modes at attempt %d, the search finds %zu\n", type.c_str(), attempt, found.size());
        return;
    }
    ADD_FAILURE() << "no " << type << " with six real modes in the scan";
}

TEST(DirectKinematicsRobots, SixModes3RPR) { sixModes("RPR", 1, 7); }
TEST(DirectKinematicsRobots, SixModes3RRR) { sixModes("RRR", 0, 8); }

TEST(DirectKinematicsRobots, NoAssemblyIsZeroModes) {
    const Model model(io::exampleRobot("3-rrr"));
    ActuatorVector u = actuatorsAt(model, model.home);
    Data data(model);
    AssemblyModes modes;
    u(0) += 2.0;  // a crank turned far: still some poses, or none, but never a failure
    EXPECT_TRUE(directKinematics(model, data, u, modes).ok());
    expectRoundTrip(model, u, modes, "3-rrr turned crank");
    const Model rpr(io::exampleRobot("3-rpr"));
    Data rpr_data(rpr);
    ActuatorVector legs = actuatorsAt(rpr, rpr.home);
    legs(0) += 1.0;  // one leg a metre longer: no pose closes
    EXPECT_TRUE(directKinematics(rpr, rpr_data, legs, modes).ok());
    EXPECT_EQ(modes.count, 0);
    legs(1) = std::nan("");
    EXPECT_EQ(directKinematics(rpr, rpr_data, legs, modes).code, StatusCode::not_finite);
}

TEST(DirectKinematicsRobots, RedundantInconsistentActuatorsHaveNoMode) {
    const Model model(io::exampleRobot("4-rrr"));
    ActuatorVector u = actuatorsAt(model, model.home);
    Data data(model);
    AssemblyModes modes;
    u(3) += 1e-3;  // the fourth crank disagrees with the other three
    ASSERT_TRUE(directKinematics(model, data, u, modes).ok());
    EXPECT_EQ(modes.count, 0);
    ASSERT_TRUE(directKinematics(model, data, u, modes, {.tolerance = 1e-2}).ok());
    EXPECT_GE(modes.count, 1);
    for (const AssemblyMode& m : modes) EXPECT_GT(m.u_error, 1e-5);
}

// --- tracker ----------------------------------------------------------------------------

/// Follows the paper's trajectory 1 at 1 kHz from home: every step within round-off of the
/// pose u was computed at.
void trackTrajectory(const std::string& name) {
    const Model model(io::exampleRobot(name));
    const PoseTrajectory trajectory = paperTrajectory1();
    Data reference(model), data(model);
    Pose p = model.home;
    double worst = 0.0;
    int max_iterations = 0;
    for (int k = 0; k <= 1000; ++k) {
        Pose target, dp, ddp;
        trajectory.evaluate(1e-3 * k, target, dp, ddp);
        target += model.home;
        ASSERT_TRUE(inverseDisplacement(model, reference, target).ok()) << name << " k = " << k;
        TrackerReport report;
        const Status status = trackPose(model, data, reference.u, p, {}, &report);
        ASSERT_TRUE(status.ok()) << name << " k = " << k << ": " << describe(status, model);
        worst = std::max({worst, std::abs(p(0) - target(0)), (p.tail<2>() - target.tail<2>()).cwiseAbs().maxCoeff()});
        max_iterations = std::max(max_iterations, report.iterations);
    }
    EXPECT_LE(worst, 1e-12) << name;
    EXPECT_LE(max_iterations, 4) << name;
    std::printf("%s: tracker within %.1e of the trajectory, at most %d Newton steps\n", name.c_str(), worst,
                max_iterations);
}

TEST(DirectKinematicsRobots, TrackerFollowsThePaperTrajectory) {
    for (const std::string& name : io::exampleRobotNames()) trackTrajectory(name);
}

/// The pose of trajectory 1 (about home) at t.
Pose trajectoryPose(const Model& model, double t) {
    Pose p, dp, ddp;
    paperTrajectory1().evaluate(t, p, dp, ddp);
    return p + model.home;
}

TEST(DirectKinematicsRobots, TrackerStopsAfterARoundOffStepWithoutAnotherEvaluation) {
    // one Newton step of 1e-10 from the exact pose leaves round-off: the tracker verifies it by
    // inverse displacement without evaluating the equations again (one step, not two)
    for (const std::string& name : io::exampleRobotNames()) {
        const Model model(io::exampleRobot(name));
        Data data(model);
        const Pose target = trajectoryPose(model, 0.013);
        const ActuatorVector u = actuatorsAt(model, target);
        Pose p = target + Pose(1e-10, -1e-10 * model.length_scale, 1e-10 * model.length_scale);
        TrackerReport report;
        ASSERT_TRUE(trackPose(model, data, u, p, {}, &report).ok()) << name;
        EXPECT_EQ(report.iterations, 1) << name;
        EXPECT_LE(report.residual, 1e-13) << name;
        EXPECT_LE(std::abs(p(0) - target(0)), 1e-14) << name;
        EXPECT_LE((p.tail<2>() - target.tail<2>()).cwiseAbs().maxCoeff(), 1e-14 * model.length_scale) << name;
        // from 1e-3 away it iterates to the same pose
        p = target + Pose(1e-3, 1e-3 * model.length_scale, 0.0);
        ASSERT_TRUE(trackPose(model, data, u, p, {}, &report).ok()) << name;
        EXPECT_GE(report.iterations, 2) << name;
        EXPECT_LE((p - target).cwiseAbs().maxCoeff(), 1e-14 * std::max(1.0, model.length_scale)) << name;
    }
}

TEST(DirectKinematicsRobots, PoseTrackerTakesOneNewtonStepPerSampleAt10kHz) {
    // the extrapolated start is within h^4 |d4p/dt4| ~ 1e-11 of the pose: one step each, to
    // round-off, where trackPose from the previous pose takes two
    for (const std::string& name : io::exampleRobotNames()) {
        const Model model(io::exampleRobot(name));
        Data data(model);
        PoseTracker tracker(trajectoryPose(model, 0.0));
        Pose previous = tracker.pose();
        double worst = 0.0;
        int most = 0, most_from_previous = 0;
        for (int k = 1; k <= 200; ++k) {
            const Pose target = trajectoryPose(model, 1e-4 * k);
            const ActuatorVector u = actuatorsAt(model, target);
            TrackerReport report;
            ASSERT_TRUE(tracker.step(model, data, u, {}, &report).ok()) << name << " k = " << k;
            if (k > 4) most = std::max(most, report.iterations);
            worst = std::max(worst, (tracker.pose() - target).cwiseAbs().maxCoeff());
            ASSERT_TRUE(trackPose(model, data, u, previous, {}, &report).ok()) << name << " k = " << k;
            most_from_previous = std::max(most_from_previous, report.iterations);
        }
        EXPECT_EQ(most, 1) << name;
        EXPECT_GE(most_from_previous, 2) << name;
        EXPECT_LE(worst, 1e-13) << name;
    }
}

TEST(DirectKinematicsRobots, PoseTrackerRecoversFromAJumpAndSaysWhenTheModeIsLost) {
    const Model model(io::exampleRobot("3-rrr"));
    Data data(model);
    PoseTracker tracker(trajectoryPose(model, 0.0));
    for (int k = 1; k <= 5; ++k)
        ASSERT_TRUE(tracker.step(model, data, actuatorsAt(model, trajectoryPose(model, 1e-4 * k))).ok());
    // u jumps 10 ms ahead, far from the extrapolation: still tracked
    const Pose ahead = trajectoryPose(model, 0.0105);
    ASSERT_TRUE(tracker.step(model, data, actuatorsAt(model, ahead)).ok());
    EXPECT_LE((tracker.pose() - ahead).cwiseAbs().maxCoeff(), 1e-13);
    // far beyond the workspace: not tracked, the last pose kept
    ActuatorVector u = actuatorsAt(model, ahead);
    u(0) += 1.0;
    const Status lost = tracker.step(model, data, u);
    EXPECT_FALSE(lost.ok());
    EXPECT_NE(lost.code, StatusCode::not_finite);
    EXPECT_LE((tracker.pose() - ahead).cwiseAbs().maxCoeff(), 1e-13);
    EXPECT_EQ(tracker.prediction(), tracker.pose()) << "the motion is forgotten after a failure";
}

TEST(DirectKinematicsRobots, TrackerReportsWhatStopsIt) {
    const Model model(io::exampleRobot("3-rpr"));
    Data data(model);
    ActuatorVector u = actuatorsAt(model, model.home);
    Pose p = model.home;
    u(0) += 0.5;  // far beyond the workspace
    const Status status = trackPose(model, data, u, p);
    EXPECT_FALSE(status.ok());
    EXPECT_TRUE(status.code == StatusCode::assembly_mode_lost || status.code == StatusCode::workspace_edge ||
                status.code == StatusCode::unreachable || status.code == StatusCode::singular_limb ||
                status.code == StatusCode::singular_actuation)
        << describe(status, model);
    EXPECT_TRUE(p.allFinite());
    u(0) = std::nan("");
    EXPECT_EQ(trackPose(model, data, u, p).code, StatusCode::not_finite);
}

// What stops the tracker is described for the robot at hand: its limb and the condition number
// or residual, not the 3-PRR's rail distance d_j^M.
TEST(DirectKinematicsRobots, TrackerFailuresAreDescribedByLimb) {
    const Model model(io::exampleRobot("3-rpr"));
    const std::string edge = describe(Status{StatusCode::workspace_edge, 1, 5000.0}, model);
    EXPECT_NE(edge.find("edge of the workspace: limb 2"), std::string::npos) << edge;
    EXPECT_NE(edge.find("condition number 5000"), std::string::npos) << edge;
    EXPECT_EQ(edge.find("d_"), std::string::npos) << edge;
    const std::string lost = describe(Status{StatusCode::assembly_mode_lost, 0, 1e-3}, model);
    EXPECT_NE(lost.find("lost the assembly mode (limb 1, scaled residual 0.001)"), std::string::npos) << lost;
}

TEST(DirectKinematicsRobots, AllocationFree) {
    for (const std::string& name : io::exampleRobotNames()) {
        const Model model(io::exampleRobot(name));
        Data data(model);
        const ActuatorVector u = actuatorsAt(model, model.home + Pose(0.01, 0.001, -0.001));
        AssemblyModes modes;
        Pose p = model.home;
        const long before = allocationCount();
        const Status all = directKinematics(model, data, u, modes);
        const Status tracked = trackPose(model, data, u, p);
        PoseTracker tracker(model.home);
        const Status stepped = tracker.step(model, data, u);
        const long after = allocationCount();
        EXPECT_TRUE(all.ok() && tracked.ok() && stepped.ok()) << name;
        if (kCountsMalloc) {
            EXPECT_EQ(after - before, 0) << name;
        }
    }
}

// --- the state from actuator values and rates ---------------------------------------------

/// Every example robot and random robots of every limb type: from u and du computed at a known
/// pose and rate near home (the working mode), stateFromActuators gives back that state; the
/// least-squares rate solve allocates nothing.
TEST(StateFromActuators, GivesBackTheStateOfItsActuatorValuesAndRates) {
    std::vector<std::pair<std::string, Model>> robots;
    for (const std::string& name : io::exampleRobotNames()) robots.emplace_back(name, Model(io::exampleRobot(name)));
    std::mt19937 rng(11);
    for (const std::string& type : limbTypes()) {
        for (int tries = 0; tries < 50; ++tries) {
            if (auto robot = randomRobot(RandomRobotSpec{{type, type, type}, 3, false, false}, rng)) {
                robots.emplace_back("random-" + type, Model(*robot));
                break;
            }
        }
    }
    int checked = 0;
    for (const auto& [name, model] : robots) {
        Data data(model);
        const Pose p = model.home + Pose(0.004, 0.02 * model.length_scale, -0.01 * model.length_scale);
        const Twist dp(0.3, -0.05, 0.08);
        if (!inverseDisplacement(model, data, p).ok() || !velocityFromPlatformTwist(model, data, dp).ok()) continue;
        const ActuatorVector u = data.u;
        const ActuatorVector du = data.du;
        ActuatorStart start;
        const Status status = stateFromActuators(model, data, u, du, 0, start);
        ASSERT_TRUE(status.ok()) << name << ": " << describe(status, model);
        EXPECT_LT((start.p - p).cwiseAbs().maxCoeff(), 1e-11) << name;
        EXPECT_LT((start.dp - dp).cwiseAbs().maxCoeff(), 1e-9) << name;
        EXPECT_TRUE(start.nearest_home) << name;
        EXPECT_GE(start.working, 1) << name;
        EXPECT_GE(start.modes, start.working) << name;
        EXPECT_LT((data.du - du).cwiseAbs().maxCoeff(), 1e-12) << name << ": the velocity stage is left at the state";
        // at rest without rates, and the mode chosen by number is the same one
        ActuatorStart by_number;
        ASSERT_TRUE(stateFromActuators(model, data, u, ActuatorVector(), start.mode, by_number).ok()) << name;
        EXPECT_EQ(by_number.p, start.p) << name;
        EXPECT_EQ(by_number.dp, Twist::Zero()) << name;
        EXPECT_FALSE(by_number.nearest_home) << name;
        // one mode more than there are
        const Status missing = stateFromActuators(model, data, u, du, start.working + 1, by_number);
        EXPECT_EQ(missing.code, StatusCode::assembly_mode_missing) << name;
        EXPECT_EQ(missing.value, start.working) << name;
        EXPECT_NE(describe(missing, model).find("fewer than the one asked for"), std::string::npos);
        // the rate solve alone, allocation-free
        Twist solved;
        ASSERT_TRUE(inverseDisplacement(model, data, p).ok());
        const long before = allocationCount();
        const Status rates = velocityFromActuatorRatesLeastSquares(model, data, du, solved);
        const long after = allocationCount();
        EXPECT_TRUE(rates.ok()) << name;
        EXPECT_LT((solved - dp).cwiseAbs().maxCoeff(), 1e-9) << name;
        if (kCountsMalloc) {
            EXPECT_EQ(after - before, 0) << name;
        }
        ++checked;
    }
    EXPECT_GE(checked, 8);
}

/// A redundant robot's rates that no platform motion has are refused with the residual; its
/// consistent rates are solved exactly.
TEST(StateFromActuators, RedundantRobotRefusesInconsistentRates) {
    const Model model(io::exampleRobot("4-rrr"));
    Data data(model);
    const Twist dp(0.2, 0.01, -0.02);
    ASSERT_TRUE(inverseDisplacement(model, data, model.home).ok());
    ASSERT_TRUE(velocityFromPlatformTwist(model, data, dp).ok());
    const ActuatorVector u = data.u;
    ActuatorVector du = data.du;
    ActuatorStart start;
    ASSERT_TRUE(stateFromActuators(model, data, u, du, 0, start).ok());
    EXPECT_LT((start.dp - dp).cwiseAbs().maxCoeff(), 1e-12);
    du(3) += 1e-3;
    const Status status = stateFromActuators(model, data, u, du, 0, start);
    EXPECT_EQ(status.code, StatusCode::inconsistent_rates);
    EXPECT_GT(status.value, 1e-4);
    EXPECT_LT(status.value, 1e-3);
    EXPECT_NE(describe(status, model).find("not the rates of any platform motion"), std::string::npos);
}

/// Actuator values no working mode has: assembly_mode_missing with value 0.
TEST(StateFromActuators, NoWorkingModeIsMissing) {
    const Model model(io::exampleRobot("3-rpr"));
    Data data(model);
    ActuatorVector u = actuatorsAt(model, model.home);
    u(0) += 1.0;  // one leg a metre longer: no pose closes
    ActuatorStart start;
    const Status status = stateFromActuators(model, data, u, ActuatorVector(), 0, start);
    EXPECT_EQ(status.code, StatusCode::assembly_mode_missing);
    EXPECT_EQ(status.value, 0.0);
    EXPECT_NE(describe(status, model).find("cannot start there"), std::string::npos);
}

}  // namespace
}  // namespace nocdyn::test
