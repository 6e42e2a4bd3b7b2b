// The 3-PRR short form means the general robot it expands to: `forward-kinematics` on the
// short form (or no --robot) lists exactly what it lists for robots/paper-3prr-general.yaml,
// with the assembly modes the hand-derived 3-PRR solver found, and flags actuator values
// beyond the stroke.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "cli_support.hpp"

namespace nocdyn::test {
namespace {

const std::string kRobots = std::string(NOCDYN_SOURCE_DIR) + "/robots/";

nlohmann::json forwardKinematics(const std::string& arguments) {
    const CliResult r = runCli("forward-kinematics " + arguments + " --all-branches --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
}

TEST(CliShortForm, ForwardKinematicsListsTheGeneralRobotsModes) {
    const nlohmann::json none = forwardKinematics("0.005 -0.006 0.012");
    const nlohmann::json short_form = forwardKinematics("0.005 -0.006 0.012 --robot " + kRobots + "paper-3prr.yaml");
    const nlohmann::json general =
        forwardKinematics("0.005 -0.006 0.012 --robot " + kRobots + "paper-3prr-general.yaml");
    EXPECT_EQ(none, short_form);
    ASSERT_EQ(short_form["solutions"].size(), general["solutions"].size());
    for (std::size_t k = 0; k < general["solutions"].size(); ++k) {
        const auto& a = short_form["solutions"][k];
        const auto& b = general["solutions"][k];
        EXPECT_EQ(a["branch"], b["branch"]);
        EXPECT_EQ(a["working"], b["working"]);
        for (const char* c : {"theta", "x", "y"}) {
            EXPECT_NEAR(a["pose"][c].get<double>(), b["pose"][c].get<double>(), 1e-12) << c;
        }
    }
}

TEST(CliShortForm, ForwardKinematicsAtZeroFindsTheTwoModesOfThe3PrrSolver) {
    // The hand-derived solver (degree-12 polynomial in tan(theta/2)): at u = 0 the reference
    // pose and the platform turned by 2.972884660246 rad, both on the working branches.
    const nlohmann::json json = forwardKinematics("0 0 0");
    ASSERT_EQ(json["solutions_all_branches"].get<int>(), 2);
    EXPECT_EQ(json["solutions_working_branches"].get<int>(), 2);
    EXPECT_TRUE(json["within_limits"].get<bool>());
    const auto& modes = json["solutions"];
    ASSERT_EQ(modes.size(), 2U);
    EXPECT_NEAR(modes[0]["pose"]["theta"].get<double>(), 0.0, 1e-12);
    EXPECT_NEAR(modes[1]["pose"]["theta"].get<double>(), 2.972884660246, 1e-11);
    for (const auto& mode : modes) {
        EXPECT_NEAR(mode["pose"]["x"].get<double>(), 0.0, 1e-12);
        EXPECT_NEAR(mode["pose"]["y"].get<double>(), 0.0, 1e-12);
        EXPECT_LE(mode["u_error"].get<double>(), 1e-12);
    }
}

TEST(CliShortForm, ForwardKinematicsFlagsAValueBeyondTheStroke) {
    // half stroke 12.45 mm: u2 = 13 mm is beyond it
    EXPECT_FALSE(forwardKinematics("0 0.013 0")["within_limits"].get<bool>());
    const CliResult r = runCli("forward-kinematics 0 0.013 0");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("(u2 beyond its joint's range)"), std::string::npos) << r.out;
    EXPECT_EQ(runCli("forward-kinematics 0 0.012 0").out.find("beyond"), std::string::npos);
}

}  // namespace
}  // namespace nocdyn::test
