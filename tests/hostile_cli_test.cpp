// Hostile input to the command line, round two: each case the exact input that once gave a
// confident wrong answer, an unbounded cost or a broken file, now a clear error or a correct
// result.
#include <gtest/gtest.h>

#include "nocdyn/detail/sanitizer.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/description.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/io/robot_file.hpp"

extern char** environ;

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kSource = NOCDYN_SOURCE_DIR;
const std::string kRobot = kSource + "/robots/paper-3prr-general.yaml";

void writeFile(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

/// The general paper robot with its name replaced (the YAML scalar given as it stands).
std::string robotNamed(const std::string& yaml_name) {
    std::string text = readWhole(kRobot);
    const auto at = text.find("name: paper-3prr\n");
    EXPECT_NE(at, std::string::npos);
    return text.replace(at, std::string("name: paper-3prr\n").size(), "name: " + yaml_name + "\n");
}

TEST(HostileCli, IdentifyOnATranslationAlongXAloneIsAnErrorNamingWhatItCannotSee) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    writeFile(dir / "loaded.yaml", [] {
        // the paper's robot carrying the payload (0.5 kg at (12, -7) mm, 8e-4 kg m^2)
        RobotDescription robot = io::loadRobotDescription(kRobot);
        robot = withPayload(robot, Payload{0.5, 8e-4, Vector2(0.012, -0.007)});
        return io::descriptionToYaml(robot);
    }());
    writeFile(dir / "xonly.yaml",
              "name: xonly\nduration: 1\nx: {offset: 0.0, harmonics: [{amplitude: 0.002, frequency: 5, phase: 0}]}\n");
    const CliResult id = runCli("inverse-dynamics --robot " + (dir / "loaded.yaml").string() + " --trajectory " +
                                (dir / "xonly.yaml").string() + " --rate 1000 -o " + (dir / "x.csv").string());
    ASSERT_EQ(id.exit_code, 0) << id.err;
    const CliResult r = runCli("identify --robot " + kRobot + " --data " + (dir / "x.csv").string() + " --payload");
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_EQ(r.out.find("payload:"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("payload inertia"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("payload c.o.m. x"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not identifiable"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("payload mass 0.5 kg"), std::string::npos) << r.err;
}

TEST(HostileCli, ShakeRefusesAnAllZeroRecord) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    std::string record = "zeros\nzeros\nThe units are (g)\nNPTS=  64, DT= .01000 SEC\n";
    for (int k = 0; k < 8; ++k)
        record += "   0.00000   0.00000   0.00000   0.00000   0.00000   0.00000   0.00000   0.00000\n";
    writeFile(dir / "zero.AT2", record);
    const CliResult r = runCli("shake --robot " + kRobot + " --record " + (dir / "zero.AT2").string() + " --out-dir " +
                               (dir / "out").string());
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_NE(r.err.find("zero.AT2: every acceleration is zero"), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("RMS error"), std::string::npos) << r.out;
}

TEST(HostileCli, ConvertWritesOddNamesThatReadBackTheSame) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    // YAML double-quoted scalars: a newline, a key, a comment, quotes, a backslash, a tab,
    // ESC, "]]>" and UTF-8
    const std::string names[][2] = {{"\"a: b\"", "a: b"},
                                    {"\"# hash\"", "# hash"},
                                    {"\"two\\nlines: x\"", "two\nlines: x"},
                                    {"\"it's \\\"q\\\"\"", "it's \"q\""},
                                    {"\"back\\\\slash\"", "back\\slash"},
                                    {"\"tab\\there\"", "tab\there"},
                                    {"\"esc\\x1b]0;t\\x07\"", "esc\x1b]0;t\x07"},
                                    {"\"]]> & <x>\"", "]]> & <x>"},
                                    {"\"- [x, {y}]\"", "- [x, {y}]"},
                                    {"\"gr\xC3\xBC\xC3\x9F\"", "gr\xC3\xBC\xC3\x9F"}};
    for (const auto& [yaml, name] : names) {
        writeFile(dir / "odd.yaml", robotNamed(yaml));
        ASSERT_EQ(io::loadRobotDescription((dir / "odd.yaml").string()).name, name) << yaml;
        const CliResult r = runCli("convert " + (dir / "odd.yaml").string() + " -o " + (dir / "back.yaml").string());
        ASSERT_EQ(r.exit_code, 0) << yaml << ": " << r.err;
        const RobotDescription back = io::loadRobotDescription((dir / "back.yaml").string());
        EXPECT_EQ(back.name, name) << yaml << "\n" << readWhole(dir / "back.yaml");
        const std::string text = readWhole(dir / "back.yaml");
        EXPECT_EQ(text.find('\x1b'), std::string::npos) << yaml;
        EXPECT_EQ(text.find('\x07'), std::string::npos) << yaml;
    }
}

TEST(HostileCli, IdentifyWritesARobotWithAnOddNameThatReadsBackTheSame) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    const std::string name = "two\nlines: # x \"q\" ]]>";
    RobotDescription robot = io::loadRobotDescription(kRobot);
    robot.name = name;
    writeFile(dir / "odd.yaml", io::descriptionToYaml(robot));
    writeFile(dir / "loaded.yaml",
              io::descriptionToYaml(withPayload(robot, Payload{0.5, 8e-4, Vector2(0.012, -0.007)})));
    const CliResult id = runCli("inverse-dynamics --robot " + (dir / "loaded.yaml").string() +
                                " --trajectory paper1 --rate 1000 -o " + (dir / "log.csv").string());
    ASSERT_EQ(id.exit_code, 0) << id.err;
    const CliResult r = runCli("identify --robot " + (dir / "odd.yaml").string() + " --data " +
                               (dir / "log.csv").string() + " -o " + (dir / "out.yaml").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const RobotDescription back = io::loadRobotDescription((dir / "out.yaml").string());
    EXPECT_EQ(back.name, name + " + payload") << readWhole(dir / "out.yaml");  // as withPayload names it
    EXPECT_NEAR(back.platform.mass, robot.platform.mass + 0.5, 1e-9);
}

TEST(HostileCli, ErrorMessagesShowControlBytesEscaped) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    // an unknown key holding ESC ] 0 ; ... BEL (a terminal's set-title sequence)
    std::string text = readWhole(kRobot) + "\"x\\e]0;owned\\a\": 1\n";
    writeFile(dir / "bad.yaml", text);
    const CliResult r = runCli("convert " + (dir / "bad.yaml").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\x07'), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("\\x1B]0;owned\\x07"), std::string::npos) << r.err;
}

TEST(HostileCli, RobotAndTrajectoryNamesOnStdoutShowControlBytesEscaped) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    writeFile(dir / "odd.yaml", robotNamed("\"x\\e]0;owned\\a\""));
    const CliResult r = runCli("forward-kinematics 0 0 0 --robot " + (dir / "odd.yaml").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find('\x07'), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("robot x\\x1B]0;owned\\x07"), std::string::npos) << r.out;
}

TEST(HostileCli, SvgOfARobotNamedWithACdataEndIsWellFormed) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    writeFile(dir / "odd.yaml", robotNamed("\"a]]>b <c> & d\""));
    const CliResult r = runCli("animate --robot " + (dir / "odd.yaml").string() +
                               " --trajectory paper1 --duration 0.01 --frame 0 --svg " + (dir / "f.svg").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string svg = readWhole(dir / "f.svg");
    ASSERT_FALSE(svg.empty());
    EXPECT_EQ(svg.find("]]>"), std::string::npos);
    // parsed by Python's XML parser (expat): well-formed
    const CliResult xml = runCli(
        "--version >/dev/null; /usr/bin/python3 -c \"import sys, xml.dom.minidom; "
        "xml.dom.minidom.parse(sys.argv[1]); print('ok')\" " +
        (dir / "f.svg").string() + " #");
    EXPECT_NE(xml.out.find("ok"), std::string::npos) << xml.err;
}

TEST(HostileCli, SimulateRefusesAForceColumnBeyondTheActuators) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    writeFile(dir / "f.csv", "t,tau1,tau2,tau3,tau4\n0,0,0,0,5\n0.01,0,0,0,5\n");
    const CliResult r = runCli("simulate --robot " + kRobot + " --forces " + (dir / "f.csv").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("f.csv: column 'tau4'"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
}

TEST(HostileCli, AnEmptyOutputNameIsAnErrorNotStandardOutput) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    writeFile(dir / "f.csv", "t,tau1,tau2,tau3\n0,0,0,0\n0.01,0,0,0\n");
    for (const std::string& command : std::vector<std::string>{
             "simulate --robot " + kRobot + " --forces " + (dir / "f.csv").string() + " -o ''",
             std::string("inverse-dynamics --trajectory paper1 -o ''"), "convert " + kRobot + " -o ''"}) {
        const CliResult r = runCli(command);
        EXPECT_EQ(r.exit_code, 2) << command;
        EXPECT_TRUE(r.out.empty()) << command;
        EXPECT_NE(r.err.find("empty file name"), std::string::npos) << r.err;
    }
}

TEST(HostileCli, AnimateRefusesToOverwriteItsOwnInput) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    fs::copy_file(kRobot, dir / "robot.yaml");
    const std::string before = readWhole(dir / "robot.yaml");
    const CliResult r = runCli("animate --robot " + (dir / "robot.yaml").string() +
                               " --trajectory paper1 --duration 0.01 --frame 0 --png " + (dir / "robot.yaml").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("--png"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("is an input file"), std::string::npos) << r.err;
    EXPECT_EQ(readWhole(dir / "robot.yaml"), before);
}

TEST(HostileCli, ThirtyThousandHarmonicsOverALongDurationAreRefusedWithAnEstimate) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    std::string text = "name: many\nduration: 100\n";
    for (const char* axis : {"x", "y", "theta"}) {
        text += std::string(axis) + ": {offset: 0, harmonics: [";
        for (int k = 1; k <= 10000; ++k)
            text += (k > 1 ? "," : "") + std::string("{amplitude: 1e-9, frequency: ") + std::to_string(k) + "}";
        text += "]}\n";
    }
    writeFile(dir / "many.yaml", text);
    const auto start = std::chrono::steady_clock::now();
    const CliResult r = runCli("inverse-dynamics --robot " + kRobot + " --trajectory " + (dir / "many.yaml").string() +
                               " --rate 25000 -o " + (dir / "out.csv").string());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("30000 harmonics"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("h of computing"), std::string::npos) << r.err;
    EXPECT_LT(seconds, 30.0);
    EXPECT_FALSE(fs::exists(dir / "out.csv"));
}

/// A forces file of `rows` short rows (t and three zero forces at 10 kHz).
void writeShortRows(const fs::path& path, int rows) {
    std::ofstream out(path);
    out << "t,tau1,tau2,tau3\n";
    char line[64];
    for (int k = 0; k < rows; ++k) {
        std::snprintf(line, sizeof line, "%.4f,0,0,0\n", k * 1e-4);
        out << line;
    }
}

TEST(HostileCli, SimulateOnTwoMillionShortRowsPeaksBelow300MB) {
    const fs::path dir = freshScratchDirectory("hostile_cli");
    writeShortRows(dir / "big.csv", 2'000'000);
    const CliResult r = runCli("simulate --robot " + kRobot + " --forces " + (dir / "big.csv").string() +
                               " --duration 0.01 -o " + (dir / "out.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    rusage usage{};
    ASSERT_EQ(getrusage(RUSAGE_CHILDREN, &usage), 0);
#if NOCDYN_ASAN()
    // AddressSanitizer's shadow memory, redzones and quarantine triple the resident set (496 MB
    // measured where the release build peaks at 163 MB); the per-row growth this guards against
    // (903 MB in a release build) would be about 2.7 GB here.
    constexpr long kLimitKiB = 3L * 300 * 1024;
#else
    constexpr long kLimitKiB = 300L * 1024;
#endif
    EXPECT_LT(usage.ru_maxrss, kLimitKiB) << "peak resident set of the children: " << usage.ru_maxrss << " KiB";
}

TEST(HostileCli, SigtermAndSigintLeaveNoTemporaryFile) {
    for (const int signal_number : {SIGTERM, SIGINT}) {
        const fs::path dir = freshScratchDirectory("hostile_cli");
        writeShortRows(dir / "f.csv", 1000);
        // a long simulation writing its CSV: interrupted once its temporary file exists
        const std::string forces = (dir / "f.csv").string(), output = (dir / "big.csv").string();
        const std::string cli = NOCDYN_CLI;
        const char* argv[] = {cli.c_str(),    "simulate",     "--robot", kRobot.c_str(), "--forces",
                              forces.c_str(), "--duration",   "1000",    "--rate",       "10000",
                              "-o",           output.c_str(), nullptr};
        pid_t pid = 0;
        ASSERT_EQ(posix_spawn(&pid, cli.c_str(), nullptr, nullptr, const_cast<char**>(argv), environ), 0);
        const auto temporary = [&] {
            for (const auto& entry : fs::directory_iterator(dir))
                if (entry.path().extension() == ".tmp") return true;
            return false;
        };
        for (int i = 0; i < 2000 && !temporary(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        ASSERT_TRUE(temporary()) << "no temporary file appeared";
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        kill(pid, signal_number);
        int status = 0;
        ASSERT_EQ(waitpid(pid, &status, 0), pid);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal_number) << status;
        EXPECT_FALSE(temporary()) << "signal " << signal_number;
        EXPECT_FALSE(fs::exists(dir / "big.csv")) << "signal " << signal_number;
    }
}

}  // namespace
}  // namespace nocdyn::test
