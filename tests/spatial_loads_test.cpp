// `nocdyn loads` on spatial robots: the table's peaks against spatial::jointReactions along the
// same samples; the closed form of a Gough-Stewart platform with massless legs at rest (each
// leg a two-force member carrying its cylinder's force, from the platform's statics); the
// Delta's U joints passing moments about their crosses' normals only; the envelope and a
// planar trajectory refused in one line with no output file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "cli_support.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_reactions.hpp"
#include "nocdyn/spatial_trajectory.hpp"

namespace nocdyn::spatial {
namespace {

std::string source(const std::string& path) { return std::string(NOCDYN_SOURCE_DIR) + "/" + path; }

/// The loads CSV: its header and its rows as text cells (the type column holds words).
struct LoadsCsv {
    std::vector<std::string> columns;
    std::vector<std::vector<std::string>> rows;
    [[nodiscard]] std::size_t at(const std::string& name) const {
        const auto it = std::find(columns.begin(), columns.end(), name);
        EXPECT_NE(it, columns.end()) << name;
        return static_cast<std::size_t>(it - columns.begin());
    }
    [[nodiscard]] double number(std::size_t row, const std::string& name) const {
        return std::stod(rows[row][at(name)]);
    }
};

std::vector<std::string> cells(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
    return out;
}

LoadsCsv readLoads(const std::filesystem::path& path) {
    std::ifstream in(path);
    LoadsCsv csv;
    std::string line;
    if (std::getline(in, line)) csv.columns = cells(line);
    while (std::getline(in, line)) {
        if (!line.empty()) csv.rows.push_back(cells(line));
    }
    return csv;
}

/// `nocdyn loads` of robot along trajectory at rate for duration, its CSV read back.
LoadsCsv runLoads(const std::string& robot, const std::string& trajectory, double duration, double rate) {
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_loads");
    const std::filesystem::path csv = dir / "loads.csv";
    const test::CliResult r =
        test::runCli("loads --robot " + robot + " --trajectory " + trajectory + " --duration " +
                     std::to_string(duration) + " --rate " + std::to_string(rate) + " --output " + csv.string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("largest: limb "), std::string::npos) << r.out;
    return readLoads(csv);
}

/// Per [limb][joint] the largest |f| and |m| and the RMS of |f| over t_k = k / rate, computed
/// in-process; `each` sees every sample's reactions and data.
struct Peaks {
    std::vector<std::vector<double>> force, moment, rms;
    std::vector<std::vector<char>> type;
};

template <class Each>
Peaks peaksInProcess(const Model& model, const Trajectory& trajectory, double duration, double rate, Each each) {
    Data data(model);
    Reactions reactions(model);
    Peaks peaks;
    for (const auto& joints : reactions.joint) {
        peaks.force.emplace_back(joints.size(), 0.0);
        peaks.moment.emplace_back(joints.size(), 0.0);
        peaks.rms.emplace_back(joints.size(), 0.0);
        peaks.type.emplace_back(joints.size(), '?');
    }
    TaskVector p, dp, ddp;
    const long n = std::lround(duration * rate);
    for (long k = 0; k < n; ++k) {
        trajectory.evaluate(static_cast<double>(k) / rate, p, dp, ddp);
        EXPECT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
        EXPECT_TRUE(jointReactions(model, data, reactions).ok());
        each(data, reactions);
        for (std::size_t j = 0; j < reactions.joint.size(); ++j) {
            for (std::size_t i = 0; i < reactions.joint[j].size(); ++i) {
                const JointReaction& r = reactions.joint[j][i];
                peaks.force[j][i] = std::max(peaks.force[j][i], r.force.norm());
                peaks.moment[j][i] = std::max(peaks.moment[j][i], r.moment.norm());
                peaks.rms[j][i] += r.force.squaredNorm() / static_cast<double>(n);
                peaks.type[j][i] = r.type;
            }
        }
    }
    for (auto& limb : peaks.rms) {
        for (double& v : limb) v = std::sqrt(v);
    }
    return peaks;
}

void expectTableMatches(const LoadsCsv& csv, const Peaks& peaks, const std::string& robot) {
    std::size_t row = 0;
    double largest = 0.0;
    for (const auto& limb : peaks.force) {
        for (const double f : limb) largest = std::max(largest, f);
    }
    for (std::size_t j = 0; j < peaks.force.size(); ++j) {
        for (std::size_t i = 0; i < peaks.force[j].size(); ++i, ++row) {
            ASSERT_LT(row, csv.rows.size()) << robot;
            const std::string where = robot + " limb " + std::to_string(j + 1) + " joint " + std::to_string(i + 1);
            EXPECT_EQ(csv.number(row, "limb"), static_cast<double>(j + 1)) << where;
            EXPECT_EQ(csv.number(row, "joint"), static_cast<double>(i + 1)) << where;
            EXPECT_EQ(csv.rows[row][csv.at("type")], std::string(1, peaks.type[j][i])) << where;
            // 1e-12 relative; a quantity that is zero but for rounding (an S joint's moment) to
            // 1e-15 of the largest force
            const auto expectNear = [&](const std::string& column, double expected) {
                EXPECT_NEAR(csv.number(row, column), expected, std::max(1e-12 * expected, 1e-15 * largest))
                    << where << " " << column;
            };
            expectNear("peak_force", peaks.force[j][i]);
            expectNear("rms_force", peaks.rms[j][i]);
            expectNear("peak_moment", peaks.moment[j][i]);
        }
    }
    EXPECT_EQ(row, csv.rows.size()) << robot;
}

TEST(SpatialLoads, TheTablesPeaksAreThoseOfTheJointReactionsAlongTheSamples) {
    // the shipped hexapod along its sway (U, P, S legs) and the Delta along its pick (R, U, U)
    for (const auto& [name, trajectory_file] : {std::pair<std::string, std::string>{"stewart", "stewart-sway"},
                                                std::pair<std::string, std::string>{"delta", "delta-pick"}}) {
        const std::string robot = source("robots/" + name + ".yaml");
        const std::string trajectory = source("trajectories/" + trajectory_file + ".yaml");
        const LoadsCsv csv = runLoads(robot, trajectory, 0.5, 200.0);
        std::vector<std::string> expected{"limb",         "joint",        "type",         "peak_force",
                                          "peak_force_t", "peak_force_x", "peak_force_y", "peak_force_z"};
        if (name == "stewart")
            expected.insert(expected.end(), {"peak_force_roll", "peak_force_pitch", "peak_force_yaw"});
        expected.insert(expected.end(), {"rms_force", "peak_moment", "peak_moment_t"});
        EXPECT_EQ(csv.columns, expected);
        const Model model(io::loadSpatialRobotDescription(robot));
        const Trajectory path = io::loadSpatialTrajectory(trajectory, model.task_dimension);
        const Peaks peaks = peaksInProcess(model, path, 0.5, 200.0, [](const Data&, const Reactions&) {});
        expectTableMatches(csv, peaks, name);
    }
}

/// robots/stewart.yaml with massless legs (every body's mass and inertia zero) and no friction.
std::string masslessStewart(const std::filesystem::path& dir) {
    std::ifstream in(source("robots/stewart.yaml"));
    std::ostringstream text;
    std::string line;
    const std::regex body(R"(^(\s+- \{)mass: [0-9.]+, (com: \[[^\]]*\]), inertia: .*$)");
    const std::regex friction(R"(damping: [0-9.]+, friction: [0-9.]+)");
    int bodies = 0;
    while (std::getline(in, line)) {
        if (std::regex_match(line, body)) {
            line = std::regex_replace(line, body, "$1mass: 0.0, $2, inertia: [[0, 0, 0], [0, 0, 0], [0, 0, 0]]}");
            ++bodies;
        }
        text << std::regex_replace(line, friction, "damping: 0.0, friction: 0.0") << '\n';
    }
    EXPECT_EQ(bodies, 12);
    const std::filesystem::path path = dir / "stewart-massless.yaml";
    std::ofstream(path) << text.str();
    return path.string();
}

TEST(SpatialLoads, AHexapodWithMasslessLegsAtRestPassesEachLegsForceThroughItsBallJoint) {
    // two-force members: each S joint passes the force of its leg, |tau_i|, where tau solves
    // the table's statics sum_i tau_i n_i + m g = 0, sum_i s_i x tau_i n_i + c x m g = 0 (n_i
    // the unit leg from its U to its S at s_i, c the table's c.o.m.); the U passes the same
    // force and no moment, the P (its force along the leg taken out) nothing
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_loads_massless");
    const std::string robot = masslessStewart(dir);
    const std::array<double, 6> pose{0.01, -0.02, 1.07, 0.03, -0.02, 0.05};
    const std::filesystem::path still = dir / "still.yaml";
    std::ofstream(still) << "name: still\nduration: 0.05\n"
                         << "x: {offset: " << pose[0] << "}\ny: {offset: " << pose[1] << "}\nz: {offset: " << pose[2]
                         << "}\nroll: {offset: " << pose[3] << "}\npitch: {offset: " << pose[4]
                         << "}\nyaw: {offset: " << pose[5] << "}\n";
    const LoadsCsv csv = runLoads(robot, still.string(), 0.05, 100.0);
    ASSERT_EQ(csv.rows.size(), 18U);
    // the statics, from the file's geometry: joints at home, the table turned and moved
    const SpatialRobotDescription d = io::loadSpatialRobotDescription(robot);
    const Model model(d);
    const Eigen::Matrix3d R = rotation(pose[3], pose[4], pose[5]);
    const Eigen::Vector3d o(pose[0], pose[1], pose[2]), o_home = model.home.head<3>();
    Eigen::Matrix<double, 6, 6> G;
    for (int i = 0; i < 6; ++i) {
        const auto& joints = d.limbs[static_cast<std::size_t>(i)].joints;
        const Eigen::Vector3d u = joints.front().point, s = o + R * (joints.back().point - o_home);
        const Eigen::Vector3d n = (s - u).normalized();
        G.col(i) << n, s.cross(n);
    }
    const Eigen::Vector3d weight = model.platform_mass * model.gravity, c = o + R * model.platform_com;
    Eigen::Matrix<double, 6, 1> w;
    w << -weight, -c.cross(weight);
    const Eigen::Matrix<double, 6, 1> tau = G.partialPivLu().solve(w);
    for (std::size_t i = 0; i < 6; ++i) {
        const double f = std::abs(tau(static_cast<Eigen::Index>(i)));
        ASSERT_GT(f, 100.0);  // every leg carries a share of the 300 kg table
        EXPECT_EQ(csv.rows[3 * i][csv.at("type")], "U");
        EXPECT_EQ(csv.rows[3 * i + 1][csv.at("type")], "P");
        EXPECT_EQ(csv.rows[3 * i + 2][csv.at("type")], "S");
        EXPECT_NEAR(csv.number(3 * i + 2, "peak_force"), f, 1e-9 * f) << "leg " << i + 1;
        EXPECT_NEAR(csv.number(3 * i + 2, "rms_force"), f, 1e-9 * f) << "leg " << i + 1;
        EXPECT_NEAR(csv.number(3 * i, "peak_force"), f, 1e-9 * f) << "leg " << i + 1;
        EXPECT_LT(csv.number(3 * i, "peak_moment"), 1e-9 * f) << "leg " << i + 1;
        EXPECT_LT(csv.number(3 * i + 2, "peak_moment"), 1e-9 * f) << "leg " << i + 1;
        EXPECT_LT(csv.number(3 * i + 1, "peak_force"), 1e-9 * f) << "leg " << i + 1;
    }
}

TEST(SpatialLoads, TheEnvelopeAndAPlanarTrajectoryAreRefusedInOneLineWithNoFile) {
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_loads_refused");
    const std::filesystem::path csv = dir / "loads.csv";
    const std::string robot = source("robots/stewart.yaml");
    const auto refused = [&](const std::string& arguments, const std::string& expected) {
        const test::CliResult r =
            test::runCli("loads --robot " + robot + " " + arguments + " --output " + csv.string());
        EXPECT_NE(r.exit_code, 0) << arguments;
        EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(std::filesystem::exists(csv)) << arguments;
    };
    refused("--envelope", "spatial robot");
    refused("--trajectory " + source("trajectories/paper1.yaml"), "theta");
    refused("--trajectory " + source("trajectories/stewart-sway.yaml") + " --duration 0.1 --rate 100 --figure " +
                (dir / "f").string(),
            "planar robots only");
}

TEST(SpatialLoads, AFailingSampleIsNamedByItsTimeAndLimbWithNoFile) {
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_loads_failing");
    const std::filesystem::path csv = dir / "loads.csv";
    const auto refused = [&](const std::string& z, const std::string& expected) {
        const std::filesystem::path path = dir / "reach.yaml";
        std::ofstream(path) << "name: reach\nx: {offset: 0.0}\ny: {offset: 0.0}\nz: " << z << "\n";
        const test::CliResult r = test::runCli("loads --robot " + source("robots/delta.yaml") + " --trajectory " +
                                               path.string() + " --duration 0.5 --rate 100 --output " + csv.string());
        EXPECT_NE(r.exit_code, 0) << z;
        EXPECT_EQ(r.err.rfind("nocdyn: error: " + expected, 0), 0U) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(std::filesystem::exists(csv)) << z;
    };
    // 1.4 m below the base: beyond the 0.35 + 0.8 m arms
    refused("{offset: -1.4}", "t = 0 s: pose out of reach: limb 1 (arm1) cannot close");
    // down from -0.8 m: the first arm's motor leaves its range at the ninth sample
    refused("{offset: -0.8, harmonics: [{amplitude: 0.6, frequency: 1}]}",
            "t = 0.08 s: joint range exceeded: limb 1 (arm1), joint 1: q = -0.835554, range [-0.8, 1.2]");
}

TEST(SpatialLoads, ALimbsNameReachesTheReportWithItsControlBytesEscaped) {
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_loads_name");
    std::ifstream in(source("robots/delta.yaml"));
    std::ostringstream text;
    text << in.rdbuf();
    const std::string original = text.str();
    const std::size_t at = original.find("name: arm1");
    ASSERT_NE(at, std::string::npos);
    const std::filesystem::path robot = dir / "delta.yaml";
    std::ofstream(robot) << original.substr(0, at) << R"(name: "arm\u001b[2J\nnocdyn: forged")"
                         << original.substr(at + 10);
    const test::CliResult r = test::runCli("loads --robot " + robot.string() + " --trajectory " +
                                           source("trajectories/delta-pick.yaml") + " --duration 0.05 --rate 100");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("limb 1 (arm\\x1B[2J\\x0Anocdyn: forged) joint 1"), std::string::npos) << r.out;
}

TEST(SpatialLoads, TheDeltasUJointsPassMomentsAboutTheirCrossesNormalsOnly) {
    // a U passes no moment about either of its axes: its moment is along a1 x a2 (the cross's
    // normal), and not zero: the parallelogram's U joints carry the arm's bending
    const Model model(io::loadSpatialRobotDescription(source("robots/delta.yaml")));
    const Trajectory path = io::loadSpatialTrajectory(source("trajectories/delta-pick.yaml"), 3);
    int checked = 0;
    double largest = 0.0;
    const Peaks peaks = peaksInProcess(model, path, 0.5, 200.0, [&](const Data& data, const Reactions& reactions) {
        for (int j = 0; j < model.limbs(); ++j) {
            const Limb& limb = model.limb[static_cast<std::size_t>(j)];
            const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
            for (int k = 0; k + 1 < limb.size(); ++k) {
                const Freedom& f = limb.freedoms[static_cast<std::size_t>(k)];
                const Freedom& g = limb.freedoms[static_cast<std::size_t>(k + 1)];
                const JointReaction& r =
                    reactions.joint[static_cast<std::size_t>(j)][static_cast<std::size_t>(f.joint)];
                if (r.type != 'U' || g.joint != f.joint) continue;
                const Eigen::Vector3d a1 = ld.J.col(k).head<3>(), a2 = ld.J.col(k + 1).head<3>();
                const double scale = r.force.norm() + r.moment.norm();
                EXPECT_LT(std::abs(r.moment.dot(a1)), 1e-10 * scale) << "limb " << j + 1;
                EXPECT_LT(std::abs(r.moment.dot(a2)), 1e-10 * scale) << "limb " << j + 1;
                EXPECT_LT(r.moment.cross(a1.cross(a2)).norm(), 1e-10 * scale * a1.cross(a2).norm());
                largest = std::max(largest, r.moment.norm());
                ++checked;
            }
        }
    });
    EXPECT_EQ(checked, 100 * 2 * model.limbs());
    EXPECT_GT(largest, 0.01);  // [N m]: arms 2 and 3 bend about their elbows (arm 1 moves in its plane)
    for (std::size_t j = 0; j < peaks.type.size(); ++j) {
        EXPECT_EQ(std::string(peaks.type[j].begin(), peaks.type[j].end()), "RUU") << j;
    }
}

}  // namespace
}  // namespace nocdyn::spatial
