// Robot and trajectory files and CSV tables: the shipped files, and every class of bad
// input with the field and line named in the error.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/tables/forces.hpp"
#include "nocdyn/io/robot_yaml.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/description.hpp"
#include "nocdyn/model.hpp"

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
    const io::RobotParameters file = io::loadRobot(std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr.yaml");
    const io::RobotParameters builtin;
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
    io::RobotParameters robot;
    robot.name = "odd";
    robot.link_mass = 0.123456789012345678;
    robot.max_condition = 5e3;
    const io::RobotParameters back = io::parseRobot(io::robotToYaml(robot), "x.yaml");
    EXPECT_EQ(back.name, "odd");
    EXPECT_EQ(back.link_mass, robot.link_mass);
    EXPECT_EQ(back.max_condition, robot.max_condition);
}

TEST(RobotFile, NameDefaultsToTheFileStem) {
    const io::RobotParameters robot = io::parseRobot(replaced(kRobot, "name: test-robot\n", ""), "dir/my-robot.yaml");
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
    expectRobotError(replaced(kRobot, "link_length: 0.15915", "link_length: 0.08"),
                     {"cannot be assembled", "link_length"});
    expectRobotError(replaced(kRobot, "platform_side: 0.110", "platform_side: 0.5"),
                     {"cannot be assembled", "platform"});
}

TEST(RobotFile, MalformedYamlNamesTheLine) {
    expectRobotError("geometry: {base_side: 0.4\nslider: [", {"robot.yaml:", "not valid YAML"});
    expectRobotError("- just\n- a list\n", {"robot.yaml", "mapping"});
}

TEST(RobotFile, MissingFileIsAnError) { EXPECT_THROW((void)io::loadRobot("/nonexistent/robot.yaml"), Error); }

TEST(RobotModel, InvalidParametersThroughTheLibraryThrow) {
    io::RobotParameters robot;
    robot.link_inertia = -1.0;
    EXPECT_THROW((void)Model(expand(robot)), Error);
    robot = io::RobotParameters{};
    robot.max_condition = 0.5;
    EXPECT_THROW((void)Model(expand(robot)), Error);
}

TEST(RobotFile, DuplicateKeysSectionsAndDocumentsAreErrors) {
    expectRobotError(replaced(kRobot, "  link_com: 0.079575\n", "  link_com: 0.079575\n  link_com: 0.05\n"),
                     {"robot.yaml:7", "geometry.link_com", "duplicate key", "line 6"});
    expectRobotError(kRobot + "slider: {mass: 3}\n", {"robot.yaml:11", "slider", "duplicate key", "line 7"});
    expectRobotError(kRobot + "---\nname: second\n", {"robot.yaml:11", "second YAML document"});
}

TEST(RobotFile, OnlyDecimalNumbersAreAccepted) {
    expectRobotError(replaced(kRobot, "0.15915", "0x1p-3"), {"robot.yaml:5", "geometry.link_length", "'0x1p-3'"});
    expectRobotError(replaced(kRobot, "0.15915", ".inf"), {"geometry.link_length", "finite"});
    expectRobotError(replaced(kRobot, "0.15915", "1e999"), {"geometry.link_length", "'1e999'", "beyond the range"});
    expectRobotError(replaced(kRobot, "0.15915", "1e-400"), {"geometry.link_length", "'1e-400'", "beyond the range"});
}

TEST(RobotFile, ByteOrderMarkIsAccepted) {
    const io::RobotParameters robot = io::parseRobot("\xEF\xBB\xBF" + kRobot, "robot.yaml");
    EXPECT_EQ(robot.name, "test-robot");
    EXPECT_EQ(robot.link_length, 0.15915);
}

TEST(RobotFile, RangeErrorsNameTheLineAndTheAcceptedRange) {
    // 1e308 is finite but its products overflow: refused by the plausibility range, on its line
    expectRobotError(replaced(kRobot, "inertia: 6.17311382e-3", "inertia: 1e308"),
                     {"robot.yaml:9", "platform.inertia", "[1e-15, 1e+12] kg m^2", "got 1e+308"});
    // a subnormal value is a number, only too small
    expectRobotError(replaced(kRobot, "{mass: 1.46966}", "{mass: 1e-310}"),
                     {"robot.yaml:7", "slider.mass", "got 1e-310"});
    try {
        (void)io::parseRobot(replaced(kRobot, "{mass: 1.46966}", "{mass: 1e-310}"), "robot.yaml");
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).find("finite"), std::string::npos) << e.what();
    }
    expectRobotError(replaced(kRobot, "link_com: 0.079575", "link_com: 0.2"), {"robot.yaml:6", "geometry.link_com"});
    expectRobotError(replaced(kRobot, "link_length: 0.15915", "link_length: 0.08"),
                     {"robot.yaml:5", "geometry.link_length", "cannot be assembled"});
    expectRobotError(kRobot + "limits: {max_condition: 1}\n", {"robot.yaml:11", "limits.max_condition"});
}

TEST(RobotModel, EveryRangeHoldsInTheLibraryToo) {
    io::RobotParameters robot;
    robot.platform_inertia = 1e308;
    try {
        const Model model(expand(robot));
        ADD_FAILURE() << "accepted platform.inertia = 1e308";
    } catch (const io::ParameterError& e) {
        EXPECT_EQ(e.field(), "platform.inertia");
    }
    robot = io::RobotParameters{};
    robot.link_mass = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW((void)Model(expand(robot)), io::ParameterError);
}

/// A scratch file of this test binary's temporary folder with the given content.
std::string scratchFile(const std::string& name, const std::string& content) {
    const std::string path = testing::TempDir() + "/" + name;
    std::ofstream(path, std::ios::binary | std::ios::trunc) << content;
    return path;
}

void expectFileError(const std::function<void()>& read, std::initializer_list<const char*> fragments) {
    try {
        read();
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        for (const char* fragment : fragments) {
            EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what() << "\nmissing: " << fragment;
        }
    }
}

TEST(InputFiles, SpecialFilesAreRefusedWithoutReading) {
    // /dev/zero never ends and a FIFO without writer blocks: both are refused at once.
    expectFileError([] { (void)io::readCsvFile("/dev/zero"); }, {"/dev/zero", "not a regular file"});
    expectFileError([] { (void)io::loadTrajectory("/dev/urandom"); }, {"/dev/urandom", "not a regular file"});
    expectFileError([] { (void)io::loadRobot("/dev/null"); }, {"not a regular file"});
    const std::string fifo = testing::TempDir() + "/reader_fifo";
    std::filesystem::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    expectFileError([&] { (void)io::readCsvFile(fifo); }, {"reader_fifo", "not a regular file"});
    std::filesystem::remove(fifo);
    expectFileError([] { (void)io::loadRobot(testing::TempDir()); }, {"not a regular file"});
}

TEST(InputFiles, OversizedFilesAreRefusedWithTheCap) {
    // sparse files: the size is refused before anything is read
    const std::string yaml = scratchFile("big.yaml", "");
    std::filesystem::resize_file(yaml, (std::uintmax_t{4} << 20) + 1);
    expectFileError([&] { (void)io::loadRobot(yaml); }, {"big.yaml", "larger than the 4 MiB accepted"});
    const std::string csv = scratchFile("big.csv", "");
    std::filesystem::resize_file(csv, (std::uintmax_t{256} << 20) + 1);
    expectFileError([&] { (void)io::readCsvFile(csv); }, {"big.csv", "larger than the 256 MiB accepted"});
    std::filesystem::remove(yaml);
    std::filesystem::remove(csv);
}

TEST(Csv, DuplicateColumnsHexFloatsAndNonFiniteCellsAreErrors) {
    expectFileError([] { (void)io::parseCsv("t,tau1,tau1\n0,1,2\n", "f.csv"); }, {"f.csv:1", "'tau1' appears twice"});
    expectFileError([] { (void)io::parseCsv("t,tau1\n0,0x1p3\n", "f.csv"); }, {"f.csv:2", "column 'tau1'", "'0x1p3'"});
    expectFileError([] { (void)io::parseCsv("t,tau1\n0,nan\n", "f.csv"); }, {"f.csv:2", "'nan'"});
    expectFileError([] { (void)io::parseCsv("t,tau1\n0,inf\n", "f.csv"); }, {"f.csv:2", "'inf'"});
    expectFileError([] { (void)io::parseCsv("t,,x\n0,1,2\n", "f.csv"); }, {"f.csv:1", "empty column name"});
}

TEST(Csv, CategoryColumnsAreWrittenAsWords) {
    io::Table table;
    table.columns = {"axis", "amplitude", "limit"};
    table.categories = {{"theta", "x", "y"}, {}, {"range", "effort"}};
    table.rows = {{1.0, 0.25, 1.0}, {0.0, 1e-3, 0.0}};
    std::ostringstream out;
    io::writeCsv(out, table);
    EXPECT_EQ(out.str(), "axis,amplitude,limit\nx,0.25,effort\ntheta,0.001,range\n");
    const auto path = std::filesystem::temp_directory_path() / "nocdyn_io_test_categories.csv";
    io::writeCsvFile(path.string(), table);
    std::ifstream file(path);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(file), {}), out.str());
    std::filesystem::remove(path);
    // a code without a name, or not a whole number, is an error naming the column
    for (const double code : {3.0, 0.5, -1.0}) {
        table.rows = {{code, 0.0, 0.0}};
        std::ostringstream ignored;
        expectFileError([&] { io::writeCsv(ignored, table); }, {"axis"});
    }
}

TEST(Csv, ByteOrderMarkIsSkipped) {
    const io::Table table = io::parseCsv("\xEF\xBB\xBFt,tau1\n0,1\n", "f.csv");
    ASSERT_EQ(table.columns.size(), 2u);
    EXPECT_EQ(table.columns[0], "t");
    EXPECT_TRUE(table.has("t"));
}

TEST(Csv, ErrorsNameTheRealLineAfterBlankLines) {
    expectFileError([] { (void)io::parseCsv("\nt,tau1\n\n0,1\n\n\n0.1,x\n", "f.csv"); }, {"f.csv:7:", "column 'tau1'"});
    // forcesFromTable reports the file's line of a time that does not increase
    const io::Table table = io::parseCsv("t,tau1,tau2,tau3\n\n0,1,2,3\n\n0.1,1,2,3\n0.1,1,2,3\n", "f.csv");
    EXPECT_EQ(table.lines, (std::vector<std::size_t>{3, 5, 6}));
    expectFileError([&] { (void)tables::forcesFromTable(table, 3, Interpolation::linear, "f.csv"); },
                    {"f.csv:6:", "column 't'", "does not increase"});
}

TEST(Csv, RowAndColumnCountsAreBounded) {
    std::string wide;
    for (std::size_t k = 0; k <= io::kMaxCsvColumns; ++k) wide += (k ? ",c" : "c") + std::to_string(k);
    expectFileError([&] { (void)io::parseCsv(wide + "\n", "f.csv"); }, {"f.csv:1", "columns, at most 256"});
    const std::string long_line = "t\n" + std::string(io::kMaxCsvLineBytes + 1, '1') + "\n";
    expectFileError([&] { (void)io::parseCsv(long_line, "f.csv"); }, {"f.csv:2", "line longer than"});
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
        const PoseTrajectory file =
            io::loadTrajectory(std::string(NOCDYN_SOURCE_DIR) + "/trajectories/" + name + ".yaml");
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
    expectTrajectoryError("x: {harmonics: [{amplitude: 1, frequency: -3}]}\n",
                          {"x.harmonics[0].frequency", "[0, 1e+06] Hz"});
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

TEST(Csv, UnwritablePathIsAnErrorNamingThePath) {
    try {
        io::writeCsvFile("/nonexistent-dir/x.csv", io::Table{{"t"}, {{1.0}}});
        ADD_FAILURE() << "writing into a missing folder succeeded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.csv"), std::string::npos) << e.what();
    }
}

TEST(Csv, AFailedWriteLeavesNothingBehindAndTheOldFileAsItWas) {
    // a row that cannot be written (not a finite number) fails the write after it has begun
    const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "failed_write";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const io::Table bad{{"t"}, {{1.0}, {std::numeric_limits<double>::quiet_NaN()}}};
    EXPECT_THROW(io::writeCsvFile((dir / "new.csv").string(), bad), Error);
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << "a failed write of a new file left a file in " << dir;
    std::ofstream(dir / "old.csv") << "t\n2\n";
    EXPECT_THROW(io::writeCsvFile((dir / "old.csv").string(), bad), Error);
    std::ifstream in(dir / "old.csv");
    const std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(old, "t\n2\n");
    int files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 1) << "a failed write over an old file left another file in " << dir;
}

TEST(TrajectoryFile, DuplicatesRangesAndSecondDocumentsAreErrors) {
    expectTrajectoryError("duration: 0.2\nduration: 0.3\n", {"t.yaml:2", "duration", "duplicate key"});
    expectTrajectoryError("x: {offset: 0}\nx: {offset: 1}\n", {"t.yaml:2", "x", "duplicate key"});
    expectTrajectoryError("x: {harmonics: [{amplitude: 1, frequency: 1e300}]}\n",
                          {"x.harmonics[0].frequency", "[0, 1e+06] Hz"});
    expectTrajectoryError("x: {harmonics: [{amplitude: 0x10, frequency: 1}]}\n",
                          {"x.harmonics[0].amplitude", "'0x10'"});
    expectTrajectoryError("duration: 0.2\n---\nduration: 0.3\n", {"t.yaml:2", "second YAML document"});
    // yaml-cpp 0.7 LoadAll never returns on a lone comma: refused, at once
    expectTrajectoryError(",", {"t.yaml:1", "second YAML document"});
    EXPECT_EQ(*io::parseTrajectory("\xEF\xBB\xBF"
                                   "duration: 0.25\n",
                                   "t.yaml")
                   .duration,
              0.25);
}

}  // namespace
}  // namespace nocdyn::test

namespace nocdyn {
namespace {

TEST(TrajectoryByName, AnUnknownNameSaysWhichNamesAreBuiltIn) {
    try {
        (void)io::trajectoryByNameOrFile("paper3");
        FAIL() << "paper3 is neither a file nor a built-in trajectory";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("'paper3'"), std::string::npos) << message;
        EXPECT_NE(message.find("paper1, paper2"), std::string::npos) << message;
    }
    EXPECT_EQ(io::trajectoryByNameOrFile("paper1").name, paperTrajectory1().name);
}

}  // namespace
}  // namespace nocdyn
