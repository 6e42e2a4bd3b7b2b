// nocdyn regressor and identify: the payload from an exact log, the robot file written with the
// payload merged, the base parameters printed, and clear errors for bad logs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "cli_support.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/tables/tables.hpp"
#include "identification_support.hpp"
#include "random_robots.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kRobot = std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr-general.yaml";
const Payload kPayload{0.5, 8e-4, Vector2(0.012, -0.007)};

fs::path scratch() { return freshScratchDirectory("nocdyn_cli_identify_test"); }

/// The exact log of the robot carrying kPayload along a random motion.
Measurements exactLog(int samples) {
    return test::exactLog(Model(withPayload(io::loadRobotDescription(kRobot), kPayload)), 9, samples);
}

/// The number after `key` in the text.
double after(const std::string& text, const std::string& key) {
    const std::size_t at = text.find(key);
    EXPECT_NE(at, std::string::npos) << key << " not in\n" << text;
    return at == std::string::npos ? 0.0 : std::stod(text.substr(at + key.size()));
}

TEST(CliIdentify, RecoversThePayloadFromAnExactLogAndMergesItIntoTheRobotFile) {
    const fs::path dir = scratch();
    io::writeCsvFile((dir / "log.csv").string(), tables::toTable(exactLog(300)));
    const CliResult r = runCli("identify --robot " + kRobot + " --data " + (dir / "log.csv").string() +
                               " --payload --output " + (dir / "identified.yaml").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NEAR(after(r.out, "payload: {mass: "), kPayload.mass, 1e-9 * kPayload.mass) << r.out;
    EXPECT_NEAR(after(r.out, "com: ["), kPayload.com.x(), 1e-9 * 0.012) << r.out;
    EXPECT_NEAR(after(r.out, "], inertia: "), kPayload.inertia, 1e-9 * kPayload.inertia) << r.out;
    const RobotDescription merged = io::loadRobotDescription((dir / "identified.yaml").string());
    const RobotDescription expected = withPayload(io::loadRobotDescription(kRobot), kPayload);
    EXPECT_NEAR(merged.platform.mass, expected.platform.mass, 1e-9);
    EXPECT_NEAR(merged.platform.inertia, expected.platform.inertia, 1e-12);
    EXPECT_NEAR(merged.platform.com.x(), expected.platform.com.x(), 1e-11);
}

TEST(CliIdentify, APriorExcludingThePayloadGivesTheBoundedFitAndNamesTheActiveBound) {
    const fs::path dir = scratch();
    io::writeCsvFile((dir / "log.csv").string(), tables::toTable(exactLog(120)));
    {
        std::ofstream prior(dir / "prior.yaml");
        prior << "payload:\n  mass: [0.3, 0.45]\n  com_x: [-0.02, 0.02]\n";
    }
    const std::string command = "identify --robot " + kRobot + " --data " + (dir / "log.csv").string() + " --prior " +
                                (dir / "prior.yaml").string();
    const CliResult r = runCli(command);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("active_bounds: [{parameter: mass, side: upper, bound: 0.45}]"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("# mass is on its upper bound 0.45 kg (the unbounded fit gives 0.5"), std::string::npos)
        << r.out;
    EXPECT_EQ(after(r.out, "payload: {mass: "), 0.45) << r.out;
    // a bad prior: one line naming the file, line and field; and not with --base
    {
        std::ofstream prior(dir / "prior.yaml");
        prior << "payload:\n  mass: [0.3, 0.45]\n  inertia: [2e-3, 1e-3]\n";
    }
    const CliResult bad = runCli(command);
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.err.find((dir / "prior.yaml").string() + ":3: payload.inertia: lower bound 0.002 is above upper "
                                                           "bound 0.001"),
              std::string::npos)
        << bad.err;
    EXPECT_EQ(bad.out, "");
    const CliResult base = runCli(command + " --base");
    EXPECT_NE(base.exit_code, 0);
    EXPECT_NE(base.err.find("--prior"), std::string::npos) << base.err;
}

TEST(CliIdentify, RegressorPrintsTheBaseParametersAndWhatIsUnidentifiable) {
    const CliResult r = runCli("regressor --robot " + kRobot + " --samples 40");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("platform.I_O"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("beta_1 = "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("unidentifiable (no effect on the actuator forces): limb1.body1"), std::string::npos) << r.out;
}

TEST(CliIdentify, NamesTheMissingColumn) {
    const fs::path dir = scratch();
    std::ofstream(dir / "log.csv") << "t,u1,u2,u3,tau1,tau3\n0,0,0,0,0,0\n";
    const CliResult r = runCli("identify --robot " + kRobot + " --data " + (dir / "log.csv").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("no column 'tau2'"), std::string::npos) << r.err;
}

TEST(CliIdentify, NamesTheLineOfANaNCellAndOfTimeGoingBack) {
    const fs::path dir = scratch();
    std::ofstream(dir / "nan.csv") << "t,u1,u2,u3,tau1,tau2,tau3\n0,0,0,0,0,0,0\n0.1,0,nan,0,0,0,0\n";
    const CliResult nan = runCli("identify --robot " + kRobot + " --data " + (dir / "nan.csv").string());
    EXPECT_EQ(nan.exit_code, 1);
    EXPECT_NE(nan.err.find("nan.csv:3: column 'u2'"), std::string::npos) << nan.err;
    std::ofstream(dir / "back.csv") << "t,u1,u2,u3,tau1,tau2,tau3\n0,0,0,0,0,0,0\n0.2,0,0,0,0,0,0\n0.1,0,0,0,0,0,0\n";
    const CliResult back = runCli("identify --robot " + kRobot + " --data " + (dir / "back.csv").string());
    EXPECT_EQ(back.exit_code, 1);
    EXPECT_NE(back.err.find("back.csv:4: column 't'"), std::string::npos) << back.err;
}

TEST(CliIdentify, RefusesTooFewSamples) {
    const fs::path dir = scratch();
    io::writeCsvFile((dir / "log.csv").string(), tables::toTable(exactLog(5)));
    const CliResult r = runCli("identify --robot " + kRobot + " --data " + (dir / "log.csv").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("too few"), std::string::npos) << r.err;
}

/// The experiment: computed-torque control along trajectory 1 with the payload unknown to the
/// controller, 1 um encoder noise and 0.5 N force noise, 1 s at 10 kHz, then identify; `robot`
/// is the --robot option (empty: the default robot). Returns identify's output.
std::string identifyFromSimulatedControlLog(const fs::path& dir, const std::string& robot) {
    const CliResult control =
        runCli("control" + robot +
               " --trajectory paper1 --plant nocdyn --duration 1 --rate 10000 --payload-mass 0.5 --payload-com 0.012 "
               "-0.007 --payload-inertia 8e-4 --noise-u 1e-6 --noise-tau 0.5 --log " +
               (dir / "log.csv").string());
    EXPECT_EQ(control.exit_code, 0) << control.err;
    const CliResult r = runCli("identify" + robot + " --data " + (dir / "log.csv").string() + " --held-forces");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
}

// The default robot is the paper's prototype through the general model: the experiment without
// --robot (the short form, expanded by io) identifies what it does with the general file.
TEST(CliIdentify, RecoversThePayloadFromANoisySimulatedControlLog) {
    const std::string out = identifyFromSimulatedControlLog(scratch(), " --robot " + kRobot);
    // one second (kept short for the sanitizer run): about twice the 5 s run's errors (README)
    EXPECT_NEAR(after(out, "payload: {mass: "), kPayload.mass, 0.01 * kPayload.mass) << out;
    EXPECT_NEAR(after(out, "com: ["), kPayload.com.x(), 5e-4) << out;
    EXPECT_NEAR(after(out, "], inertia: "), kPayload.inertia, 0.03 * kPayload.inertia) << out;
    const std::string fallback = identifyFromSimulatedControlLog(scratch(), "");
    for (const char* field : {"payload: {mass: ", "com: [", "], inertia: "}) {
        const double expected = after(out, field);
        EXPECT_NEAR(after(fallback, field), expected, 1e-9 * std::abs(expected)) << field << "\n" << fallback;
    }
}

}  // namespace
}  // namespace nocdyn::test
