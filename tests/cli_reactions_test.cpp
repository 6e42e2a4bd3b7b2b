// nocdyn inverse-dynamics --reactions, simulate --reactions, pose --json and nocdyn loads: the
// columns after the others, equal to the library's reactions at the same samples and balancing
// the platform; the static pose's reactions carry the weight; the design loads equal the peaks
// and RMS of those columns; bad input gets the inverse dynamics' errors.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_support.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kRobot = std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rrr.yaml";
constexpr double kRounding = 1e-12;  // of the sample's largest reaction

fs::path scratch() { return freshScratchDirectory("nocdyn_cli_reactions_test"); }

/// An example robot file with gravity along -y added (the examples have none), written to dir.
std::string withGravity(const fs::path& dir, const std::string& robot) {
    std::ifstream in(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml");
    std::stringstream text;
    text << in.rdbuf();
    const fs::path path = dir / (robot + "-gravity.yaml");
    std::ofstream(path) << "gravity: [0.0, -9.81]\n" << text.str();
    return path.string();
}

/// The largest |component| of every joint's reaction.
double peakReaction(const Model& model, const Reactions& r) {
    double peak = 0.0;
    for (int j = 0; j < model.limbs; ++j) {
        for (const Vector3& v : r.joint[static_cast<std::size_t>(j)]) peak = std::max(peak, v.cwiseAbs().maxCoeff());
    }
    return peak;
}

TEST(CliReactions, ColumnsFollowTheOthersAndEqualTheLibrarysReactions) {
    const fs::path dir = scratch();
    const CliResult r =
        runCli("inverse-dynamics --robot " + kRobot +
               " --trajectory paper1 --duration 0.05 --rate 1000 --reactions -o " + (dir / "id.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Table table = io::readCsvFile((dir / "id.csv").string());
    const Model model(io::loadRobotDescription(kRobot));
    const std::vector<std::string> first = tables::inverseDynamicsColumns(model.actuators);
    const std::vector<std::string> reactions = tables::reactionColumns(model.limbs);
    ASSERT_EQ(table.columns.size(), first.size() + reactions.size());
    for (std::size_t c = 0; c < first.size(); ++c) EXPECT_EQ(table.columns[c], first[c]);
    EXPECT_EQ(table.columns[first.size()], "limb1_j1_fx");
    EXPECT_EQ(table.columns.back(), "limb3_j3_m");
    ASSERT_EQ(table.rows.size(), 50U);
    Data data(model);
    Reactions expected;
    const PoseTrajectory trajectory = paperTrajectory1();
    for (std::size_t k = 0; k < table.rows.size(); k += 7) {
        Pose p, dp, ddp;
        trajectory.evaluate(table.rows[k][0], p, dp, ddp);
        ASSERT_TRUE(inverseDynamicsWithReactions(model, data, p, dp, ddp, expected).ok());
        double peak = 0.0;
        for (int j = 0; j < 3; ++j) {
            for (const Vector3& r : expected.joint[static_cast<std::size_t>(j)])
                peak = std::max(peak, r.cwiseAbs().maxCoeff());
        }
        for (int j = 0; j < 3; ++j) {
            for (int jk = 0; jk < 3; ++jk) {
                for (int part = 0; part < 3; ++part) {
                    const std::size_t c = first.size() + static_cast<std::size_t>(9 * j + 3 * jk + part);
                    // the CLI applies the full path's tau, the library call its own (the same to rounding)
                    EXPECT_NEAR(table.rows[k][c],
                                expected.joint[static_cast<std::size_t>(j)][static_cast<std::size_t>(jk)](part),
                                kRounding * peak)
                        << table.columns[c] << " at t = " << table.rows[k][0];
                }
            }
        }
    }
}

TEST(CliReactions, SimulateColumnsAreTheLibrarysReactionsAndBalanceThePlatform) {
    const fs::path dir = scratch();
    const std::string robot = withGravity(dir, "3-rrr");
    // the forces of trajectory 1 under gravity, fed back to the simulator
    ASSERT_EQ(runCli("inverse-dynamics --robot " + robot + " --trajectory paper1 --duration 0.05 --rate 1000 -o " +
                     (dir / "id.csv").string())
                  .exit_code,
              0);
    const CliResult r = runCli("simulate --robot " + robot + " --forces " + (dir / "id.csv").string() +
                               " --rate 1000 --reactions -o " + (dir / "sim.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Table table = io::readCsvFile((dir / "sim.csv").string());
    const Model model(io::loadRobotDescription(robot));
    const std::vector<std::string> reactions = tables::reactionColumns(model.limbs);
    const std::size_t first = 4 + 3 * static_cast<std::size_t>(model.actuators) + 1;  // t,x,y,theta,u,du,tau,kinetic
    ASSERT_EQ(table.columns.size(), first + reactions.size());
    EXPECT_EQ(table.columns[first - 1], "kinetic");
    for (std::size_t c = 0; c < reactions.size(); ++c) EXPECT_EQ(table.columns[first + c], reactions[c]);
    ASSERT_EQ(table.rows.size(), 50U);
    Data data(model);
    Reactions expected;
    for (const std::size_t k : {0UL, 13UL, 31UL, 49UL}) {
        const auto& row = table.rows[k];
        const Pose p(row[table.column("theta")], row[table.column("x")], row[table.column("y")]);
        ActuatorVector du(model.actuators), tau(model.actuators);
        for (int a = 0; a < model.actuators; ++a) {
            du(a) = row[table.column("du" + std::to_string(a + 1))];
            tau(a) = row[table.column("tau" + std::to_string(a + 1))];
        }
        // the state written: dp/dt from du = A S(c) dp/dt (eq. 5), then the forward dynamics
        ASSERT_TRUE(inverseDisplacement(model, data, p).ok());
        ASSERT_TRUE(velocityFromPlatformTwist(model, data, Twist::Zero()).ok());
        Matrix3 S;
        S << 1.0, 0.0, 0.0, p(2), 1.0, 0.0, -p(1), 0.0, 1.0;
        const Matrix3 A_p = Matrix3(data.A) * S;
        const Twist dp = A_p.partialPivLu().solve(Vector3(du));
        ASSERT_TRUE(forwardDynamics(model, data, p, dp, tau).ok());
        jointReactions(model, data, expected);
        const double peak = peakReaction(model, expected);
        ASSERT_GT(peak, 1.0) << "gravity alone loads every joint by about a newton";
        Vector2 force = Vector2::Zero();
        double moment = 0.0;  // about O
        for (int j = 0; j < model.limbs; ++j) {
            const auto jj = static_cast<std::size_t>(j);
            for (std::size_t jk = 0; jk < 3; ++jk) {
                for (int part = 0; part < 3; ++part) {
                    const std::size_t c = first + 9 * jj + 3 * jk + static_cast<std::size_t>(part);
                    EXPECT_NEAR(row[c], expected.joint[jj][jk](part), 1e-9 * peak)
                        << table.columns[c] << " at t = " << row[0];
                }
            }
            // the platform pivot (passive R, no friction): a force at the axis r, s_3 = [1; -E r]
            const Vector2 f(row[first + 9 * jj + 6], row[first + 9 * jj + 7]);
            const Twist& s3 = data.limb[jj].s[2];
            const Vector2 axis(-s3(2), s3(1));
            force += f;
            moment += axis.x() * f.y() - axis.y() * f.x();
        }
        // the platform's Newton-Euler balance: the limbs' forces give m_P (a_P - g) and I_P dw
        // (xi_P, its rate: the platform's twist referred to O; v_P = v_O + w E x_P, a_P its rate)
        const auto perp = [](const Vector2& v) { return Vector2(-v.y(), v.x()); };
        const Vector2 v_P = data.xi_P.tail<2>() + data.xi_P(0) * perp(data.x_P);
        const Vector2 a_P = data.xi_P_dot.tail<2>() + data.xi_P_dot(0) * perp(data.x_P) + data.xi_P(0) * perp(v_P);
        const Vector2 needed = model.platform_M.mass * (a_P - model.gravity);
        EXPECT_NEAR(force.x(), needed.x(), 1e-9 * peak) << "t = " << row[0];
        EXPECT_NEAR(force.y(), needed.y(), 1e-9 * peak) << "t = " << row[0];
        const double moment_needed =
            model.platform_M.inertia * data.xi_P_dot(0) + data.x_P.x() * needed.y() - data.x_P.y() * needed.x();
        EXPECT_NEAR(moment, moment_needed, 1e-9 * peak * model.length_scale) << "t = " << row[0];
    }
}

TEST(CliReactions, SimulateWithoutReactionsKeepsItsColumns) {
    const fs::path dir = scratch();
    std::ofstream(dir / "tau.csv") << "t,tau1,tau2,tau3\n0,0.1,0,0\n0.01,0.1,0,0\n";
    const CliResult r = runCli("simulate --robot " + kRobot + " --forces " + (dir / "tau.csv").string() +
                               " --rate 1000 -o " + (dir / "sim.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Table table = io::readCsvFile((dir / "sim.csv").string());
    EXPECT_EQ(table.columns.size(), 4U + 9U + 1U);
    EXPECT_EQ(table.columns.back(), "kinetic");
}

TEST(CliReactions, PoseJsonListsTheStaticReactionsThatCarryTheWeight) {
    const fs::path dir = scratch();
    for (const char* name : {"3-rrr", "3-rpr"}) {
        const std::string robot = withGravity(dir, name);
        const Model model(io::loadRobotDescription(robot));
        const Pose p(0.02, 0.001, -0.003);
        const Pose at = p + model.home;
        const CliResult r = runCli("pose " + std::to_string(at(1)) + " " + std::to_string(at(2)) + " " +
                                   std::to_string(at(0)) + " --json --robot " + robot);  // x, y, theta
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const nlohmann::json out = nlohmann::json::parse(r.out);
        const Pose pose(out["pose"]["theta"].get<double>(), out["pose"]["x"].get<double>(),
                        out["pose"]["y"].get<double>());
        Data data(model);
        Reactions expected;
        ASSERT_TRUE(inverseDynamicsWithReactions(model, data, pose, Twist::Zero(), Twist::Zero(), expected).ok());
        const double peak = peakReaction(model, expected);
        ASSERT_EQ(out["reactions"].size(), 3U * static_cast<std::size_t>(model.limbs)) << name;
        Vector2 base = Vector2::Zero(), pivots = Vector2::Zero();
        for (const auto& joint : out["reactions"]) {
            const auto j = joint["limb"].get<std::size_t>() - 1, k = joint["joint"].get<std::size_t>() - 1;
            const Vector3 got(joint["fx"].get<double>(), joint["fy"].get<double>(), joint["m"].get<double>());
            EXPECT_LT((got - expected.joint[j][k]).cwiseAbs().maxCoeff(), 1e-12 * peak) << name << " " << joint;
            EXPECT_EQ(joint["type"], model.limb[j].type[k] == JointType::revolute ? "R" : "P");
            if (model.limb[j].type[k] == JointType::revolute) {
                EXPECT_EQ(got(2), 0.0);
            }
            if (k == 0) base += got.head<2>();
            if (k == 2) pivots += got.head<2>();
        }
        double mass = model.platform_M.mass;
        for (int j = 0; j < model.limbs; ++j)
            mass +=
                model.limb[static_cast<std::size_t>(j)].M[0].mass + model.limb[static_cast<std::size_t>(j)].M[1].mass;
        // the platform pivots carry the platform's weight
        EXPECT_NEAR(pivots.x(), 0.0, 1e-12 * peak) << name;
        EXPECT_NEAR(pivots.y(), 9.81 * model.platform_M.mass, 1e-12 * peak) << name;
        if (std::string(name) == "3-rrr") {
            // the base pivots (R: the whole force, the motor gives only a torque) carry all of it
            EXPECT_NEAR(base.x(), 0.0, 1e-12 * peak);
            EXPECT_NEAR(base.y(), 9.81 * mass, 1e-12 * peak);
        }
        ASSERT_EQ(out["tau"].size(), static_cast<std::size_t>(model.actuators));
        for (int a = 0; a < model.actuators; ++a) {
            // the command's full path and the lean one here: the same to rounding
            EXPECT_NEAR(out["tau"][static_cast<std::size_t>(a)].get<double>(), data.tau(a),
                        1e-12 * (1.0 + data.tau.cwiseAbs().maxCoeff()));
        }
    }
}

TEST(CliReactions, PoseTextShowsTheReactionsAndAnUnreachablePoseIsTheSameError) {
    const CliResult r = runCli("pose 0 0 0 --robot " + kRobot);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("joint reactions"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("3     3 R"), std::string::npos) << r.out;
    const CliResult far = runCli("pose 0.5 0 0 --json --robot " + kRobot);
    EXPECT_EQ(far.exit_code, 1);
    EXPECT_NE(far.err.find("out of reach"), std::string::npos) << far.err;
}

TEST(CliLoads, PeaksAndRmsEqualThoseOfTheReactionColumns) {
    const fs::path dir = scratch();
    const std::string motion = " --robot " + kRobot + " --trajectory paper2 --duration 0.1 --rate 2000";
    ASSERT_EQ(runCli("inverse-dynamics" + motion + " --reactions -o " + (dir / "id.csv").string()).exit_code, 0);
    const CliResult r = runCli("loads" + motion + " -o " + (dir / "loads.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("largest: limb "), std::string::npos) << r.out;
    const io::Table id = io::readCsvFile((dir / "id.csv").string());
    const io::Table loads = io::readCsvFile((dir / "loads.csv").string());
    ASSERT_EQ(loads.rows.size(), 9U);
    for (const auto& row : loads.rows) {
        const auto j = static_cast<int>(row[loads.column("limb")]), k = static_cast<int>(row[loads.column("joint")]);
        const std::string stem = "limb" + std::to_string(j) + "_j" + std::to_string(k) + "_";
        double peak = 0.0, t_peak = 0.0, sum = 0.0;
        for (const auto& s : id.rows) {
            const double f = std::hypot(s[id.column(stem + "fx")], s[id.column(stem + "fy")]);
            if (f > peak) {
                peak = f;
                t_peak = s[0];
            }
            sum += f * f;
        }
        ASSERT_GT(peak, 1.0) << stem;
        EXPECT_NEAR(row[loads.column("peak_force")], peak, 1e-12 * peak) << stem;
        EXPECT_EQ(row[loads.column("peak_force_t")], t_peak) << stem;
        EXPECT_NEAR(row[loads.column("rms_force")], std::sqrt(sum / static_cast<double>(id.rows.size())), 1e-12 * peak)
            << stem;
        EXPECT_EQ(row[loads.column("peak_moment")], 0.0) << stem << ": an R joint's reaction has no couple";
    }
}

TEST(CliLoads, EnvelopeLoadsCoverEveryJointAndDrawTheWorstPose) {
    const fs::path dir = scratch();
    const CliResult r = runCli("loads --envelope --points 2 --robot " + kRobot + " -o " + (dir / "env.csv").string() +
                               " --figure " + (dir / "worst").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("over the operating envelope's motions"), std::string::npos) << r.out;
    const io::Table env = io::readCsvFile((dir / "env.csv").string());
    ASSERT_EQ(env.rows.size(), 9U);
    for (const auto& row : env.rows) {
        EXPECT_GT(row[env.column("peak_force")], 0.0);
        EXPECT_GE(row[env.column("peak_force_frequency")], 1.0);
    }
    EXPECT_TRUE(fs::is_regular_file(dir / "worst.png"));
    EXPECT_TRUE(fs::is_regular_file(dir / "worst.svg"));
}

TEST(CliLoads, TheWorstPoseFigureStatesItsArrowScaleAndDrawsAReferenceArrow) {
    const fs::path dir = scratch();
    const CliResult r = runCli("loads --robot " + kRobot + " --trajectory paper1 --figure " + (dir / "worst").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_NE(r.out.find("largest: limb 2 joint 1, 36.53 N"), std::string::npos) << r.out;
    // the largest force drawn at most a third of the drawing's size (its farthest joint, 200 mm
    // from the origin): 36.53 N * 10 mm / 66.7 mm = 5.5 N, rounded up to 10 N per 10 mm; the
    // reference is the round force below the largest, 20 N
    const std::string svg = readWhole(dir / "worst.svg");
    EXPECT_NE(svg.find("arrows: 10 mm = 10 N"), std::string::npos);
    EXPECT_NE(svg.find("reference arrow (lower left): 20 N"), std::string::npos);
    EXPECT_NE(svg.find("reaction force (largest 36.53 N)"), std::string::npos);
}

TEST(CliLoads, UnreachableTrajectoryIsTheInverseDynamicsErrorAndNoFile) {
    const fs::path dir = scratch();
    std::ofstream(dir / "far.yaml") << "name: far\nx:\n  offset: 0.5\n";
    const CliResult id = runCli("inverse-dynamics --robot " + kRobot + " --trajectory " + (dir / "far.yaml").string() +
                                " --duration 0.01 --reactions -o " + (dir / "id.csv").string());
    const CliResult loads = runCli("loads --robot " + kRobot + " --trajectory " + (dir / "far.yaml").string() +
                                   " --duration 0.01 -o " + (dir / "loads.csv").string());
    EXPECT_EQ(id.exit_code, 1);
    EXPECT_EQ(loads.exit_code, 1);
    EXPECT_NE(loads.err.find("t = 0 s"), std::string::npos) << loads.err;
    EXPECT_EQ(loads.err.substr(loads.err.find("t = ")), id.err.substr(id.err.find("t = "))) << loads.err;
    EXPECT_FALSE(fs::exists(dir / "loads.csv"));
    EXPECT_FALSE(fs::exists(dir / "id.csv"));
}

}  // namespace
}  // namespace nocdyn::test
