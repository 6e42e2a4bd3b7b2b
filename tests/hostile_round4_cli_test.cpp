// Hostile input, fourth round, at the command line: each test holds one finding of the review
// with its exact input. Outputs over inputs and over each other, options that do not apply,
// an unstable closed loop, names reaching the terminal raw, the mode shapes' layout in JSON,
// unclear option errors, help's edge cases, a rigid plant on a compliant robot, and a replay
// animated on another robot.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_support.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kSource = NOCDYN_SOURCE_DIR;
const std::string kCompliant = kSource + "/robots/paper-3prr-compliant.yaml";
const std::string kRrr = kSource + "/robots/3-rrr.yaml";
const std::string kRecord = kSource + "/data/elcentro_1940_ns.AT2";
/// A short, fast replay (as the parity tests play it).
const std::string kQuick = " --window 0.5 --plant nocdyn-rk4 --rate 1000";

void writeFile(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// The robot file's text with `from` replaced by `to` (the first occurrence).
std::string edited(const std::string& path, const std::string& from, const std::string& to) {
    std::string text = readWhole(path);
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

TEST(HostileRound4Cli, NoOutputReplacesAnInputOrAnotherOutput) {
    const fs::path dir = freshScratchDirectory("hostile_round4_cli");
    const fs::path robot = dir / "r.yaml";
    fs::copy_file(kCompliant, robot);
    const std::string original = readWhole(robot);
    const std::string base = "frequency-response --robot " + robot.string() + " --points 3";
    // --summary over the robot file it reads
    CliResult r = runCli(base + " --summary " + robot.string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(has(r.err, "--summary '" + robot.string() + "' is an input file (--robot")) << r.err;
    EXPECT_EQ(readWhole(robot), original);
    // the table and the summary in one file
    r = runCli(base + " -o " + (dir / "p.csv").string() + " --summary " + (dir / "p.csv").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(has(r.err, "is also written by --output")) << r.err;
    EXPECT_FALSE(fs::exists(dir / "p.csv"));
    // the same file by another spelling of its path
    r = runCli(base + " -o " + (dir / "q.csv").string() + " --summary " + (dir / "." / "q.csv").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    // the workspace table and the frequency map's CSV; the two figures on one stem
    const std::string workspace = "workspace --robot " + robot.string() + " --resolution 11 -q";
    r = runCli(workspace + " -o " + (dir / "m.csv").string() + " --frequency-map " + (dir / "m").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(has(r.err, "--frequency-map '" + (dir / "m.csv").string() + "' is also written by --output")) << r.err;
    r = runCli(workspace + " --figure " + (dir / "f").string() + " --frequency-map " + (dir / "f").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(has(r.err, "--frequency-map '" + (dir / "f.png").string() + "' is also written by --figure")) << r.err;
    EXPECT_FALSE(fs::exists(dir / "f.png"));
    // the frequency map's CSV over the robot file
    fs::copy_file(kCompliant, dir / "rob.csv");
    r = runCli("workspace --robot " + (dir / "rob.csv").string() + " --resolution 11 -q --frequency-map " +
               (dir / "rob").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(has(r.err, "is an input file (--robot")) << r.err;
    EXPECT_EQ(readWhole(dir / "rob.csv"), original);
    // an older command with two outputs: control's table and its sensor log
    r = runCli("control --trajectory paper1 --duration 0.002 --plant nocdyn-rk4 -o " + (dir / "c.csv").string() +
               " --log " + (dir / "c.csv").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(has(r.err, "is also written by")) << r.err;
    // a device is no file to replace: the table and the summary both to /dev/null are fine
    r = runCli(base + " -o /dev/null --summary /dev/null");
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(HostileRound4Cli, AnUnstableClosedLoopIsRefusedAndItsRatesAreShakes) {
    CliResult r = runCli(
        "frequency-response --closed-loop --natural-frequency 10000 --min-frequency 0.1 --max-frequency 4000 "
        "--points 50");
    EXPECT_EQ(r.exit_code, 1) << r.out;
    EXPECT_TRUE(has(r.err, "--closed-loop: unstable closed loop (spectral radius")) << r.err;
    EXPECT_TRUE(has(r.err, "lower --natural-frequency")) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    // the first feedback that diverges at the 10 kHz tick (measured: stable up to 1500 Hz)
    r = runCli("frequency-response --closed-loop --natural-frequency 2000 --max-frequency 100 --points 3");
    EXPECT_EQ(r.exit_code, 1) << r.out;
    // the radius as printed (1.01377 in the release build, 1.01368 under the sanitizers' -O1:
    // the eigenvalue of a loop just past its edge moves with the rounding)
    const std::size_t radius_at = r.err.find("max |eig F| = ");
    ASSERT_NE(radius_at, std::string::npos) << r.err;
    const double radius = std::stod(r.err.substr(radius_at + std::string("max |eig F| = ").size()));
    EXPECT_GT(radius, 1.01) << r.err;
    EXPECT_LT(radius, 1.02) << r.err;
    EXPECT_TRUE(has(r.err, " >= 1 at a tick of 10000 Hz with f_n = 2000 Hz")) << r.err;
    // the default loop is stable (|eig F| = 0.99626; the acceleration correction's sum at gain 0
    // holds eigenvalue 1 but no input reaches it), with or without a payload, and answers
    for (const std::string payload : {"0", "2", "100"}) {
        r = runCli("frequency-response --closed-loop --points 3 --max-frequency 2000 --payload-mass " + payload);
        EXPECT_EQ(r.exit_code, 0) << payload << "\n" << r.err;
    }
    EXPECT_EQ(runCli("frequency-response --closed-loop --points 3 --natural-frequency 1500").exit_code, 0);
    // the controller rates shake refuses are refused here too, in shake's words
    for (const char* rate : {"50", "2e6"}) {
        r = runCli(std::string("frequency-response --closed-loop --max-frequency 10 --controller-rate ") + rate);
        EXPECT_EQ(r.exit_code, 2) << rate;
        EXPECT_TRUE(has(r.err, "--controller-rate: must be a finite number in [100, 1e+06] Hz")) << r.err;
        EXPECT_EQ(runCli("shake --record " + kRecord + " --rate " + std::string(rate)).exit_code, 2) << rate;
    }
    r = runCli("frequency-response --closed-loop --natural-frequency 2e4");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(has(r.err, "--natural-frequency: must be a finite number in [0.1, 10000] Hz")) << r.err;
}

TEST(HostileRound4Cli, ControllerOptionsWithoutTheClosedLoopAreRefusedAndThePayloadApplies) {
    for (const std::string option : {"--controller-rate 50000", "--natural-frequency 100"}) {
        const CliResult r = runCli("frequency-response --points 3 " + option);
        EXPECT_EQ(r.exit_code, 1) << option;
        EXPECT_TRUE(has(r.err, option.substr(0, option.find(' ')) + ": does not apply to the plant: it goes with "
                                                                    "--closed-loop"))
            << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
    const CliResult closed = runCli("frequency-response --closed-loop --points 3 --output-kind actuators");
    EXPECT_EQ(closed.exit_code, 1);
    EXPECT_TRUE(has(closed.err, "--output-kind: does not apply to the closed loop")) << closed.err;
    // the payload is on the plant: a rigid 3-PRR's acceleration per force at rest is 1 / mass
    // along x, so 5 kg more lowers |ddx/tau| by 20 log10((m + 5) / m) at every frequency
    const auto gain = [](const std::string& options) {
        const CliResult r =
            runCli("frequency-response --points 2 --min-frequency 1 --max-frequency 2 --compliance rigid" + options);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        std::istringstream lines(r.out);
        std::string header, row;
        std::getline(lines, header);
        std::getline(lines, row);
        EXPECT_TRUE(header.starts_with("f,ddx_tau1_db")) << header;
        return std::stod(row.substr(row.find(',') + 1));
    };
    const double unloaded = gain(""), loaded = gain(" --payload-mass 5");
    EXPECT_LT(loaded, unloaded - 1.0) << "the payload changes nothing";
    const CliResult summary = runCli("frequency-response --points 3 --payload 5 -o /dev/null");
    EXPECT_TRUE(has(summary.out, "payload 5 kg at C")) << summary.out;
}

TEST(HostileRound4Cli, PoseJsonModeShapesAreColumnsAsInTheText) {
    const CliResult r = runCli("pose 0.004 -0.003 0.03 --json --robot " + kCompliant);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    const auto matrix = [](const nlohmann::json& rows) {
        Eigen::MatrixXd m(rows.size(), rows[0].size());
        for (std::size_t i = 0; i < rows.size(); ++i)
            for (std::size_t k = 0; k < rows[i].size(); ++k)
                m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = rows[i][k];
        return m;
    };
    const Eigen::MatrixXd V = matrix(j["mode_shapes"]), A = matrix(j["A"]), I = matrix(j["I"]),
                          K = matrix(j["stiffness"]["matrix"]);
    ASSERT_EQ(V.rows(), 3);
    ASSERT_EQ(V.cols(), 3);
    // the inertia in the pose coordinates; column i is mode i: K v = w^2 M v, v^T M v = 1
    const Eigen::MatrixXd M = A.transpose() * I * A;
    for (Eigen::Index i = 0; i < 3; ++i) {
        const double w = 2.0 * std::numbers::pi * j["natural_frequencies"][static_cast<std::size_t>(i)].get<double>();
        const Eigen::VectorXd v = V.col(i);
        EXPECT_LT((K * v - w * w * M * v).norm() / (K * v).norm(), 1e-8) << "mode " << i;
        EXPECT_NEAR(v.dot(M * v), 1.0, 1e-9) << "mode " << i;
    }
}

TEST(HostileRound4Cli, EveryRobotAndLimbNameIsEscapedOnTheTerminal) {
    const fs::path dir = freshScratchDirectory("hostile_round4_cli");
    writeFile(dir / "inj.yaml",
              edited(kCompliant, "name: paper-3prr-compliant", "name: \"evil\\u001b]0;PWNED\\u0007\\u001b[2J\""));
    const std::string robot = " --robot " + (dir / "inj.yaml").string();
    for (const std::string& command :
         {std::string("pose 0 0 0"), std::string("frequency-response --points 3 -o /dev/null"),
          std::string("frequency-response --closed-loop --natural-frequency 0.5 --points 3 -o /dev/null"),
          std::string("regressor"), std::string("envelope --points 2"), std::string("workspace --resolution 11")}) {
        const CliResult r = runCli(command + robot);
        EXPECT_EQ(r.exit_code, 0) << command << "\n" << r.err;
        EXPECT_FALSE(has(r.out + r.err, "\x1b")) << command << ": a raw ESC reached the terminal";
        EXPECT_FALSE(has(r.out + r.err, "\x07")) << command << ": a raw BEL reached the terminal";
    }
    EXPECT_TRUE(has(runCli("pose 0 0 0" + robot).out, "robot evil\\x1B]0;PWNED\\x07\\x1B[2J,"));
    // a limb's name with a newline, in an error (a stiffness on one passive joint of a rigid limb):
    // one line, the newline shown as \x0A
    std::string limb = edited(kRrr, "name: limb1", "name: \"L1\\nnocdyn: forged line\"");
    const std::string elbow = "{type: R, point: [0.08, -0.13175]}";
    limb.replace(limb.find(elbow), elbow.size(), "{type: R, point: [0.08, -0.13175], stiffness: 50}");
    writeFile(dir / "limb.yaml", limb);
    const CliResult bad = runCli("pose 0 0 0 --robot " + (dir / "limb.yaml").string());
    EXPECT_FALSE(std::regex_search(bad.out + bad.err, std::regex("(^|\n)nocdyn: forged line"))) << bad.err;
    EXPECT_TRUE(has(bad.out + bad.err, "L1\\x0Anocdyn: forged line")) << bad.out << bad.err;
}

TEST(HostileRound4Cli, FirstFrequencyOfAFamilyWithoutComplianceIsRefusedUpFront) {
    const fs::path dir = freshScratchDirectory("hostile_round4_cli");
    writeFile(dir / "fam.yaml", edited(kRrr, "max_condition:", "parameters:\n  m1: 0.30\nmax_condition:"));
    std::string text = readWhole(dir / "fam.yaml");
    const std::string mass = "{mass: 0.30,";
    const auto at = text.find(mass);
    ASSERT_NE(at, std::string::npos) << text;
    text.replace(at, mass.size(), "{mass: m1,");
    writeFile(dir / "fam.yaml", text);
    const CliResult r = runCli("design --robot " + (dir / "fam.yaml").string() +
                               " --vary m1=0.2:0.4 --metric first_frequency_min --samples 5 --resolution 11 "
                               "--no-figures --out-dir " +
                               (dir / "d").string());
    EXPECT_NE(r.exit_code, 0) << r.out;
    EXPECT_TRUE(has(r.err, "--metric: first_frequency_min: the family")) << r.err;
    EXPECT_TRUE(has(r.err, "declares no compliance")) << r.err;
    EXPECT_FALSE(fs::exists(dir / "d" / "designs.csv"));
    // a metric asked twice is refused as a parameter varied twice is
    const CliResult twice = runCli("design --robot " + (dir / "fam.yaml").string() +
                                   " --vary m1=0.2:0.4 --metric moving_mass --metric moving_mass --samples 2 "
                                   "--no-figures --out-dir " +
                                   (dir / "e").string());
    EXPECT_NE(twice.exit_code, 0);
    EXPECT_TRUE(has(twice.err, "--metric: 'moving_mass' is asked twice")) << twice.err;
    EXPECT_FALSE(fs::exists(dir / "e" / "designs.csv"));
}

TEST(HostileRound4Cli, OldOptionSpellingsWarnAndMeanTheNewOnes) {
    // one name per concept across the commands: --min-frequency (envelope, loads), --payload-mass
    // (control, shake), --noise-u (control), --threads (design); the old spellings go in the next
    // release
    const std::string grid = "frequency-response --points 3 --compliance rigid";
    const CliResult current = runCli(grid + " --min-frequency 2 --max-frequency 20 --payload-mass 1");
    ASSERT_EQ(current.exit_code, 0) << current.err;
    EXPECT_TRUE(current.err.empty()) << current.err;
    const CliResult old = runCli(grid + " --f-min 2 --f-max 20 --payload 1");
    ASSERT_EQ(old.exit_code, 0) << old.err;
    EXPECT_EQ(old.out, current.out);
    for (const char* warning : {"nocdyn: warning: --f-min is deprecated: use --min-frequency",
                                "nocdyn: warning: --f-max is deprecated: use --max-frequency",
                                "nocdyn: warning: --payload is deprecated: use --payload-mass"}) {
        EXPECT_TRUE(has(old.err, warning)) << old.err;
    }
    EXPECT_EQ(std::count(old.err.begin(), old.err.end(), '\n'), 3) << old.err;
    // both spellings at once: refused, nothing computed
    const CliResult both = runCli(grid + " --f-min 2 --min-frequency 2");
    EXPECT_EQ(both.exit_code, 2);
    EXPECT_TRUE(has(both.err, "--f-min excludes --min-frequency")) << both.err;
    EXPECT_TRUE(both.out.empty()) << both.out;
    // shake's: the same check and the same meaning as the new spelling (its refusal names it)
    const CliResult jobs = runCli("shake --record " + kRecord + kQuick + " --jobs 2");
    EXPECT_EQ(jobs.exit_code, 1);
    EXPECT_TRUE(has(jobs.err, "nocdyn: warning: --jobs is deprecated: use --threads")) << jobs.err;
    EXPECT_TRUE(has(jobs.err, "--threads: does not apply to one record")) << jobs.err;
    const CliResult noise = runCli("shake --record " + kRecord + kQuick + " --encoder-noise 2");
    EXPECT_EQ(noise.exit_code, 2);
    EXPECT_TRUE(has(noise.err, "--encoder-noise: must be a finite number in [1e-12, 1] m or rad")) << noise.err;
    // --out, the old spelling of --output (animate, excite) and of --out-dir (design, shake,
    // reproduce)
    const fs::path dir = freshScratchDirectory("hostile_round4_cli");
    const CliResult page =
        runCli("animate --trajectory paper1 --duration 0.05 --rate 1000 --out " + (dir / "p.html").string());
    EXPECT_EQ(page.exit_code, 0) << page.err;
    EXPECT_TRUE(fs::exists(dir / "p.html"));
    EXPECT_TRUE(has(page.err, "nocdyn: warning: --out is deprecated: use --output")) << page.err;
    const CliResult sweep = runCli("design --robot " + kCompliant + " --out " + (dir / "d").string());
    EXPECT_EQ(sweep.exit_code, 2);
    EXPECT_TRUE(has(sweep.err, "nocdyn: warning: --out is deprecated: use --out-dir")) << sweep.err;
    // excite's --frequency and --random, now --base-frequency and --random-shapes as the library
    // and Python name them: refused under the new spelling's checks, naming the old one
    // (a value the new spelling accepts warns; the output folder missing then stops the run early)
    const CliResult base = runCli("excite --frequency 2 --output " + (dir / "missing" / "e.yaml").string());
    EXPECT_EQ(base.exit_code, 1);
    EXPECT_TRUE(has(base.err, "nocdyn: warning: --frequency is deprecated: use --base-frequency")) << base.err;
    EXPECT_TRUE(has(base.err, "the folder")) << base.err;
    const CliResult refused = runCli("excite --frequency 1e6");
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_TRUE(has(refused.err, "--frequency: must be a finite number in [0.001, 1000] Hz")) << refused.err;
    const CliResult shapes = runCli("excite --random 0");
    EXPECT_EQ(shapes.exit_code, 2);
    EXPECT_TRUE(has(shapes.err, "--random: Value 0 not in range 1 to 1000000")) << shapes.err;
    // the old spellings are not offered in --help
    const CliResult help = runCli("frequency-response --help");
    EXPECT_FALSE(has(help.out, "--f-min")) << help.out;
    EXPECT_TRUE(has(help.out, "--min-frequency")) << help.out;
}

TEST(HostileRound4Cli, OptionErrorsAreShortAndNameTheOption) {
    const fs::path dir = freshScratchDirectory("hostile_round4_cli");
    CliResult r = runCli("frequency-response --min-frequency 0");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_LT(r.err.size(), 200u) << r.err;
    EXPECT_TRUE(has(r.err, "--min-frequency: must be a finite number in [1e-09, 1e+09] Hz, got '0'")) << r.err;
    // the old spelling, under the same check
    r = runCli("frequency-response --f-min 0");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_LT(r.err.size(), 200u) << r.err;
    EXPECT_TRUE(has(r.err, "--f-min: must be a finite number in [1e-09, 1e+09] Hz, got '0'")) << r.err;
    // an extreme grid is refused up front, not at the table's write
    r = runCli("frequency-response --robot " + kCompliant + " --min-frequency 1e-9 --max-frequency 1e300 --points 5");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(has(r.err, "--max-frequency")) << r.err;
    EXPECT_FALSE(has(r.err, "is not a finite number")) << r.err;
    // a grid whose low end is below the range (|u / tau| ~ 1 / w^2 would leave a double): the end
    // named before anything is written
    r = runCli("frequency-response --min-frequency 1e-300 --max-frequency 1e9 --points 5 --output-kind actuators");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_TRUE(has(r.err, "--min-frequency")) << r.err;
    EXPECT_FALSE(has(r.err, "cannot write")) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    // a payload beyond its range blames the option, not the robot file's platform
    r = runCli("frequency-response --closed-loop --payload-mass 1e6 --points 3");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(has(r.err, "--payload-mass: must be a finite number in [0, 10000] kg")) << r.err;
    EXPECT_FALSE(has(r.err, "platform.mass")) << r.err;
    r = runCli("excite --payload-guess 1e6 0 0 0 -o " + (dir / "e.yaml").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(has(r.err, "--payload-guess: 1000000 is outside [0, 10000] kg")) << r.err;
    EXPECT_FALSE(has(r.err, "platform.mass")) << r.err;
    // an output folder that is a file: said before anything runs, without "filesystem error"
    writeFile(dir / "afile", "x\n");
    writeFile(dir / "fam.yaml",
              edited(kCompliant, "max_condition: 10000", "parameters:\n  k: 2.0e5\nmax_condition: 10000"));
    r = runCli("design --robot " + (dir / "fam.yaml").string() +
               " --vary k=1e5:2e5 --metric moving_mass --samples 2 --no-figures --out-dir " + (dir / "afile").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_TRUE(has(r.err, "--out-dir: '" + (dir / "afile").string() + "' is not a folder: it is a file")) << r.err;
    EXPECT_FALSE(has(r.err, "filesystem error")) << r.err;
    r = runCli("shake --record " + kRecord + kQuick + " --out-dir " + (dir / "afile" / "s").string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(has(r.err, "--out-dir: '" + (dir / "afile" / "s").string() + "' is not a folder")) << r.err;
    EXPECT_EQ(readWhole(dir / "afile"), "x\n");
}

TEST(HostileRound4Cli, ShakeRefusesOptionsThatDoNotApplyInTheCommandLinesWords) {
    const fs::path dir = freshScratchDirectory("hostile_round4_cli");
    const std::string shake = "shake --record " + kRecord + kQuick + " --out-dir " + (dir / "s").string();
    const std::vector<std::pair<std::string, std::string>> refused = {
        {" --drive-model exact", "--drive-model: does not apply here: it goes with --iterations 1 or more"},
        {" --drive-model difference", "--drive-model: does not apply here: it goes with --iterations"},
        {" --iteration-gain 0.5", "--iteration-gain: does not apply here: it goes with --iterations"},
        {" --drive-specimen", "--drive-specimen: goes with --drive-model exact or difference"},
        {" --excitation-duration 4", "--excitation-duration: does not apply here: it goes with --identify-payload"},
        {" --controller pose --noise-u 1e-5", "--noise-u: does not apply here: it goes with --controller table"},
        {" --noise-pose 1e-5", "--noise-pose: does not apply here: it goes with --controller pose"},
        {" --accuracy 1e-8", "--accuracy: does not apply here: it goes with --plant simbody"},
        {" --no-accelerometer --acceleration-gain 0.1", "--acceleration-gain: does not apply here"},
        {" --threads 2", "--threads: does not apply to one record: it goes with a suite"}};
    for (const auto& [option, message] : refused) {
        const CliResult r = runCli(shake + option);
        EXPECT_EQ(r.exit_code, 1) << option;
        EXPECT_TRUE(has(r.err, message)) << option << "\n" << r.err;
        EXPECT_FALSE(std::regex_search(r.err, std::regex("[a-z]_[a-z]"))) << "a field name: " << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "s"));
}

TEST(HostileRound4Cli, LoadsRefusesTheOptionsOfItsOtherMode) {
    CliResult r = runCli("loads --trajectory paper1 --duration 0.01 --min-frequency 5");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(has(r.err, "--min-frequency: does not apply to a trajectory: it goes with --envelope")) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    r = runCli("loads --envelope --rate 5000");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_TRUE(has(r.err, "--rate: does not apply to the envelope's motions: it goes with --trajectory")) << r.err;
}

TEST(HostileRound4Cli, HelpTakesOneCommandAndFailsOnAFullOutput) {
    CliResult r = runCli("help pose extra");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(has(r.err, "help takes one command name")) << r.err;
    EXPECT_FALSE(has(r.err, "unknown command 'help'")) << r.err;
    r = runCli("help help");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "nocdyn help <command>")) << r.out;
    for (const std::string arguments : {"help pose", "--help", "pose --help", "--version"}) {
        r = runCli(arguments + " > /dev/full");
        EXPECT_EQ(r.exit_code, 1) << arguments;
        EXPECT_TRUE(has(r.err, "cannot write standard output")) << arguments << "\n" << r.err;
    }
    // every command in a named group: no stray heading of CLI11's own
    r = runCli("--help");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_FALSE(std::regex_search(r.out, std::regex("(^|\n)Subcommands:"))) << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("\n  frequency-response "))) << r.out;
}

TEST(HostileRound4Cli, ARigidPlantOnACompliantRobotSaysSo) {
    const fs::path dir = freshScratchDirectory("hostile_round4_cli");
    CliResult r =
        runCli("frequency-response --closed-loop --compliance rigid --points 3 -o /dev/null --robot " + kCompliant);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "# rigid plant: the compliance the robot file declares")) << r.out;
    // by default the closed loop's plant is the lumped compliant model, said so (a pose feedback
    // slow enough for its 2 %-damped resonance: the default 6 Hz is refused as unstable)
    r = runCli("frequency-response --closed-loop --natural-frequency 0.5 --points 3 -o /dev/null --robot " +
               kCompliant);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "# plant: the lumped compliant model")) << r.out;
    r = runCli("frequency-response --closed-loop --points 3 -o /dev/null --robot " + kCompliant);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_TRUE(has(r.err, "unstable closed loop")) << r.err;
    EXPECT_TRUE(has(r.err, "lumped compliant plant")) << r.err;
    // without compliance, no such line
    EXPECT_FALSE(has(runCli("frequency-response --closed-loop --points 3 -o /dev/null").out, "rigid plant"));
    r = runCli("shake --robot " + kCompliant + " --record " + kRecord + kQuick + " --out-dir " + (dir / "s").string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(has(r.err, "shake: the compliance the robot file declares")) << r.err;
    EXPECT_TRUE(has(r.err, "first resonance at home 41.04 Hz")) << r.err;
    EXPECT_TRUE(has(r.err, "the plant is the rigid robot")) << r.err;
}

TEST(HostileRound4Cli, AnimatingAnotherRobotsReplayWarns) {
    const fs::path dir = freshScratchDirectory("hostile_round4_cli");
    // the 3-PRR's forces (N, effort 262 N) played on the 3-RRR (N m, effort 12 N m)
    const fs::path motion = dir / "prr.csv";
    ASSERT_EQ(runCli("inverse-dynamics --trajectory paper1 --duration 0.05 -o " + motion.string()).exit_code, 0);
    const CliResult r =
        runCli("animate --motion " + motion.string() + " --robot " + kRrr + " -o " + (dir / "a.html").string());
    EXPECT_TRUE(has(r.err, "warning")) << r.err;
    EXPECT_TRUE(has(r.err, "is the motion another robot's?")) << r.err;
    // the same motion on its own robot: no such warning
    const CliResult own = runCli("animate --motion " + motion.string() + " -o " + (dir / "b.html").string());
    EXPECT_EQ(own.exit_code, 0) << own.err;
    EXPECT_FALSE(has(own.err, "another robot")) << own.err;
}

}  // namespace
}  // namespace nocdyn::test
