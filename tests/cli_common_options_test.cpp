// What every command of `nocdyn` shares: --quiet with one meaning (only errors and warnings on
// standard error, the results unchanged), outputs refused before the work when their folder is
// missing, option errors that point to the command's own help, a bare `nocdyn` that shows the
// help, and --version with the commit the build was configured from.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "cli_support.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kSource = NOCDYN_SOURCE_DIR;
const std::string kRrr = kSource + "/robots/3-rrr.yaml";

/// What a shell command printed on stdout (stderr discarded) and its exit status.
std::pair<std::string, int> shellOutput(const std::string& command) {
    std::string out;
    FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r");
    if (pipe == nullptr) return {out, -1};
    char buffer[4096];
    for (std::size_t n = 0; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
    const int status = pclose(pipe);
    return {out, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

/// Every command of this build, from the command line's own registry (`nocdyn --help-json`, the
/// options of each command it defines): a command added later is tested without being listed.
std::vector<std::string> registeredCommands() {
    const auto [json, status] = shellOutput(std::string(NOCDYN_CLI) + " --help-json");
    std::vector<std::string> names;
    if (status != 0) return {"(nocdyn --help-json failed)"};
    const nlohmann::json commands = nlohmann::json::parse(json);
    for (auto command = commands.begin(); command != commands.end(); ++command) names.push_back(command.key());
    return names;
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// The inputs some normal runs read (a force history, a closed-loop log), made once per process
/// (ctest runs each test in a process of its own, several at once).
const fs::path& inputs() {
    static const fs::path dir = [] {
        const fs::path d =
            fs::path(testing::TempDir()) / "cli_common_options" / ("inputs-" + std::to_string(::getpid()));
        fs::remove_all(d);
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

/// A normal run of each command, its outputs under {out} (a folder of the test's own): short,
/// as the parity tests run them. `compare`: an output file the run with --quiet must write byte
/// for byte as the run without it (empty: none deterministic).
struct NormalRun {
    std::string arguments, compare;
};

const std::map<std::string, NormalRun>& normalRuns() {
    static const std::map<std::string, NormalRun> runs = {
        {"pose", {"0.001 -0.002 0.01 --robot " + kRrr, ""}},
        {"inverse-dynamics", {"--trajectory paper1 --duration 0.01 --rate 2000 -o {out}/id.csv", "id.csv"}},
        {"reproduce", {"--out-dir {out}/results --closed-loop-duration 0.001 --identification-duration 0.01", ""}},
        {"forward-kinematics", {"0.001 -0.0005 0.0002", ""}},
        {"simulate", {"--forces {in}/forces.csv --rate 2000 -o {out}/motion.csv", "motion.csv"}},
        {"control",
         {"--trajectory paper1 --duration 0.01 --rate 2000 --plant nocdyn -o {out}/control.csv --log {out}/log.csv",
          "control.csv"}},
        {"envelope", {"--points 2 --min-frequency 5 --max-frequency 50 -o {out}/envelope.csv", "envelope.csv"}},
        {"workspace", {"--robot " + kRrr + " --resolution 21 -o {out}/grid.csv", "grid.csv"}},
        {"convert", {kRrr + " -o {out}/converted.yaml", "converted.yaml"}},
        {"animate", {"--trajectory paper1 --duration 0.005 --rate 2000 -o {out}/page.html", "page.html"}},
        {"shake",
         {"--record " + kSource +
              "/data/elcentro_1940_ns.AT2 --window 0.5 --plant nocdyn-rk4 --rate 1000 --out-dir "
              "{out}/shake",
          "shake/shake.csv"}},
        {"regressor", {"--robot " + kRrr + " --samples 40 -o {out}/regressor.txt", "regressor.txt"}},
        {"identify", {"--data {in}/log.csv --holdout 0 -o {out}/estimates.csv", "estimates.csv"}},
        {"excite",
         {"--robot " + kRrr +
              " --evaluations 12 --random-shapes 6 --samples 48 --check-samples 300 --duration 0.4 -o "
              "{out}/excite.yaml",
          "excite.yaml"}},
        {"loads", {"--trajectory paper1 --duration 0.005 --rate 2000 -o {out}/loads.csv", "loads.csv"}},
        {"design",
         {"--robot " + kSource +
              "/examples/design_3rrr/family.yaml --set l2=0.11 --vary r_b=0.15:0.25 --samples 4 --metric "
              "workspace_area --metric moving_mass --resolution 11 --no-figures --out-dir {out}/design",
          "design/designs.csv"}},
        {"frequency-response", {"--points 7 -o {out}/response.csv", "response.csv"}},
        {"validate", {"--trajectory paper1 --duration 0.005 -o {out}/validation.csv", "validation.csv"}},
    };
    return runs;
}

std::string substituted(std::string text, const fs::path& out) {
    for (const auto& [key, value] : {std::pair<std::string, std::string>{"{out}", out.string()},
                                     std::pair<std::string, std::string>{"{in}", inputs().string()}}) {
        for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at)) {
            text.replace(at, key.size(), value);
        }
    }
    return text;
}

class QuietOnEveryCommand : public testing::TestWithParam<std::string> {
protected:
    static void SetUpTestSuite() {
        // the force history simulate replays and the closed-loop log identify reads
        const std::string in = inputs().string();
        ASSERT_EQ(shellOutput(std::string(NOCDYN_CLI) +
                              " inverse-dynamics --trajectory paper1 --duration 0.005 "
                              "--rate 2000 --quiet -o " +
                              in + "/forces.csv")
                      .second,
                  0);
        ASSERT_EQ(shellOutput(std::string(NOCDYN_CLI) +
                              " control --trajectory paper1 --duration 0.01 --rate 2000 --payload-mass 0.5 --plant "
                              "nocdyn --quiet -o " +
                              in + "/c.csv --log " + in + "/log.csv")
                      .second,
                  0);
    }
    static void TearDownTestSuite() { fs::remove_all(inputs()); }
};

TEST_P(QuietOnEveryCommand, OnlyErrorsOnStandardErrorAndTheSameResults) {
    const std::string& command = GetParam();
    const auto run = normalRuns().find(command);
    ASSERT_NE(run, normalRuns().end()) << "no normal run of '" << command
                                       << "' in normalRuns(): add one, so that its --quiet is tested";
    const fs::path dir = freshScratchDirectory("cli_common_options");
    fs::create_directories(dir / "quiet");
    fs::create_directories(dir / "loud");
    const CliResult quiet = runCli(command + " " + substituted(run->second.arguments, dir / "quiet") + " --quiet");
    ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
    EXPECT_EQ(quiet.err, "") << command << " --quiet wrote on standard error";
    if (command == "reproduce") return;  // the longest run: once is enough (its summary holds timings)
    const CliResult loud = runCli(command + " " + substituted(run->second.arguments, dir / "loud"));
    ASSERT_EQ(loud.exit_code, 0) << loud.err;
    if (!run->second.compare.empty()) {
        // without --quiet the file is named as written; with it the file is the same
        EXPECT_TRUE(has(loud.err, "nocdyn: wrote ")) << command << ": " << loud.err;
        const std::string written = readWhole(dir / "quiet" / run->second.compare);
        EXPECT_FALSE(written.empty()) << command;
        EXPECT_EQ(written, readWhole(dir / "loud" / run->second.compare)) << command << ": " << run->second.compare;
    } else {
        EXPECT_EQ(quiet.out, loud.out) << command << ": the answer on standard output";
    }
}

INSTANTIATE_TEST_SUITE_P(Registry, QuietOnEveryCommand, testing::ValuesIn(registeredCommands()),
                         [](const testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param;
                             for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                             return name;
                         });

TEST(CommonOptions, QuietHasOneDefinitionInEveryCommand) {
    const auto [json, status] = shellOutput(std::string(NOCDYN_CLI) + " --help-json");
    ASSERT_EQ(status, 0);
    std::string help;
    const nlohmann::json commands = nlohmann::json::parse(json);
    for (auto entry = commands.begin(); entry != commands.end(); ++entry) {
        const std::string& command = entry.key();
        const nlohmann::json& options = entry.value();
        int found = 0;
        for (const auto& option : options) {
            if (option["long"] != nlohmann::json::array({"quiet"})) continue;
            ++found;
            EXPECT_EQ(option["short"], nlohmann::json::array({"q"})) << command;
            EXPECT_TRUE(option["flag"].get<bool>()) << command;
            if (help.empty()) help = option["help"].get<std::string>();
            EXPECT_EQ(option["help"].get<std::string>(), help) << command << ": another meaning of --quiet";
        }
        EXPECT_EQ(found, 1) << command << " has no --quiet";
    }
    EXPECT_TRUE(has(help, "errors")) << help;
}

TEST(CommonOptions, QuietAfterTheCommandInItsShortForm) {
    const fs::path dir = freshScratchDirectory("cli_common_options");
    const std::string csv = (dir / "loads.csv").string();
    const CliResult loud = runCli("loads --trajectory paper1 --duration 0.005 --rate 2000 -o " + csv);
    ASSERT_EQ(loud.exit_code, 0) << loud.err;
    EXPECT_EQ(loud.err, "nocdyn: wrote " + csv + "\n");
    const CliResult quiet = runCli("loads -q --trajectory paper1 --duration 0.005 --rate 2000 -o " + csv);
    ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
    EXPECT_EQ(quiet.err, "");
}

// --- outputs into a folder that does not exist: refused before the work ----------------------

TEST(CommonOptions, AnOutputIntoAMissingFolderIsRefusedBeforeTheWork) {
    const fs::path dir = freshScratchDirectory("cli_common_options");
    const std::string missing = (dir / "no-such-folder").string();
    struct Case {
        std::string arguments, option, path;
    };
    // long runs (20 s of trajectory, a 20 s closed loop, a fine envelope, a fine frequency map):
    // refused before any of the work
    const Case cases[] = {
        {"inverse-dynamics --trajectory paper1 --duration 20 -o " + missing + "/id.csv", "--output",
         missing + "/id.csv"},
        {"control --trajectory paper1 --duration 20 --plant nocdyn --log " + missing + "/log.csv", "--log",
         missing + "/log.csv"},
        {"envelope --points 30 --figure " + missing + "/envelope", "--figure", missing + "/envelope"},
        {"workspace --resolution 401 --frequency-map " + missing + "/f --robot " + kSource +
             "/robots/paper-3prr-compliant.yaml",
         "--frequency-map", missing + "/f"},
    };
    for (const Case& c : cases) {
        const CliResult r = runCli(c.arguments);
        EXPECT_EQ(r.exit_code, 1) << c.arguments << "\n" << r.err;
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
        EXPECT_TRUE(has(r.err, c.option + " '" + c.path)) << r.err;
        EXPECT_TRUE(has(r.err, "the folder '" + missing + "' does not exist")) << r.err;
        EXPECT_FALSE(fs::exists(missing)) << c.arguments;
    }
    // the output folder of a command is created, parents and all
    const fs::path created = dir / "new" / "shake";
    const CliResult r = runCli("shake --record " + kSource +
                               "/data/elcentro_1940_ns.AT2 --window 0.5 --plant "
                               "nocdyn-rk4 --rate 1000 --quiet --out-dir " +
                               created.string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(created / "shake.csv"));
}

TEST(CommonOptions, AnOutputUnderAFileIsRefusedNamingIt) {
    const fs::path dir = freshScratchDirectory("cli_common_options");
    const fs::path file = dir / "plain.txt";
    { std::ofstream(file) << "a file\n"; }
    CliResult r = runCli("inverse-dynamics --trajectory paper1 -o " + (file / "forces.csv").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(has(
        r.err, "--output '" + (file / "forces.csv").string() + "': '" + file.string() + "' is a file, not a folder"))
        << r.err;
    // an output folder under a file: the command's own check (app::requireOutputFolder), before the work
    r = runCli("shake --record " + kSource + "/data/elcentro_1940_ns.AT2 --out-dir " + (file / "out").string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_TRUE(has(r.err, "--out-dir: '" + (file / "out").string() + "' is not a folder")) << r.err;
    EXPECT_EQ(readWhole(file), "a file\n");
}

// --- option errors point to the command's own help --------------------------------------------

TEST(CommonOptions, OptionErrorsPointToTheCommandsHelp) {
    const struct {
        std::string arguments, command;
        int code;
    } cases[] = {
        {"pose 0 0 0 --bogus", "pose", 2},                                            // unknown option
        {"inverse-dynamics --trajectory paper1 --duraton 1", "inverse-dynamics", 2},  // a slip
        {"simulate --forces f.csv --rate abc", "simulate", 2},                        // a bad value
        {"envelope --points 0", "envelope", 2},                                       // out of range
        {"inverse-dynamics", "inverse-dynamics", 2},                                  // a required option
        {"frequency-response --controller-rate 1000", "frequency-response", 1},       // refused by the job
    };
    for (const auto& c : cases) {
        const CliResult r = runCli(c.arguments);
        EXPECT_EQ(r.exit_code, c.code) << c.arguments << "\n" << r.err;
        EXPECT_TRUE(has(r.err, "(see nocdyn " + c.command + " --help)")) << c.arguments << "\n" << r.err;
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
        // the help pointed to exists
        EXPECT_EQ(runCli(c.command + " --help").exit_code, 0) << c.command;
    }
    // no command named: the list of commands
    for (const std::string arguments : {"posr 0 0 0", "--bogus", "-q"}) {
        const CliResult r = runCli(arguments);
        EXPECT_EQ(r.exit_code, 2) << arguments;
        EXPECT_TRUE(has(r.err, "(see nocdyn --help)")) << arguments << "\n" << r.err;
    }
}

// Every choice takes exactly its table's words, in the table's order; another word is refused
// naming them all, and the default is shown in the help.
TEST(CommonOptions, EveryChoiceTakesItsTablesWordsAndRefusesAnother) {
    const struct {
        std::string command, option, words, fallback;
    } cases[] = {
        {"control --trajectory paper1", "--controller", "computed-torque,pd", "computed-torque"},
        {"control --trajectory paper1", "--measure", "pose,encoders", "pose"},
        {"design", "--sweep", "grid,random", "random"},
        {"excite", "--optimizer", "nelder-mead,gradient", "nelder-mead"},
        {"frequency-response", "--output-kind", "acceleration,actuators", "acceleration"},
        {"frequency-response", "--compliance", "auto,rigid,lumped", "auto"},
        {"shake", "--axis", "x,y", "x"},
        {"simulate", "--interpolation", "hold,linear,cubic", "cubic"},
        {"validate", "--engine", "both,simbody,mujoco", "both"},
    };
    for (const auto& c : cases) {
        const CliResult r = runCli(c.command + " " + c.option + " bogus");
        EXPECT_EQ(r.exit_code, 2) << c.option << "\n" << r.err;
        EXPECT_TRUE(has(r.err, c.option + ": bogus not in {" + c.words + "}")) << c.option << "\n" << r.err;
        const CliResult help = runCli(c.command.substr(0, c.command.find(' ')) + " --help");
        EXPECT_TRUE(has(help.out, c.option + " TEXT:{" + c.words + "}=" + c.fallback)) << c.option;
    }
}

// --- a bare `nocdyn` ----------------------------------------------------------------------------

TEST(CommonOptions, NoArgumentsShowTheHelpOnStandardErrorAndExit2) {
    const CliResult bare = runCli("");
    EXPECT_EQ(bare.exit_code, 2);
    EXPECT_EQ(bare.out, "");
    const CliResult help = runCli("--help");
    ASSERT_EQ(help.exit_code, 0);
    EXPECT_EQ(bare.err, help.out);  // the whole help: the commands in their groups
    EXPECT_TRUE(has(bare.err, "Model:") && has(bare.err, "\n  pose ")) << bare.err;
    // and the help says so
    EXPECT_TRUE(has(help.out, "Without arguments, nocdyn prints this help on standard error and exits with status 2"))
        << help.out;
}

// --- --version ----------------------------------------------------------------------------------

TEST(CommonOptions, VersionNamesTheCommitBuilt) {
    const CliResult r = runCli("--version");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(
        std::regex_match(r.out, m, std::regex(R"(nocdyn (\d+\.\d+\.\d+) \(commit ([0-9a-f]{4,40}|unknown)\)\n)")))
        << r.out;
    EXPECT_EQ(m[1].str(), NOCDYN_PROJECT_VERSION);
    EXPECT_EQ(runCli("-V").out, r.out);
    // built from a checkout: the commit is HEAD's (CMake configures again when HEAD moves)
    const auto [head, status] = shellOutput("git -C " + kSource + " rev-parse --short HEAD");
    if (status == 0 && !head.empty()) {
        EXPECT_EQ(m[2].str() + "\n", head) << "nocdyn --version: " << r.out;
    } else {
        EXPECT_EQ(m[2].str(), "unknown") << "the source is no git checkout";
    }
}

}  // namespace
}  // namespace nocdyn::test
