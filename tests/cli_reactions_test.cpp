// nocdyn inverse-dynamics --reactions and nocdyn loads: the columns after the others, equal to
// the library's reactions at the same samples; the design loads equal the peaks and RMS of
// those columns; bad input gets the inverse dynamics' errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli_support.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/tables.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kRobot = std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rrr.yaml";
constexpr double kRounding = 1e-12;  // of the sample's largest reaction

fs::path scratch() { return freshScratchDirectory("nocdyn_cli_reactions_test"); }

TEST(CliReactions, ColumnsFollowTheOthersAndEqualTheLibrarysReactions) {
    const fs::path dir = scratch();
    const CliResult r =
        runCli("inverse-dynamics --robot " + kRobot +
               " --trajectory paper1 --duration 0.05 --rate 1000 --reactions -o " + (dir / "id.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Table table = io::readCsvFile((dir / "id.csv").string());
    const Model model(io::loadRobotDescription(kRobot));
    const std::vector<std::string> first = io::inverseDynamicsColumns(model.actuators);
    const std::vector<std::string> reactions = io::reactionColumns(model.limbs);
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
