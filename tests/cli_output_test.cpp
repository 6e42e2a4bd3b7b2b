// The `nocdyn` binary's outputs: figures whose texts come from files never run anything, files
// are replaced safely (never through a planted link, never half written), special files and
// stdout are written straight through and every write is checked.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cli_support.hpp"
#include "skip.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/layouts.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

fs::path scratchDirectory() { return freshScratchDirectory("nocdyn_cli_output_test"); }

/// `text` as a double-quoted YAML scalar.
std::string yamlQuoted(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        if (c == '\n') {
            out += "\\n";
        } else {
            if (c == '"' || c == '\\') out += '\\';
            out += c;
        }
    }
    return out + "\"";
}

/// Names that would run `touch DIR/PWNED` if they reached gnuplot as code.
std::vector<std::string> hostileNames(const fs::path& dir) {
    const std::string touch = "touch " + (dir / "PWNED").string();
    return {"x\n!" + touch + " #",
            "x`" + touch + "`y",
            "x\" . system(\"" + touch + "\") . \"",
            "x' . system('" + touch + "') . '",
            "a = '" + touch + "'\n@a",
            "back\\slash\\ \"quote\" 'single' \\n @macro `" + touch + "`\\"};
}

std::string robotNamed(const std::string& name) {
    std::ifstream in(std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    return "name: " + yamlQuoted(name) + "\n" + text.substr(text.find("geometry:"));
}

void expectFigureDrawn(const fs::path& stem) {
    const fs::path png = stem.string() + ".png", svg = stem.string() + ".svg";
    ASSERT_TRUE(fs::is_regular_file(png)) << png;
    EXPECT_GT(fs::file_size(png), 1000u);
    const std::string drawing = readWhole(svg);
    EXPECT_NE(drawing.find("<svg"), std::string::npos);
    EXPECT_NE(drawing.find("</svg>"), std::string::npos);
}

TEST(CliOutput, RobotNameInAFigureIsShownNeverRun) {
    const fs::path dir = scratchDirectory();
    int index = 0;
    for (const std::string& name : hostileNames(dir)) {
        const fs::path robot = dir / ("robot" + std::to_string(index) + ".yaml");
        std::ofstream(robot) << robotNamed(name);
        const fs::path stem = dir / ("envelope" + std::to_string(index++));
        const CliResult r = runCli("envelope --points 2 --robot " + robot.string() + " --figure " + stem.string() +
                                   " -o " + (dir / "envelope.csv").string());
        ASSERT_EQ(r.exit_code, 0) << name << "\n" << r.err;
        EXPECT_FALSE(fs::exists(dir / "PWNED")) << name;
        expectFigureDrawn(stem);
        // The title carries the name's text (newlines shown as '?').
        EXPECT_NE(readWhole(stem.string() + ".svg").find("touch " + (dir / "PWNED").string()), std::string::npos)
            << name;
    }
}

TEST(CliOutput, TrajectoryNameInAFigureIsShownNeverRun) {
    const fs::path dir = scratchDirectory();
    int index = 0;
    for (const std::string& name : hostileNames(dir)) {
        const fs::path trajectory = dir / ("trajectory" + std::to_string(index) + ".yaml");
        std::ofstream(trajectory) << "name: " << yamlQuoted(name)
                                  << "\nduration: 0.01\nx: {harmonics: [{amplitude: 0.001, frequency: 10}]}\n";
        const fs::path stem = dir / ("control" + std::to_string(index++));
        const CliResult r =
            runCli("control --plant nocdyn --trajectory " + trajectory.string() + " --figure " + stem.string());
        ASSERT_EQ(r.exit_code, 0) << name << "\n" << r.err;
        EXPECT_FALSE(fs::exists(dir / "PWNED")) << name;
        expectFigureDrawn(stem);
        EXPECT_NE(readWhole(stem.string() + ".svg").find("touch " + (dir / "PWNED").string()), std::string::npos)
            << name;
    }
}

TEST(CliOutput, PlantedLinksNeverRedirectAWrite) {
    const fs::path dir = scratchDirectory();
    std::ofstream(dir / "victim.txt") << "keep";
    for (const char* planted : {"out.csv.partial", "envelope.gp", "envelope.png.partial"}) {
        fs::create_symlink(dir / "victim.txt", dir / planted);
    }
    const CliResult r =
        runCli("inverse-dynamics --trajectory paper1 --duration 0.01 --rate 1000 -o " + (dir / "out.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CliResult figure = runCli("envelope --points 2 --figure " + (dir / "envelope").string());
    ASSERT_EQ(figure.exit_code, 0) << figure.err;
    EXPECT_EQ(readWhole(dir / "victim.txt"), "keep");
    EXPECT_EQ(io::readCsvFile((dir / "out.csv").string()).rows.size(), 10u);
    expectFigureDrawn(dir / "envelope");
    // Only what was planted and what was asked for: no temporary file is left.
    std::size_t count = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
        ++count;
    }
    EXPECT_EQ(count, 7u);
}

TEST(CliOutput, OutputThatIsAFifoIsWrittenThroughAndStaysAFifo) {
    const fs::path dir = scratchDirectory();
    const fs::path fifo = dir / "pipe.csv";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Held open for reading and writing: opening never blocks and the rows wait in the pipe
    // (10 rows fit in its buffer), so a run that replaces the FIFO fails here instead of hanging.
    const int fd = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
    ASSERT_GE(fd, 0);
    const CliResult r = runCli("inverse-dynamics --trajectory paper1 --duration 0.01 --rate 1000 -o " + fifo.string());
    std::string received;
    char buffer[4096];
    for (ssize_t n = 0; (n = ::read(fd, buffer, sizeof buffer)) > 0;)
        received.append(buffer, static_cast<std::size_t>(n));
    ::close(fd);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::is_fifo(fifo));
    std::ofstream(dir / "copy.csv") << received;
    EXPECT_EQ(io::readCsvFile((dir / "copy.csv").string()).rows.size(), 10u);
}

TEST(CliOutput, FullDeviceFailsWithOneLineAndExitOne) {
    if (!fs::is_character_file("/dev/full")) NOCDYN_SKIP_OR_FAIL_IN_CI("no /dev/full");
    for (const char* redirect : {"> /dev/full", "-o /dev/full"}) {
        const CliResult r = runCli(std::string("inverse-dynamics --trajectory paper1 ") + redirect);
        EXPECT_EQ(r.exit_code, 1) << redirect;
        EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    const CliResult pose = runCli("pose 0 0 0 > /dev/full");
    EXPECT_EQ(pose.exit_code, 1);
    EXPECT_NE(pose.err.find("standard output"), std::string::npos) << pose.err;
    EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(CliOutput, ConcurrentRunsOnOneOutputEachSucceedAndLeaveOneCompleteCsv) {
    const fs::path dir = scratchDirectory();
    const fs::path out = dir / "same.csv";
    auto command = [&](int rate) {
        return std::string(NOCDYN_CLI) + " inverse-dynamics --trajectory paper1 --rate " + std::to_string(rate) +
               " -o " + out.string() + " 2>/dev/null";
    };
    for (int round = 0; round < 3; ++round) {
        // Different contents (10000 and 4000 rows), each run's own exit status.
        const std::string both = command(50000) + " & a=$!; " + command(20000) + " & b=$!; wait $a && wait $b";
        ASSERT_EQ(std::system(both.c_str()), 0) << both;
        const io::Table table = io::readCsvFile(out.string());
        const double rate = table.rows.size() == 10000u ? 50000.0 : 20000.0;
        ASSERT_TRUE(table.rows.size() == 10000u || table.rows.size() == 4000u) << table.rows.size();
        for (std::size_t k = 0; k < table.rows.size(); ++k) {
            ASSERT_EQ(table.rows[k][0], static_cast<double>(k) / rate) << "row " << k << ": not one run's output";
        }
        EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    }
}

/// A trajectory file with one harmonic on x.
fs::path harmonicFile(const fs::path& dir, const std::string& name, const std::string& harmonic) {
    const fs::path path = dir / name;
    std::ofstream(path) << "x: {harmonics: [" << harmonic << "]}\n";
    return path;
}

TEST(CliOutput, AliasingRateIsRefusedNamingTheRateNeeded) {
    const fs::path dir = scratchDirectory();
    const fs::path trajectory = harmonicFile(dir, "fast.yaml", "{amplitude: 1.0e-3, frequency: 1000}");
    const CliResult r = runCli("inverse-dynamics --trajectory " + trajectory.string() +
                               " --duration 0.01 --rate 1000 -o " + (dir / "out.csv").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("use a rate above 2000 Hz"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
    const CliResult control =
        runCli("control --plant nocdyn --trajectory " + trajectory.string() + " --duration 0.01 --rate 1000");
    EXPECT_EQ(control.exit_code, 1);
    EXPECT_NE(control.err.find("use a rate above 2000 Hz"), std::string::npos) << control.err;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(CliOutput, ForcePeakBetweenOutputSamplesIsAnErrorAndLeavesNoFile) {
    const fs::path dir = scratchDirectory();
    // 250 Hz at 1 kHz, 45 degrees of phase: every output sample is within the 262 N.
    const fs::path trajectory =
        harmonicFile(dir, "between.yaml", "{amplitude: 4.5e-5, frequency: 250, phase: 0.7853981633974483}");
    const CliResult r = runCli("inverse-dynamics --trajectory " + trajectory.string() +
                               " --duration 0.02 --rate 1000 -o " + (dir / "out.csv").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("effort limit exceeded"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("between output samples"), std::string::npos) << r.err;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(CliOutput, AllowLimitsNeverWritesANonFiniteNumber) {
    const fs::path dir = scratchDirectory();
    const fs::path trajectory = harmonicFile(dir, "overflow.yaml", "{amplitude: 1.0e-3, frequency: 1.0e160}");
    const std::string args =
        "inverse-dynamics --allow-limits --trajectory " + trajectory.string() + " --duration 1e-157 --rate 3e160";
    // refused before anything is computed (the duration and rate are outside their accepted
    // ranges) or, were they accepted, when the motion overflows: never a file, never a NaN
    const CliResult file = runCli(args + " -o " + (dir / "out.csv").string());
    EXPECT_NE(file.exit_code, 0);
    EXPECT_NE(file.err.find("finite"), std::string::npos) << file.err;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
    const CliResult out = runCli(args);
    EXPECT_NE(out.exit_code, 0);
    EXPECT_EQ(out.out.find("nan"), std::string::npos) << out.out;
    EXPECT_EQ(out.out.find("inf"), std::string::npos) << out.out;
}

TEST(CliOutput, StreamedCsvOnStdoutEqualsTheFileAndReadsBack) {
    const fs::path dir = scratchDirectory();
    const std::string args = "inverse-dynamics --trajectory paper2 --duration 0.05 --rate 20000";
    const CliResult out = runCli(args);
    const CliResult file = runCli(args + " -o " + (dir / "out.csv").string());
    ASSERT_EQ(out.exit_code, 0) << out.err;
    ASSERT_EQ(file.exit_code, 0) << file.err;
    EXPECT_EQ(out.out, readWhole(dir / "out.csv"));
    const io::Table table = io::readCsvFile((dir / "out.csv").string());
    ASSERT_EQ(table.rows.size(), 1000u);
    EXPECT_EQ(table.rows[999][table.column("t")], 999.0 / 20000.0);
}

// Any robot file: task-space control on nocdyn's forward dynamics, n actuators in the CSV and
// the summary; an encoder-noise option without the encoders is refused with one line naming
// the replacement.
TEST(CliOutput, ControlTakesAnyRobotFile) {
    const fs::path dir = scratchDirectory();
    const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/4-rrr.yaml";
    const fs::path out = dir / "control.csv";
    const CliResult r = runCli("control --plant nocdyn --robot " + robot +
                               " --trajectory paper1 --duration 0.02 --payload-mass 0.3 --payload-com 0.01 -0.005"
                               " -o " +
                               out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("computed-torque on the nocdyn forward dynamics plant, 4-rrr, paper1"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("payload unknown to the controller"), std::string::npos);
    EXPECT_NE(r.out.find("actuator 4 (limb 4): RMS error"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("saturated ticks: 0 of 200"), std::string::npos) << r.out;
    const io::Table table = io::readCsvFile(out.string());
    ASSERT_EQ(table.rows.size(), 200U);
    ASSERT_EQ(table.columns.size(), 22U);
    EXPECT_EQ(table.columns, io::columnNames(io::TableId::closed_loop, {.actuators = 4}));
    EXPECT_EQ(table.columns[9], "e_theta");  // the pose in the order x, y, theta
    EXPECT_EQ(table.columns.back(), "tau4");
    for (const auto& row : table.rows) {
        // each error is the desired value minus the achieved one, in the same pose order
        for (const char* axis : {"x", "y", "theta"}) {
            const std::string a(axis);
            EXPECT_DOUBLE_EQ(row[table.column("e_" + a)], row[table.column(a + "_d")] - row[table.column(a)]) << a;
        }
    }
    for (const auto& row : table.rows) {
        for (const double v : row) EXPECT_TRUE(std::isfinite(v));
        for (std::size_t a = 18; a < 22; ++a) EXPECT_LE(std::abs(row[a]), 12.0);  // effort [N m]
    }
    const CliResult noise_u = runCli("control --plant nocdyn --robot " + robot + " --trajectory paper1 --noise-u 1e-6");
    EXPECT_EQ(noise_u.exit_code, 1);
    EXPECT_NE(noise_u.err.find("use --noise-pose and --noise-rate"), std::string::npos) << noise_u.err;
    EXPECT_EQ(std::count(noise_u.err.begin(), noise_u.err.end(), '\n'), 1) << noise_u.err;
    // The default robot (the short form, expanded) takes every option a general robot file takes.
    const fs::path log = dir / "log.csv";
    const CliResult fallback = runCli(
        "control --plant nocdyn --trajectory paper1 --duration 0.02 --noise-pose 1e-6 --payload-mass 0.5 "
        "--payload-com 0.012 -0.007 --noise-u 1e-6 --noise-tau 0.5 --log " +
        log.string());
    ASSERT_EQ(fallback.exit_code, 0) << fallback.err;
    EXPECT_NE(fallback.out.find("computed-torque on the nocdyn forward dynamics plant, paper-3prr, paper1"),
              std::string::npos)
        << fallback.out;
    EXPECT_NE(fallback.out.find("actuator 3 (limb 3): RMS error"), std::string::npos) << fallback.out;
    const io::Table sensors = io::readCsvFile(log.string());
    // the forces are the commands held over each tick, and the log says so
    EXPECT_EQ(sensors.columns,
              (std::vector<std::string>{"t", "u1", "u2", "u3", "tau1_held", "tau2_held", "tau3_held"}));
    EXPECT_EQ(sensors.rows.size(), 200U);
}

}  // namespace
}  // namespace nocdyn::test
