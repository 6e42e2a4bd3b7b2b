// Robot and trajectory files and CSV tables: the shipped files, and every class of bad
// input with the field and line named in the error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_yaml.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/prr3/model.hpp"

namespace nocdyn::test {
namespace {

const std::string kRobot = R"(name: test-robot
geometry:
  base_side: 0.400
  platform_side: 0.110
  link_length: 0.15915
  link_com: 0.079575
slider:   {mass: 1.46966}
link:     {mass: 0.63863, inertia: 1.5786066e-3}
platform: {mass: 1.75257, inertia: 6.17311382e-3}
actuator: {stroke: 0.0249, peak_force: 262.0}
)";

/// Expects parseRobot(text) to throw an Error whose message contains every fragment.
void expectRobotError(const std::string& text, std::initializer_list<const char*> fragments) {
    try {
        (void)io::parseRobot(text, "robot.yaml");
        ADD_FAILURE() << "accepted:\n" << text;
    } catch (const Error& e) {
        for (const char* fragment : fragments) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what() << "\nmissing: " << fragment;
        }
    }
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

TEST(RobotFile, ShippedPaperRobotEqualsTheBuiltInDefault) {
    const RobotParameters file = io::loadRobot(std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr.yaml");
    const RobotParameters builtin;
    EXPECT_EQ(file.name, "paper-3prr");
    EXPECT_EQ(file.base_side, builtin.base_side);
    EXPECT_EQ(file.platform_side, builtin.platform_side);
    EXPECT_EQ(file.link_length, builtin.link_length);
    EXPECT_EQ(file.link_com, builtin.link_com);
    EXPECT_EQ(file.slider_mass, builtin.slider_mass);
    EXPECT_EQ(file.link_mass, builtin.link_mass);
    EXPECT_EQ(file.link_inertia, builtin.link_inertia);
    EXPECT_EQ(file.platform_mass, builtin.platform_mass);
    EXPECT_EQ(file.platform_inertia, builtin.platform_inertia);
    EXPECT_EQ(file.stroke, builtin.stroke);
    EXPECT_EQ(file.peak_force, builtin.peak_force);
    EXPECT_EQ(file.max_condition, builtin.max_condition);
}

TEST(RobotFile, RoundTripsThroughYaml) {
    RobotParameters robot;
    robot.name = "odd";
    robot.link_mass = 0.123456789012345678;
    robot.max_condition = 5e3;
    const RobotParameters back = io::parseRobot(io::robotToYaml(robot), "x.yaml");
    EXPECT_EQ(back.name, "odd");
    EXPECT_EQ(back.link_mass, robot.link_mass);
    EXPECT_EQ(back.max_condition, robot.max_condition);
}

TEST(RobotFile, NameDefaultsToTheFileStem) {
    const RobotParameters robot = io::parseRobot(replaced(kRobot, "name: test-robot\n", ""), "dir/my-robot.yaml");
    EXPECT_EQ(robot.name, "my-robot");
}

TEST(RobotFile, UnknownKeyIsAnErrorWithItsLine) {
    expectRobotError(replaced(kRobot, "link_com:", "link_cmo:"), {"robot.yaml:6", "geometry.link_cmo", "unknown key"});
    expectRobotError(kRobot + "colour: red\n", {"robot.yaml:11", "colour", "unknown key"});
}

TEST(RobotFile, MissingFieldIsNamed) {
    expectRobotError(replaced(kRobot, "  link_length: 0.15915\n", ""), {"geometry.link_length", "missing"});
    expectRobotError(replaced(kRobot, "slider:   {mass: 1.46966}\n", ""), {"slider", "missing"});
}

TEST(RobotFile, NonNumericAndNonFiniteValuesAreRejected) {
    expectRobotError(replaced(kRobot, "0.15915", "long"), {"robot.yaml:5", "geometry.link_length", "'long'"});
    expectRobotError(replaced(kRobot, "0.15915", ".nan"), {"geometry.link_length", "finite"});
    expectRobotError(replaced(kRobot, "0.15915", "[1, 2]"), {"geometry.link_length", "number"});
}

TEST(RobotFile, UnphysicalValuesAreRejectedWithTheField) {
    expectRobotError(replaced(kRobot, "{mass: 0.63863", "{mass: -0.63863"), {"link.mass", "positive"});
    expectRobotError(replaced(kRobot, "inertia: 6.17311382e-3", "inertia: 0"), {"platform.inertia", "positive"});
    expectRobotError(replaced(kRobot, "base_side: 0.400", "base_side: 0"), {"geometry.base_side", "positive"});
    expectRobotError(replaced(kRobot, "peak_force: 262.0", "peak_force: -1"), {"actuator.peak_force"});
    expectRobotError(replaced(kRobot, "link_com: 0.079575", "link_com: 0.2"), {"geometry.link_com", "[0, link_length"});
    expectRobotError(replaced(kRobot, "link_com: 0.079575", "link_com: -0.01"), {"geometry.link_com"});
}

TEST(RobotFile, RobotThatCannotBeAssembledIsRejected) {
    expectRobotError(replaced(kRobot, "link_length: 0.15915", "link_length: 0.08"), {"cannot be assembled", "link_length"});
    expectRobotError(replaced(kRobot, "platform_side: 0.110", "platform_side: 0.5"), {"cannot be assembled", "platform"});
}

TEST(RobotFile, MalformedYamlNamesTheLine) {
    expectRobotError("geometry: {base_side: 0.4\nslider: [", {"robot.yaml:", "not valid YAML"});
    expectRobotError("- just\n- a list\n", {"robot.yaml", "mapping"});
}

TEST(RobotFile, MissingFileIsAnError) {
    EXPECT_THROW((void)io::loadRobot("/nonexistent/robot.yaml"), Error);
}

TEST(RobotModel, InvalidParametersThroughTheLibraryThrow) {
    RobotParameters robot;
    robot.link_inertia = -1.0;
    EXPECT_THROW(prr3::Model{robot}, Error);
    robot = RobotParameters{};
    robot.max_condition = 0.5;
    EXPECT_THROW(prr3::Model{robot}, Error);
}

const std::string kTrajectory = R"(duration: 0.3
x:     {offset: 0.001, harmonics: [{amplitude: -0.002, frequency: 10, phase: 0.5235987755982988}]}
theta: {harmonics: [{amplitude: 0.05, frequency: 5}, {amplitude: 0.01, frequency: 20, phase: 1}]}
)";

TEST(TrajectoryFile, ParsesAxesHarmonicsAndDefaults) {
    const PoseTrajectory trajectory = io::parseTrajectory(kTrajectory, "t.yaml");
    ASSERT_TRUE(trajectory.duration.has_value());
    EXPECT_EQ(*trajectory.duration, 0.3);
    EXPECT_EQ(trajectory.x.offset, 0.001);
    ASSERT_EQ(trajectory.theta.harmonics.size(), 2u);
    EXPECT_EQ(trajectory.theta.harmonics[1].phase, 1.0);
    EXPECT_EQ(trajectory.theta.harmonics[0].phase, 0.0);
    EXPECT_TRUE(trajectory.y.harmonics.empty());
    EXPECT_EQ(trajectory.y.offset, 0.0);
    Pose p, dp, ddp;
    trajectory.evaluate(0.0125, p, dp, ddp);
    EXPECT_DOUBLE_EQ(p(1), 0.001 - 0.002 * std::sin(2 * M_PI * 10 * 0.0125 + 0.5235987755982988));
}

TEST(TrajectoryFile, ShippedPaperFilesEqualTheBuiltIns) {
    for (const char* name : {"paper1", "paper2"}) {
        const PoseTrajectory file = io::loadTrajectory(std::string(NOCDYN_SOURCE_DIR) + "/trajectories/" + name + ".yaml");
        const PoseTrajectory builtin = io::trajectoryByNameOrFile(name);
        for (double t : {0.0, 0.0123, 0.1, 0.17}) {
            Pose a, da, dda, b, db, ddb;
            file.evaluate(t, a, da, dda);
            builtin.evaluate(t, b, db, ddb);
            EXPECT_LT((a - b).norm() + (da - db).norm() + (dda - ddb).norm(), 1e-12) << name << " t = " << t;
        }
    }
}

void expectTrajectoryError(const std::string& text, std::initializer_list<const char*> fragments) {
    try {
        (void)io::parseTrajectory(text, "t.yaml");
        ADD_FAILURE() << "accepted:\n" << text;
    } catch (const Error& e) {
        for (const char* fragment : fragments) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what() << "\nmissing: " << fragment;
        }
    }
}

TEST(TrajectoryFile, BadInputsNameFieldAndLine) {
    expectTrajectoryError("z: {offset: 1}\n", {"t.yaml:1", "z", "unknown key"});
    expectTrajectoryError("duration: -1\n", {"duration", "> 0"});
    expectTrajectoryError("duration: soon\n", {"duration", "'soon'"});
    expectTrajectoryError("x: {harmonics: [{frequency: 3}]}\n", {"x.harmonics[0].amplitude", "missing"});
    expectTrajectoryError("x: {harmonics: [{amplitude: 1, frequency: -3}]}\n", {"x.harmonics[0].frequency", ">= 0"});
    expectTrajectoryError("x:\n  harmonics:\n    - {amplitude: 1, frequency: 3, phse: 1}\n",
                          {"t.yaml:3", "x.harmonics[0].phse", "unknown key"});
    expectTrajectoryError("x: {harmonics: 3}\n", {"x.harmonics", "list"});
}

TEST(Csv, WritesDoublesThatReadBackExactly) {
    const std::string path = testing::TempDir() + "/roundtrip.csv";
    io::Table table{{"t", "value"}, {{0.1, 1.0 / 3.0}, {0.2, -2.5e-300}}};
    io::writeCsvFile(path, table);
    const io::Table back = io::readCsvFile(path);
    ASSERT_EQ(back.columns, table.columns);
    ASSERT_EQ(back.rows.size(), 2u);
    EXPECT_EQ(back.rows[0][1], 1.0 / 3.0);
    EXPECT_EQ(back.rows[1][1], -2.5e-300);
    EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

TEST(Csv, RaggedRowsAndNonNumbersAreErrorsWithTheLine) {
    const std::string path = testing::TempDir() + "/bad.csv";
    std::ofstream(path) << "t,tau1\n0,1\n0.1,abc\n";
    try {
        (void)io::readCsvFile(path);
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.csv:3: column 'tau1'"), std::string::npos) << e.what();
    }
    std::ofstream(path) << "t,tau1\n0,1,2\n";
    EXPECT_THROW((void)io::readCsvFile(path), Error);
    EXPECT_THROW((void)io::readCsvFile("/nonexistent.csv"), Error);
}

TEST(Csv, UnwritablePathLeavesNothingBehind) {
    EXPECT_THROW(io::writeCsvFile("/nonexistent-dir/x.csv", io::Table{{"t"}, {{1.0}}}), Error);
}

}  // namespace
}  // namespace nocdyn::test
