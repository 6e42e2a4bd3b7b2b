// nocdyn excite and the calibration workflow of nocdyn identify: the designed trajectory file is
// usable as --trajectory and beats the paper's condition numbers; identify --base writes a
// calibration that identify --payload --calibration uses; bad input gives clear errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>

#include "cli_support.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "random_robots.hpp"
#include "identification_support.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kRobot = std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr-general.yaml";
const std::string kSmall = " --evaluations 30 --random-shapes 15 --samples 48 --check-samples 300";

fs::path scratch() { return freshScratchDirectory("nocdyn_cli_excite_test"); }

/// The number after `key` in the text.
double after(const std::string& text, const std::string& key) {
    const std::size_t at = text.find(key);
    EXPECT_NE(at, std::string::npos) << key << " not in\n" << text;
    return at == std::string::npos ? 0.0 : std::stod(text.substr(at + key.size()));
}

TEST(CliExcite, WritesATrajectoryFileBetterConditionedThanThePaperTrajectories) {
    const fs::path dir = scratch();
    const std::string out = (dir / "excitation.yaml").string();
    const CliResult r = runCli("excite --robot " + kRobot + " --payload-guess 0.5 0.012 -0.007 8e-4 --duration 1" +
                               kSmall + " --output " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const double designed = after(r.out, "designed: {condition_number: ");
    EXPECT_LT(designed, after(r.out, "paper_trajectory_1: {condition_number: ")) << r.out;
    EXPECT_LT(designed, after(r.out, "paper_trajectory_2: {condition_number: ")) << r.out;
    const PoseTrajectory trajectory = io::loadTrajectory(out);
    EXPECT_EQ(trajectory.duration, 1.0);
    EXPECT_FALSE(trajectory.x.harmonics.empty());
    // the file drives the other commands: inverse dynamics along it stays within the limits
    const CliResult id = runCli("inverse-dynamics --robot " + kRobot + " --trajectory " + out + " --rate 2000 -o " +
                                (dir / "tau.csv").string());
    EXPECT_EQ(id.exit_code, 0) << id.err;
}

TEST(CliExcite, RefusesADurationThatIsNotWholePeriodsAndAPayloadWithBase) {
    const fs::path dir = scratch();
    const std::string out = (dir / "e.yaml").string();
    CliResult r = runCli("excite --robot " + kRobot + " --duration 0.3" + kSmall + " --output " + out);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("not a whole number of base periods"), std::string::npos) << r.err;
    r = runCli("excite --robot " + kRobot + " --base --payload-guess 0.5 0 0 1e-4 --duration 1" + kSmall +
               " --output " + out);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("--payload-guess"), std::string::npos) << r.err;
    r = runCli("excite --robot " + kRobot + " --payload-guess 0.5 0.01 --duration 1 --output " + out);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("payload-guess"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

TEST(CliExcite, TheGradientOptimizerRunsAndAnUnknownOneIsRefusedInOneLine) {
    const fs::path dir = scratch();
    const std::string out = (dir / "e.yaml").string();
    CliResult r = runCli("excite --robot " + kRobot + " --payload-guess 0.5 0.012 -0.007 8e-4 --duration 1" + kSmall +
                         " --optimizer gradient --output " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("then BFGS on the exact gradient"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(out));
    fs::remove(out);
    r = runCli("excite --robot " + kRobot + " --optimizer bfgs --output " + out);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--optimizer: bfgs not in {nelder-mead,gradient}"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

TEST(CliIdentify, CalibratesTheRobotThenIdentifiesThePayloadAgainstIt) {
    const fs::path dir = scratch();
    // the robot as built: a heavier platform than its file says
    RobotDescription built = io::loadRobotDescription(kRobot);
    built.platform.mass += 0.2;
    const Payload payload{0.5, 8e-4, Vector2(0.012, -0.007)};
    io::writeCsvFile((dir / "tare.csv").string(), tables::toTable(exactLog(Model(built), 3, 300)));
    io::writeCsvFile((dir / "load.csv").string(),
                     tables::toTable(exactLog(Model(withPayload(built, payload)), 4, 300)));
    const std::string cal = (dir / "cal.yaml").string();
    const CliResult base =
        runCli("identify --robot " + kRobot + " --data " + (dir / "tare.csv").string() + " --base --output " + cal);
    ASSERT_EQ(base.exit_code, 0) << base.err;
    const CliResult r = runCli("identify --robot " + kRobot + " --data " + (dir / "load.csv").string() +
                               " --payload --calibration " + cal);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NEAR(after(r.out, "payload: {mass: "), payload.mass, 1e-9 * payload.mass) << r.out;
    EXPECT_NEAR(after(r.out, "], inertia: "), payload.inertia, 1e-9 * payload.inertia) << r.out;
    // without the calibration the platform's extra 0.2 kg is taken for payload
    const CliResult raw = runCli("identify --robot " + kRobot + " --data " + (dir / "load.csv").string());
    ASSERT_EQ(raw.exit_code, 0) << raw.err;
    EXPECT_NEAR(after(raw.out, "payload: {mass: "), payload.mass + 0.2, 1e-6) << raw.out;
    // a calibration of another robot is refused, naming the file
    const CliResult other = runCli("identify --robot " + std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rrr.yaml --data " +
                                   (dir / "load.csv").string() + " --calibration " + cal);
    EXPECT_NE(other.exit_code, 0);
    EXPECT_NE(other.err.find("cal.yaml"), std::string::npos) << other.err;
    EXPECT_NE(other.err.find("not made for this robot"), std::string::npos) << other.err;
}

}  // namespace
}  // namespace nocdyn::test
