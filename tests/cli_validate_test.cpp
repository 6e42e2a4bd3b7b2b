// nocdyn validate: the agreement table of the model with Simbody and MuJoCo, and a pose out of
// reach refused with the limb named; a spatial robot's against Simbody's along its trajectory.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::test {
namespace {

int runCli(const std::string& arguments, std::string& err) {
    const std::string err_file = testing::TempDir() + "/validate_stderr.txt";
    const int status = std::system((std::string(NOCDYN_CLI) + " " + arguments + " >/dev/null 2>" + err_file).c_str());
    std::ifstream in(err_file);
    err.assign(std::istreambuf_iterator<char>(in), {});
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Validation, ValidateCommandReportsAgreementAndRejectsPosesOutOfReach) {
    std::string err;
    const std::string csv = testing::TempDir() + "/validate.csv";
    ASSERT_EQ(runCli("validate --trajectory paper2 --duration 0.05 --rate 1000 --output " + csv, err), 0) << err;
    EXPECT_NE(err.find("| Simbody | 1 |"), std::string::npos) << err;
    EXPECT_NE(err.find("| MuJoCo | 3 |"), std::string::npos) << err;
    const io::Table table = io::readCsvFile(csv);
    EXPECT_EQ(table.rows.size(), 50u);
    for (const char* column : {"simbody_tau1", "mujoco_tau3", "tau2", "u1"}) EXPECT_TRUE(table.has(column)) << column;
    for (const auto& row : table.rows) {
        EXPECT_NEAR(row[table.column("simbody_tau2")], row[table.column("tau2")], 1e-9 * 262);
    }

    const std::string far = testing::TempDir() + "/far.yaml";
    std::ofstream(far) << "duration: 0.1\ny: {harmonics: [{amplitude: 0.2, frequency: 5}]}\n";
    EXPECT_EQ(runCli("validate --trajectory " + far, err), 1);
    EXPECT_NE(err.find("pose out of reach: limb"), std::string::npos) << err;
}

}  // namespace
}  // namespace nocdyn::test

// `nocdyn validate` of a spatial robot along a trajectory: nocdyn's actuator forces against the
// independent Simbody model of the same file (loops closed by ball and universal constraints).

namespace nocdyn::test {
namespace {

std::string sourcePath(const std::string& relative) { return std::string(NOCDYN_SOURCE_DIR) + "/" + relative; }

/// max_t |column_a| over the rows.
double peakOf(const io::Table& table, const std::string& column) {
    double peak = 0.0;
    for (const auto& row : table.rows) peak = std::max(peak, std::abs(row[table.column(column)]));
    return peak;
}

/// Runs `validate` of a shipped spatial robot along `trajectory` at `rate` (both engines),
/// checks the table's columns and rows and returns the largest over the engines and actuators
/// of max_t |tau_a^engine - tau_a| over max_t |tau_a|, read from the CSV; checks that the report
/// states the same numbers.
double spatialAgreement(const std::string& robot, const std::string& trajectory, double rate,
                        const std::vector<std::string>& pose, int actuators, std::size_t rows, double min_peak) {
    const std::filesystem::path dir = freshScratchDirectory("cli_validate");
    const std::string csv = (dir / "validate.csv").string();
    const CliResult run =
        test::runCli("validate --robot " + sourcePath("robots/" + robot + ".yaml") + " --trajectory " + trajectory +
                     " --rate " + std::to_string(rate) + " -o " + csv);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.out, "");
    const io::Table table = io::readCsvFile(csv);
    std::vector<std::string> columns{"t"};
    columns.insert(columns.end(), pose.begin(), pose.end());
    for (const char* prefix : {"u", "tau", "simbody_tau", "mujoco_tau", "simbody_dtau", "mujoco_dtau"}) {
        for (int a = 1; a <= actuators; ++a) columns.push_back(prefix + std::to_string(a));
    }
    EXPECT_EQ(table.columns, columns);
    EXPECT_EQ(table.rows.size(), rows);
    double worst_of_all = 0.0;
    for (const auto& [engine, name] : {std::pair{"simbody", "Simbody"}, std::pair{"mujoco", "MuJoCo"}}) {
        double worst = 0.0;
        for (int a = 1; a <= actuators; ++a) {
            const std::string tau = "tau" + std::to_string(a), theirs = engine + ("_tau" + std::to_string(a)),
                              dtau = engine + ("_dtau" + std::to_string(a));
            const double peak = peakOf(table, tau);
            EXPECT_GT(peak, min_peak) << robot << " actuator " << a;
            double diff = 0.0;
            for (const auto& row : table.rows) {
                diff = std::max(diff, std::abs(row[table.column(theirs)] - row[table.column(tau)]));
                EXPECT_NEAR(row[table.column(dtau)], row[table.column(theirs)] - row[table.column(tau)], 1e-12 * peak);
            }
            worst = std::max(worst, diff / peak);
            EXPECT_NE(run.err.find(std::string("| ") + name + " | " + std::to_string(a) + " | "), std::string::npos)
                << run.err;
        }
        const std::string said = std::string(engine[0] == 's' ? "relative to our peak abs(tau): " : ", ") + name + " ";
        const std::size_t at = run.err.find(said);
        EXPECT_NE(at, std::string::npos) << run.err;
        if (at != std::string::npos) {
            const double reported = std::stod(run.err.substr(at + said.size()));
            EXPECT_NEAR(reported, worst, 1e-3 * worst + 1e-300) << run.err;
        }
        std::printf("%s along %s: largest |tau_%s - tau| / peak |tau| = %.3e\n", robot.c_str(), trajectory.c_str(),
                    engine, worst);
        worst_of_all = std::max(worst_of_all, worst);
    }
    return worst_of_all;
}

const std::vector<std::string> kTranslation{"x", "y", "z"}, kFull{"x", "y", "z", "roll", "pitch", "yaw"};

TEST(SpatialValidation, DeltaAgreesWithBothEnginesAlongItsPickAndPlace) {
    const std::string trajectory = sourcePath("trajectories/delta-pick.yaml");
    EXPECT_LT(spatialAgreement("delta", trajectory, 200, kTranslation, 3, 200, 1.0), 1e-9);
}

TEST(SpatialValidation, StewartPlatformAgreesWithBothEnginesAlongItsSway) {
    const std::string trajectory = sourcePath("trajectories/stewart-sway.yaml");
    EXPECT_LT(spatialAgreement("stewart", trajectory, 100, kFull, 6, 200, 1000.0), 1e-9);
}

TEST(SpatialValidation, SixRusAgreesWithBothEnginesAlongASway) {
    // stewart-sway's motion about the 6-RUS's home (z = 0.308 m): a few mm and about a degree
    const std::filesystem::path dir = freshScratchDirectory("cli_validate_trajectory");
    const std::string trajectory = (dir / "6-rus-sway.yaml").string();
    std::ofstream(trajectory) << "name: 6-rus-sway\nduration: 1.0\n"
                                 "x: {harmonics: [{amplitude: 0.005, frequency: 2}]}\n"
                                 "y: {harmonics: [{amplitude: 0.003, frequency: 3, phase: 0.5}]}\n"
                                 "z: {offset: 0.30794957407098617, harmonics: [{amplitude: 0.004, frequency: 1}]}\n"
                                 "roll: {harmonics: [{amplitude: 0.0175, frequency: 2}]}\n"
                                 "pitch: {harmonics: [{amplitude: 0.0175, frequency: 1, phase: 1.0}]}\n"
                                 "yaw: {harmonics: [{amplitude: 0.026, frequency: 3, phase: -0.3}]}\n";
    EXPECT_LT(spatialAgreement("hexa-6rus", trajectory, 200, kFull, 6, 200, 0.1), 1e-9);
}

TEST(SpatialValidation, NocdynsColumnsAreInverseDynamicsOwn) {
    const std::filesystem::path dir = freshScratchDirectory("cli_validate");
    const std::string robot = sourcePath("robots/stewart.yaml"),
                      trajectory = sourcePath("trajectories/stewart-sway.yaml");
    const std::string validated = (dir / "validate.csv").string(), computed = (dir / "id.csv").string();
    const std::string common = " --robot " + robot + " --trajectory " + trajectory + " --rate 50 --duration 1";
    ASSERT_EQ(test::runCli("validate" + common + " -o " + validated).exit_code, 0);
    ASSERT_EQ(test::runCli("inverse-dynamics" + common + " -o " + computed).exit_code, 0);
    const io::Table v = io::readCsvFile(validated), id = io::readCsvFile(computed);
    ASSERT_EQ(v.rows.size(), 50u);
    ASSERT_EQ(id.rows.size(), v.rows.size());
    for (const char* column : {"t", "x", "z", "yaw", "u1", "u6", "tau1", "tau2", "tau3", "tau4", "tau5", "tau6"}) {
        const double scale = std::max(1.0, peakOf(id, column));
        for (std::size_t k = 0; k < v.rows.size(); ++k) {
            EXPECT_NEAR(v.rows[k][v.column(column)], id.rows[k][id.column(column)], 1e-12 * scale)
                << column << " " << k;
        }
    }
}

TEST(SpatialValidation, ABadTrajectoryIsOneLineAndNoFile) {
    const std::filesystem::path dir = freshScratchDirectory("cli_validate");
    const std::string delta = sourcePath("robots/delta.yaml"), csv = (dir / "validate.csv").string();
    // out of reach: the Delta's arms do not reach 2 m below the base
    const std::string far = (dir / "far.yaml").string();
    std::ofstream(far) << "name: far\nduration: 0.1\nx: {offset: 0}\ny: {offset: 0}\nz: {offset: -2.0}\n";
    const CliResult out_of_reach = test::runCli("validate --robot " + delta + " --trajectory " + far + " -o " + csv);
    EXPECT_EQ(out_of_reach.exit_code, 1);
    EXPECT_EQ(out_of_reach.err.rfind("nocdyn: error: t = 0 s: pose out of reach: limb 1 (arm1)", 0), 0u)
        << out_of_reach.err;
    EXPECT_EQ(std::count(out_of_reach.err.begin(), out_of_reach.err.end(), '\n'), 1) << out_of_reach.err;
    // a translation robot's trajectory (x, y, z) for the hexapod, which takes six coordinates
    const CliResult short_pose =
        test::runCli("validate --robot " + sourcePath("robots/stewart.yaml") + " --trajectory " +
                     sourcePath("trajectories/delta-pick.yaml") + " -o " + csv);
    EXPECT_NE(short_pose.exit_code, 0);
    EXPECT_EQ(short_pose.err.rfind("nocdyn: error: ", 0), 0u) << short_pose.err;
    EXPECT_NE(short_pose.err.find("delta-pick.yaml"), std::string::npos) << short_pose.err;
    EXPECT_EQ(std::count(short_pose.err.begin(), short_pose.err.end(), '\n'), 1) << short_pose.err;
    EXPECT_FALSE(std::filesystem::exists(csv));
}

}  // namespace
}  // namespace nocdyn::test
