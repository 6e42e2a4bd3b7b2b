// Two-DOF planar robots (motion: translation, pose [x, y] of a point tool) through the commands of
// forces and files: `nocdyn inverse-dynamics`, `loads`, `validate` and `convert` on the shipped
// five-bar and biglide.
//   - inverse-dynamics writes t,x,y,u1,u2,du1,du2,ddu1,ddu2,tau1,tau2,kinetic, and its numbers
//     equal the core's inverse dynamics at the pose [home(0), x, y] of the same trajectory, from
//     a trajectory file keyed x, y (harmonics: the shipped five-bar figure eight, within the
//     robot's workspace and limits) and from samples t,x,y (CSV); a theta that moves is refused.
//   - loads: the peak and RMS reaction forces equal those of the core's reactions at the same
//     samples, and those reactions balance every body (Newton-Euler, the bodies' accelerations
//     from central differences of the position and velocity stages: independent of the NOC's T_i).
//   - validate: the forces agree with Simbody's and MuJoCo's to 1e-9 of the peak.
//   - convert: the general form it writes loads back to the same model (the same forces).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/reactions.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = std::numbers::pi;
// The command's numbers against the core's at the same samples [N m, N, rad, m and their rates].
constexpr double kSame = 1e-12;
// Newton-Euler balance with fourth-order central differences (h = 0.5 ms), relative to the
// largest transmitted wrench.
constexpr double kBalance = 1e-7;  // measured: 1.4e-8

std::string source(const std::string& relative) { return std::string(NOCDYN_SOURCE_DIR) + "/" + relative; }
std::string robotPath(const std::string& name) { return source("robots/" + name + ".yaml"); }
const std::string kFigureEight = source("trajectories/five-bar-figure-eight.yaml");

/// Samples t, x, y of the biglide's tool about its home [0, 0.2] m every 1 ms over 0.2 s (CSV).
std::string biglideSamples(const fs::path& dir) {
    const fs::path path = dir / "biglide-samples.csv";
    std::ofstream out(path);
    out << "t,x,y\n";
    char line[200];
    for (int k = 0; k <= 200; ++k) {
        const double t = 1e-3 * k;
        std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", t, 0.03 * std::sin(2.0 * kPi * 3.0 * t),
                      0.2 + 0.02 * (1.0 - std::cos(2.0 * kPi * 3.0 * t)));
        out << line;
    }
    return path.string();
}

/// The CSV of `nocdyn inverse-dynamics` against the core at each row's time.
void expectInverseDynamicsOfTheCore(const std::string& robot, const std::string& trajectory_path,
                                    const std::string& options, const fs::path& dir) {
    const std::string csv = (dir / "forces.csv").string();
    const CliResult r = runCli("inverse-dynamics --robot " + robotPath(robot) + " --trajectory " + trajectory_path +
                               " " + options + " -o " + csv);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Table table = io::readCsvFile(csv);
    const std::vector<std::string> columns{"t",   "x",    "y",    "u1",   "u2",   "du1",
                                           "du2", "ddu1", "ddu2", "tau1", "tau2", "kinetic"};
    ASSERT_EQ(table.columns, columns) << robot;
    const Model model(io::loadRobotDescription(robotPath(robot)));
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(trajectory_path);
    Data data(model);
    double peak = 0.0, largest = 0.0;
    for (const auto& row : table.rows) {
        Pose p, dp, ddp;
        trajectory.evaluate(row[0], p, dp, ddp);
        EXPECT_EQ(row[1], p(1));
        EXPECT_EQ(row[2], p(2));
        // the core's pose of the task coordinates [x, y]: [home(0), x, y], rates [0, dx, dy]
        const TaskVector p_task = Eigen::Vector2d(p(1), p(2)), dp_task = Eigen::Vector2d(dp(1), dp(2)),
                         ddp_task = Eigen::Vector2d(ddp(1), ddp(2));
        const Status status = inverseDynamics(model, data, poseOfTask(model, p_task), rateOfTask(model, dp_task),
                                              rateOfTask(model, ddp_task));
        ASSERT_TRUE(status.ok()) << describe(status, model);
        for (int a = 0; a < 2; ++a) {
            EXPECT_NEAR(row[3 + a], data.u(a), kSame);
            EXPECT_NEAR(row[5 + a], data.du(a), kSame);
            EXPECT_NEAR(row[7 + a], data.ddu(a), kSame);
            EXPECT_NEAR(row[9 + a], data.tau(a), kSame) << robot << " t = " << row[0];
            peak = std::max(peak, std::abs(data.tau(a)));
            largest = std::max(largest, std::abs(row[9 + a] - data.tau(a)));
        }
    }
    std::printf("%s: %zu samples, peak |tau| %.4g, largest |tau_cli - tau_core| %.3g\n", robot.c_str(),
                table.rows.size(), peak, largest);
    EXPECT_GT(peak, 0.05) << "the motion must load the actuators";
}

TEST(TwoDofForcesCli, InverseDynamicsOfTheFigureEightEqualsTheCore) {
    const fs::path dir = freshScratchDirectory("twodof_forces_cli");
    // the shipped figure eight: within the workspace and every limit (no --allow-limits), its
    // duration from the file
    expectInverseDynamicsOfTheCore("five-bar", kFigureEight, "--rate 400", dir);
    const io::Table table = io::readCsvFile(dir / "forces.csv");
    EXPECT_EQ(table.rows.size(), 200u);  // 0.5 s at 400 Hz
    // within the workspace with a margin: every 0.5 ms, each limb and the actuation well
    // conditioned (far from both singularity types), every joint and effort limit kept
    const Model model(io::loadRobotDescription(robotPath("five-bar")));
    const PoseTrajectory eight = io::trajectoryByNameOrFile(kFigureEight);
    Data data(model);
    double worst_limb = 0.0, worst_actuation = 0.0;
    for (int k = 0; k <= 1000; ++k) {
        Pose p, dp, ddp;
        eight.evaluate(0.5e-3 * k, p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok()) << "t = " << 0.5e-3 * k;
        EXPECT_TRUE(checkJointLimits(model, data).ok()) << "t = " << 0.5e-3 * k;
        EXPECT_TRUE(checkEffort(model, data).ok()) << "t = " << 0.5e-3 * k;
        worst_actuation = std::max(worst_actuation, data.cond_A);
        for (int j = 0; j < model.limbs; ++j)
            worst_limb = std::max(worst_limb, data.limb[static_cast<std::size_t>(j)].cond);
    }
    std::printf("figure eight: largest condition number, limbs %.4g, actuation %.4g\n", worst_limb, worst_actuation);
    EXPECT_LT(worst_limb, 20.0);       // measured 9.4
    EXPECT_LT(worst_actuation, 10.0);  // measured 2.0
}

TEST(TwoDofForcesCli, InverseDynamicsOfSamplesTXYEqualsTheCore) {
    const fs::path dir = freshScratchDirectory("twodof_forces_cli");
    expectInverseDynamicsOfTheCore("biglide", biglideSamples(dir), "--rate 500", dir);
}

TEST(TwoDofForcesCli, ATrajectoryWhoseThetaMovesIsRefusedInOneLine) {
    const fs::path dir = freshScratchDirectory("twodof_forces_cli");
    const fs::path turning = dir / "turning.csv";
    std::ofstream(turning) << "t,x,y,theta\n0,0,0.35,0\n0.1,0,0.35,0.01\n0.2,0,0.35,0.02\n";
    for (const std::string& trajectory : {std::string("paper1"), turning.string()}) {
        for (const char* command : {"inverse-dynamics", "loads"}) {
            const CliResult r =
                runCli(std::string(command) + " --robot " + robotPath("five-bar") + " --trajectory " + trajectory);
            EXPECT_EQ(r.exit_code, 1) << command;
            EXPECT_NE(r.err.find("trajectory '" + trajectory + "': theta: not 0 throughout"), std::string::npos)
                << r.err;
            EXPECT_NE(r.err.find("key the trajectory x, y"), std::string::npos) << r.err;
            EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        }
    }
    // a theta column of zeros is no rotation: taken
    const fs::path still = dir / "still.csv";
    std::ofstream(still) << "t,x,y,theta\n0,0,0.35,0\n0.1,0.001,0.35,0\n0.2,0.002,0.35,0\n";
    const CliResult r = runCli("inverse-dynamics --robot " + robotPath("five-bar") + " --trajectory " + still.string() +
                               " --rate 100 -o " + (dir / "still-forces.csv").string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

/// The body's c.o.m. and angular rate (limb j, body b) at the trajectory's time t.
struct BodyMotion {
    Vector2 x;
    double omega = 0.0;
};
BodyMotion bodyAt(const Model& model, const PoseTrajectory& trajectory, double t, int j, int b) {
    Data data(model);
    Pose p, dp, ddp;
    trajectory.evaluate(t, p, dp, ddp);
    EXPECT_TRUE(inverseDisplacement(model, data, p).ok());
    EXPECT_TRUE(velocityFromPlatformTwist(model, data, dp).ok());
    const LimbData& limb = data.limb[static_cast<std::size_t>(j)];
    return {limb.x[static_cast<std::size_t>(b)], limb.xi[static_cast<std::size_t>(b)](0)};
}

/// [n_O; f]: the wrench a body of mass m, inertia I about its c.o.m. at x needs for the
/// acceleration a and the angular acceleration alpha, referred to O: f = m (a - g).
Wrench needed(double m, double I, const Vector2& x, const Vector2& a, double alpha, const Vector2& g) {
    const Vector2 f = m * (a - g);
    return {I * alpha + x.x() * f.y() - x.y() * f.x(), f.x(), f.y()};
}

/// Newton-Euler on every body of a two-DOF robot at time t: F_1 - F_2 = w_1, F_2 - F_3 = w_2 per
/// limb, sum_j F_3 = w_P (the point mass at the tool), and s_k^T F_k = the joint's effort.
/// Returns the largest body imbalance relative to the largest transmitted wrench.
double expectBalanced(const Model& model, const PoseTrajectory& trajectory, double t, const std::string& label) {
    Data data(model);
    Reactions reactions;
    Pose p, dp, ddp;
    trajectory.evaluate(t, p, dp, ddp);
    EXPECT_TRUE(inverseDynamicsWithReactions(model, data, p, dp, ddp, reactions).ok());
    constexpr double h = 5e-4;
    double worst = 0.0;
    double scale = 1.0;
    for (int j = 0; j < model.limbs; ++j)
        for (const Wrench& F : reactions.transmitted[static_cast<std::size_t>(j)])
            scale = std::max(scale, F.cwiseAbs().maxCoeff());
    Wrench platform = Wrench::Zero();
    int actuator = 0;
    for (int j = 0; j < model.limbs; ++j) {
        const auto& F = reactions.transmitted[static_cast<std::size_t>(j)];
        for (int b = 0; b < 2; ++b) {
            // fourth-order central differences: x'' and omega' from t - 2h .. t + 2h
            BodyMotion m[5];
            for (int i = 0; i < 5; ++i) m[i] = bodyAt(model, trajectory, t + (i - 2) * h, j, b);
            const Vector2 a = (-m[4].x + 16.0 * m[3].x - 30.0 * m[2].x + 16.0 * m[1].x - m[0].x) / (12.0 * h * h);
            const double alpha = (-m[4].omega + 8.0 * m[3].omega - 8.0 * m[1].omega + m[0].omega) / (12.0 * h);
            const InertiaDyad& M = model.limb[static_cast<std::size_t>(j)].M[static_cast<std::size_t>(b)];
            const Wrench w = needed(M.mass, M.inertia, m[2].x, a, alpha, model.gravity);
            const Wrench net = F[static_cast<std::size_t>(b)] - F[static_cast<std::size_t>(b) + 1];
            worst = std::max(worst, (net - w).cwiseAbs().maxCoeff() / scale);
            EXPECT_GT(w.cwiseAbs().maxCoeff(), 1e-3 * scale) << label << ": the body must be loaded";
            EXPECT_LT((net - w).cwiseAbs().maxCoeff(), kBalance * scale)
                << label << " t = " << t << ": " << model.limbName(j) << " body " << b + 1 << " not balanced";
        }
        for (int k = 0; k < 3; ++k) {
            const JointDescription& joint =
                model.description.limbs[static_cast<std::size_t>(j)].joints[static_cast<std::size_t>(k)];
            const double effort = joint.actuated ? data.tau(actuator++) : 0.0;  // no friction in the shipped robots
            const double passed = data.limb[static_cast<std::size_t>(j)].s[static_cast<std::size_t>(k)].dot(
                F[static_cast<std::size_t>(k)]);
            EXPECT_NEAR(passed, effort, 1e-12 * scale) << label << " limb " << j + 1 << " joint " << k + 1;
        }
        platform += F[2];
    }
    const Wrench w_P =
        needed(model.platform_M.mass, 0.0, data.x_P, Vector2(ddp(1), ddp(2)), 0.0, model.gravity);  // a point mass
    EXPECT_LT((platform - w_P).cwiseAbs().maxCoeff(), 1e-12 * scale) << label << " t = " << t << ": the tool";
    return worst;
}

TEST(TwoDofForcesCli, ReactionsBalanceEveryBodyOfTheFiveBarAndTheBiglide) {
    const PoseTrajectory eight = io::trajectoryByNameOrFile(kFigureEight);
    // the biglide's tool about its home [0, 0.2] m, smooth (harmonics) for the differences
    PoseTrajectory swing;
    swing.x.harmonics = {{0.03, 3.0, 0.0}};
    swing.y = {0.2, {{0.02, 6.0, 0.4}}};
    const Model five_bar(io::loadRobotDescription(robotPath("five-bar")));
    const Model biglide(io::loadRobotDescription(robotPath("biglide")));  // vertical: under gravity
    double worst = 0.0;
    for (const double t : {0.03, 0.11, 0.27, 0.41})
        worst = std::max(worst, expectBalanced(five_bar, eight, t, "five-bar"));
    for (const double t : {0.03, 0.09, 0.15}) worst = std::max(worst, expectBalanced(biglide, swing, t, "biglide"));
    std::printf("largest body imbalance: %.3g of the largest transmitted wrench\n", worst);
}

TEST(TwoDofForcesCli, LoadsAreThePeaksOfTheCoresReactions) {
    const fs::path dir = freshScratchDirectory("twodof_forces_cli");
    const std::string csv = (dir / "loads.csv").string();
    const CliResult r =
        runCli("loads --robot " + robotPath("five-bar") + " --trajectory " + kFigureEight + " --rate 400 -o " + csv);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("pose x, y [mm] "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("theta"), std::string::npos) << r.out;
    const io::Table table = io::readCsvFile(csv);
    const std::vector<std::string> columns{"limb",         "joint",     "peak_force",  "peak_force_t", "peak_force_x",
                                           "peak_force_y", "rms_force", "peak_moment", "peak_moment_t"};
    ASSERT_EQ(table.columns, columns);
    ASSERT_EQ(table.rows.size(), 6u);
    // the core's reactions at the command's samples t_k = k / 400, k = 0..199
    const Model model(io::loadRobotDescription(robotPath("five-bar")));
    const PoseTrajectory eight = io::trajectoryByNameOrFile(kFigureEight);
    Data data(model);
    Reactions reactions;
    double peak[2][3] = {}, peak_t[2][3] = {}, squares[2][3] = {};
    for (int k = 0; k < 200; ++k) {
        const double t = static_cast<double>(k) / 400.0;
        Pose p, dp, ddp;
        eight.evaluate(t, p, dp, ddp);
        ASSERT_TRUE(inverseDynamicsWithReactions(model, data, p, dp, ddp, reactions).ok());
        for (int j = 0; j < 2; ++j) {
            for (int i = 0; i < 3; ++i) {
                const double f =
                    reactions.joint[static_cast<std::size_t>(j)][static_cast<std::size_t>(i)].head<2>().norm();
                if (f > peak[j][i]) {
                    peak[j][i] = f;
                    peak_t[j][i] = t;
                }
                squares[j][i] += f * f;
            }
        }
    }
    for (const auto& row : table.rows) {
        const int j = static_cast<int>(row[0]) - 1, i = static_cast<int>(row[1]) - 1;
        EXPECT_NEAR(row[2], peak[j][i], kSame * peak[j][i]) << "limb " << j + 1 << " joint " << i + 1;
        EXPECT_EQ(row[3], peak_t[j][i]);
        Pose p, dp, ddp;
        eight.evaluate(peak_t[j][i], p, dp, ddp);
        EXPECT_EQ(row[4], p(1));
        EXPECT_EQ(row[5], p(2));
        EXPECT_NEAR(row[6], std::sqrt(squares[j][i] / 200.0), kSame * peak[j][i]);
        EXPECT_EQ(row[7], 0.0);  // R joints: no couple
        EXPECT_GT(row[2], 0.1);  // the motion loads every joint
    }
    // the envelope moves theta too: refused for a two-DOF robot
    const CliResult envelope = runCli("loads --robot " + robotPath("five-bar") + " --envelope");
    EXPECT_EQ(envelope.exit_code, 1);
    EXPECT_NE(envelope.err.find("--envelope: not for a two-DOF robot"), std::string::npos) << envelope.err;
}

TEST(TwoDofForcesCli, ConvertWritesAFileThatLoadsBackToTheSameModel) {
    const fs::path dir = freshScratchDirectory("twodof_forces_cli");
    const PoseTrajectory eight = io::trajectoryByNameOrFile(kFigureEight);
    for (const std::string name : {"five-bar", "biglide"}) {
        const std::string out = (dir / (name + "-general.yaml")).string();
        const CliResult r = runCli("convert --robot " + robotPath(name) + " -o " + out);
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_NE(readWhole(out).find("motion: translation"), std::string::npos);
        const Model original(io::loadRobotDescription(robotPath(name)));
        const Model back(io::loadRobotDescription(out));
        EXPECT_EQ(back.task_dimension, 2);
        EXPECT_EQ(back.home, original.home);
        EXPECT_EQ(back.gravity, original.gravity);
        EXPECT_EQ(back.platform_M.mass, original.platform_M.mass);
        Data a(original), b(back);
        // the figure eight moved to the robot's home: the same forces from both files
        for (const double t : {0.0, 0.07, 0.19, 0.33}) {
            Pose p, dp, ddp;
            eight.evaluate(t, p, dp, ddp);
            p(1) += original.home(1);
            p(2) += original.home(2) - 0.32;
            ASSERT_TRUE(inverseDynamics(original, a, p, dp, ddp).ok()) << name;
            ASSERT_TRUE(inverseDynamics(back, b, p, dp, ddp).ok()) << name;
            EXPECT_EQ(a.tau, b.tau) << name << " t = " << t;
            EXPECT_EQ(a.u, b.u) << name << " t = " << t;
        }
    }
}

#ifdef NOCDYN_TEST_ENGINES
TEST(TwoDofForcesCli, ValidateAgreesWithSimbodyAndMujoco) {
    const fs::path dir = freshScratchDirectory("twodof_forces_cli");
    const std::string csv = (dir / "validate.csv").string();
    const CliResult r =
        runCli("validate --robot " + robotPath("five-bar") + " --trajectory " + kFigureEight + " --rate 100 -o " + csv);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("| Simbody | 2 |"), std::string::npos) << r.err;
    const io::Table table = io::readCsvFile(csv);
    ASSERT_EQ(table.rows.size(), 50u);
    double peak = 0.0, simbody = 0.0, mujoco = 0.0;
    for (const auto& row : table.rows) {
        for (const char* a : {"1", "2"}) {
            peak = std::max(peak, std::abs(row[table.column(std::string("tau") + a)]));
            simbody = std::max(simbody, std::abs(row[table.column(std::string("simbody_dtau") + a)]));
            mujoco = std::max(mujoco, std::abs(row[table.column(std::string("mujoco_dtau") + a)]));
        }
    }
    std::printf("validate five-bar: peak |tau| %.4g, Simbody %.3g, MuJoCo %.3g of it\n", peak, simbody / peak,
                mujoco / peak);
    EXPECT_LT(simbody, 1e-9 * peak);
    EXPECT_LT(mujoco, 1e-9 * peak);
    const CliResult theta = runCli("validate --robot " + robotPath("five-bar") + " --trajectory paper1");
    EXPECT_EQ(theta.exit_code, 1);
    EXPECT_NE(theta.err.find("theta: not 0 throughout"), std::string::npos) << theta.err;
}
#endif

}  // namespace
}  // namespace nocdyn::test
