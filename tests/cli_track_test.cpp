// The CLI on general robot files without a pose sensor: `simulate` from a first row that gives
// only the actuator values (the pose by direct kinematics, the assembly mode nearest home or
// the one --assembly-mode picks), and `control --measure encoders` (the pose by the tracker).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "cli_support.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

std::string robotFile(const std::string& name) { return std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml"; }

/// A force file at rest whose first row gives u of pose p (no pose columns): t,tau..,u..
fs::path forcesFromActuators(const fs::path& dir, const Model& model, const Pose& p) {
    Data data(model);
    EXPECT_TRUE(inverseDisplacement(model, data, p).ok());
    const fs::path file = dir / "forces.csv";
    std::ofstream out(file);
    out.precision(17);
    out << "t";
    for (int a = 1; a <= model.actuators; ++a) out << ",tau" << a;
    for (int a = 1; a <= model.actuators; ++a) out << ",u" << a;
    out << "\n";
    for (const double t : {0.0, 0.002}) {
        out << t;
        for (int a = 0; a < model.actuators; ++a) out << ",0";
        for (int a = 0; a < model.actuators; ++a) out << "," << data.u(a);
        out << "\n";
    }
    return file;
}

TEST(CliTrack, SimulateStartsAtThePoseOfTheFirstRowsActuatorValues) {
    for (const std::string name : {"3-rrr", "4-rrr"}) {
        const Model model(io::loadRobotDescription(robotFile(name)));
        const fs::path dir = freshScratchDirectory("cli_track_" + name);
        const Pose p0 = model.home + Pose(0.02, 0.002 * model.length_scale, -0.003 * model.length_scale);
        const fs::path forces = forcesFromActuators(dir, model, p0), motion = dir / "motion.csv";
        const CliResult r = runCli("simulate --robot " + robotFile(name) + " --forces " + forces.string() +
                                   " --rate 1000 -o " + motion.string());
        ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
        EXPECT_NE(r.err.find("the nearest home"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("assembly mode"), std::string::npos) << r.err;
        const io::Table table = io::readCsvFile(motion.string());
        ASSERT_FALSE(table.rows.empty());
        const auto& first = table.rows.front();
        EXPECT_NEAR(first[table.column("theta")], p0(0), 1e-10) << name;
        EXPECT_NEAR(first[table.column("x")], p0(1), 1e-10 * model.length_scale) << name;
        EXPECT_NEAR(first[table.column("y")], p0(2), 1e-10 * model.length_scale) << name;

        // --assembly-mode picks among the modes forward-kinematics lists; beyond them: an error
        Data data(model);
        ASSERT_TRUE(inverseDisplacement(model, data, p0).ok());
        const ActuatorVector u = data.u;  // data is the solver's workspace
        AssemblyModes modes;
        ASSERT_TRUE(directKinematics(model, data, u, modes).ok());
        int working = 0, home_index = 0;
        for (const AssemblyMode& mode : modes) {
            if (!mode.working) continue;
            ++working;
            if ((mode.p - p0).cwiseAbs().maxCoeff() < 1e-9) home_index = working;
        }
        ASSERT_GT(home_index, 0) << name;
        const CliResult picked =
            runCli("simulate --robot " + robotFile(name) + " --forces " + forces.string() +
                   " --rate 1000 --assembly-mode " + std::to_string(home_index) + " -o " + motion.string());
        ASSERT_EQ(picked.exit_code, 0) << picked.err;
        EXPECT_NE(picked.err.find("as --assembly-mode chose"), std::string::npos) << picked.err;
        EXPECT_NEAR(io::readCsvFile(motion.string()).rows.front()[table.column("theta")], p0(0), 1e-10);
        const CliResult beyond = runCli("simulate --robot " + robotFile(name) + " --forces " + forces.string() +
                                        " --assembly-mode " + std::to_string(working + 1));
        EXPECT_EQ(beyond.exit_code, 1);
        EXPECT_NE(beyond.err.find("give " + std::to_string(working) + " working assembly mode"), std::string::npos)
            << beyond.err;
    }
}

TEST(CliTrack, SimulateRefusesActuatorValuesWithoutAssembly) {
    const fs::path dir = freshScratchDirectory("cli_track_none");
    const fs::path forces = dir / "far.csv";
    std::ofstream(forces) << "t,tau1,tau2,tau3,u1,u2,u3\n0,0,0,0,3,-3,3\n1,0,0,0,3,-3,3\n";
    const CliResult r = runCli("simulate --robot " + robotFile("3-rrr") + " --forces " + forces.string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("far.csv:2"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("cannot start there"), std::string::npos) << r.err;
    // --assembly-mode with a first row that gives the pose: refused, not ignored
    const fs::path posed = dir / "posed.csv";
    std::ofstream(posed) << "t,tau1,tau2,tau3,theta,x,y\n0,0,0,0,0,0,0\n1,0,0,0,0,0,0\n";
    const CliResult both =
        runCli("simulate --robot " + robotFile("3-rrr") + " --forces " + posed.string() + " --assembly-mode 1");
    EXPECT_EQ(both.exit_code, 1);
    EXPECT_NE(both.err.find("but the row gives the pose x,y,theta"), std::string::npos) << both.err;
}

/// The numbers of stdout's "pose: RMS error x .. um, y .. um, theta .. urad" line.
std::vector<double> poseErrors(const std::string& out) {
    std::smatch m;
    const std::regex line("pose: RMS error x ([^ ]+) um, y ([^ ]+) um, theta ([^ ]+) urad");
    if (!std::regex_search(out, m, line)) return {};
    return {std::stod(m[1]), std::stod(m[2]), std::stod(m[3])};
}

TEST(CliTrack, ControlThroughTheEncodersMatchesThePoseSensorWithoutNoise) {
    for (const std::string name : {"3-rrr", "4-rrr"}) {
        const std::string common =
            "control --robot " + robotFile(name) + " --trajectory paper1 --plant nocdyn --duration 0.02";
        const CliResult pose = runCli(common);
        const CliResult encoders = runCli(common + " --measure encoders");
        ASSERT_EQ(pose.exit_code, 0) << pose.err;
        ASSERT_EQ(encoders.exit_code, 0) << encoders.err;
        const std::vector<double> a = poseErrors(pose.out), b = poseErrors(encoders.out);
        ASSERT_EQ(a.size(), 3u) << pose.out;
        ASSERT_EQ(b.size(), 3u) << encoders.out;
        // the tracker gives the pose to round-off: the same run
        for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], 1e-3 * a[i] + 1e-6) << name << " " << i;
        EXPECT_NE(encoders.out.find("measured through the encoders and the tracker"), std::string::npos)
            << encoders.out;
        // noisy encoders: still tracked, a larger error
        const CliResult noisy = runCli(common + " --measure encoders --noise-u 1e-6 --noise-du 1e-4");
        ASSERT_EQ(noisy.exit_code, 0) << noisy.err;
        const std::vector<double> c = poseErrors(noisy.out);
        ASSERT_EQ(c.size(), 3u) << noisy.out;
        EXPECT_GT(c[0] + c[1], a[0] + a[1]) << noisy.out;
    }
    const CliResult mixed = runCli("control --robot " + robotFile("3-rrr") +
                                   " --trajectory paper1 --plant nocdyn --duration 0.01 --measure encoders "
                                   "--noise-pose 1e-6");
    EXPECT_EQ(mixed.exit_code, 1);
    EXPECT_NE(mixed.err.find("--noise-u"), std::string::npos) << mixed.err;
}

}  // namespace
}  // namespace nocdyn::test
