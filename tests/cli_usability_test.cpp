// The command line as a newcomer meets it: a mistyped command or option named with the nearest
// one, `nocdyn help COMMAND` and -V, an example in every command's --help, every file written
// named on standard error, a replay's CSV animated, a pose far outside a joint's range warned
// about, and a `control --log` log identified right with the default options.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

/// The commands `nocdyn --help` lists (lines "  NAME  description" under a group's heading).
std::vector<std::string> listedCommands() {
    const CliResult r = runCli("--help");
    std::vector<std::string> names;
    std::istringstream lines(r.out);
    bool in_group = false;
    const std::regex heading("^([A-Z][A-Za-z ]+):$"), command("^  ([a-z][a-z0-9-]*) .*");
    std::smatch match;
    for (std::string line; std::getline(lines, line);) {
        if (std::regex_match(line, match, heading)) {
            in_group = match[1] != "Options";
            continue;
        }
        if (in_group && std::regex_match(line, match, command)) names.push_back(match[1]);
    }
    return names;
}

double after(const std::string& text, const std::string& key) {
    const std::size_t at = text.find(key);
    if (at == std::string::npos) {
        ADD_FAILURE() << "no '" << key << "' in\n" << text;
        return 0.0;
    }
    return std::stod(text.substr(at + key.size()));
}

TEST(CliUsability, EveryCommandsHelpHasAnExampleAndHelpCommandShowsTheSame) {
    const std::vector<std::string> commands = listedCommands();
    ASSERT_GE(commands.size(), 16U);
    for (const std::string& command : commands) {
        const CliResult help = runCli(command + " --help");
        ASSERT_EQ(help.exit_code, 0) << command << help.err;
        // one line "Example: nocdyn ..." that runs this command (after another one that makes its input)
        const std::size_t at = help.out.find("\nExample: nocdyn ");
        ASSERT_NE(at, std::string::npos) << command << "\n" << help.out;
        const std::string example = help.out.substr(at + 1, help.out.find('\n', at + 1) - at - 1);
        EXPECT_NE(example.find("nocdyn " + command + " "), std::string::npos) << example;
        const CliResult same = runCli("help " + command);
        EXPECT_EQ(same.exit_code, 0) << command << same.err;
        EXPECT_EQ(same.out, help.out) << command;
    }
    EXPECT_EQ(runCli("help").out, runCli("--help").out);
    const CliResult version = runCli("-V");
    EXPECT_EQ(version.exit_code, 0);
    EXPECT_EQ(version.out, runCli("--version").out);
    EXPECT_EQ(version.out.rfind("nocdyn ", 0), 0U) << version.out;
}

TEST(CliUsability, AMistypedOptionIsNamedWithTheNearestOne) {
    const CliResult r = runCli("control --trajectroy paper1");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("unknown option '--trajectroy'; did you mean '--trajectory'?"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("required"), std::string::npos) << r.err;
    const CliResult value = runCli("pose 0 0 0 --robott=robots/3-rrr.yaml");
    EXPECT_EQ(value.exit_code, 2);
    EXPECT_NE(value.err.find("'--robott'; did you mean '--robot'?"), std::string::npos) << value.err;
    // nothing near: named, without a suggestion
    const CliResult far = runCli("pose 0 0 0 --zzzzzzzzzz");
    EXPECT_EQ(far.exit_code, 2);
    EXPECT_NE(far.err.find("unknown option '--zzzzzzzzzz'"), std::string::npos) << far.err;
    EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
}

TEST(CliUsability, AMistypedCommandIsNamedWithTheNearestOne) {
    const CliResult r = runCli("inverse-dynamic --trajectory paper1");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("unknown command 'inverse-dynamic'; did you mean 'inverse-dynamics'?"), std::string::npos)
        << r.err;
    const CliResult help = runCli("help shak");
    EXPECT_EQ(help.exit_code, 2);
    EXPECT_NE(help.err.find("did you mean 'shake'?"), std::string::npos) << help.err;
    const CliResult far = runCli("frobnicate");
    EXPECT_EQ(far.exit_code, 2);
    EXPECT_NE(far.err.find("unknown command 'frobnicate' (the commands: pose, "), std::string::npos) << far.err;
}

TEST(CliUsability, EveryFileWrittenIsNamedOnStandardErrorUnlessQuiet) {
    const fs::path dir = freshScratchDirectory("cli_usability");
    const std::string csv = (dir / "id.csv").string(), page = (dir / "page.html").string();
    const CliResult id = runCli("inverse-dynamics --trajectory paper1 --duration 0.01 -o " + csv);
    ASSERT_EQ(id.exit_code, 0) << id.err;
    EXPECT_EQ(id.err, "nocdyn: wrote " + csv + "\n");
    const CliResult animate = runCli("animate --trajectory paper1 --duration 0.01 -o " + page);
    ASSERT_EQ(animate.exit_code, 0) << animate.err;
    EXPECT_NE(animate.err.find("nocdyn: wrote " + page + "\n"), std::string::npos) << animate.err;
    const std::string stem = (dir / "envelope").string();
    const CliResult envelope = runCli("envelope --points 2 -o " + (dir / "e.csv").string() + " --figure " + stem);
    ASSERT_EQ(envelope.exit_code, 0) << envelope.err;
    for (const std::string& file : {(dir / "e.csv").string(), stem + ".png", stem + ".svg"})
        EXPECT_NE(envelope.err.find("nocdyn: wrote " + file + "\n"), std::string::npos) << envelope.err;
    // to standard output: no file, nothing said; --quiet: nothing said
    EXPECT_EQ(runCli("inverse-dynamics --trajectory paper1 --duration 0.01 > /dev/null").err, "");
    EXPECT_EQ(runCli("inverse-dynamics --trajectory paper1 --duration 0.01 --quiet -o " + csv).err, "");
}

TEST(CliUsability, AReplaysCsvIsAnimatedWithItsExtraColumns) {
    const fs::path dir = freshScratchDirectory("cli_usability");
    const CliResult shake = runCli("shake --record " + std::string(NOCDYN_SOURCE_DIR) +
                                   "/data/elcentro_1940_ns.AT2 --window 1 --rate 2000 --out-dir " + dir.string());
    ASSERT_EQ(shake.exit_code, 0) << shake.err;
    const std::string page = (dir / "replay.html").string();
    const CliResult r = runCli("animate --trajectory " + (dir / "shake.csv").string() + " -o " + page);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string html = readWhole(page);
    EXPECT_NE(html.find("shake"), std::string::npos);
    const CliResult sampled = runCli("animate --trajectory " + (dir / "shake.csv").string() + " --rate 100 -o " + page);
    EXPECT_EQ(sampled.exit_code, 1);
    EXPECT_NE(sampled.err.find("is a recorded motion"), std::string::npos) << sampled.err;
}

TEST(CliUsability, ShakesDefaultPlantIsTheFastOneAndEachPlantsSpeedIsInTheHelp) {
    const CliResult r = runCli("shake --help");
    EXPECT_NE(r.out.find("=nocdyn-rk4"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("per CPU second"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("under --out-dir"), std::string::npos) << r.out;
}

// The 3-RPR reaches x = 5 m (its prismatic joints stretch) far outside their 30 mm range: 5 mm
// meant, 5 m typed.
TEST(CliUsability, APoseFarOutsideAJointsRangeWarnsOfTheUnit) {
    const std::string robot = " --robot " + std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rpr.yaml";
    const CliResult r = runCli("pose 5 0 0" + robot);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("nocdyn: warning: joint range exceeded"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("poses are in m and rad"), std::string::npos) << r.err;
    const CliResult json = runCli("pose 5 0 0 --json" + robot);
    EXPECT_NE(json.err.find("nocdyn: warning: "), std::string::npos) << json.err;
    const CliResult fk = runCli("forward-kinematics 5 0 0" + robot);
    EXPECT_NE(fk.err.find("nocdyn: warning: u1 is outside its joint's range"), std::string::npos) << fk.err;
    const CliResult fine = runCli("pose 0.001 0 0" + robot);
    EXPECT_EQ(fine.exit_code, 0) << fine.err;
    EXPECT_EQ(fine.err.find("warning"), std::string::npos) << fine.err;
}

TEST(CliUsability, AControlReferenceBeyondAJointsRangeWarns) {
    // 3-RPR's actuated joints have +-30 mm of stroke; a 50 mm swing of x stays in reach but not in range
    const std::filesystem::path motion = freshScratchDirectory("CliUsability") / "wide.yaml";
    std::ofstream(motion)
        << "duration: 0.02\nx: {harmonics: [{amplitude: 0.05, frequency: 2, phase: 1.5707963267948966}]}\n";
    const std::string robot = " --robot " + std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rpr.yaml";
    const CliResult wide = runCli("control" + robot + " --plant nocdyn-rk4 --trajectory " + motion.string());
    EXPECT_NE(wide.err.find("nocdyn: warning: the reference trajectory:"), std::string::npos) << wide.err;
    const CliResult paper = runCli("control" + robot + " --plant nocdyn-rk4 --trajectory paper1 --duration 0.02");
    EXPECT_EQ(paper.exit_code, 0) << paper.err;
    EXPECT_EQ(paper.err.find("warning"), std::string::npos) << paper.err;
}

// The trap of a log of held commands read as forces measured at each sample (18 % on the
// inertia): the log names its forces tau1_held..., and identify with its default options takes
// them so. Truth: 0.5 kg at (12, -7) mm, 2e-4 kg m^2.
TEST(CliUsability, IdentifyGetsThePayloadOfAControlLogWithinOnePercentByDefault) {
    const fs::path dir = freshScratchDirectory("cli_usability");
    const std::string log = (dir / "log.csv").string();
    const CliResult control = runCli(
        "control --trajectory paper2 --plant nocdyn-rk4 --duration 0.5 --payload-mass 0.5 --payload-com 0.012 "
        "-0.007 --payload-inertia 2e-4 --noise-u 1e-7 --noise-tau 0.05 --seed 3 --log " +
        log);
    ASSERT_EQ(control.exit_code, 0) << control.err;
    EXPECT_TRUE(io::readCsvFile(log).has("tau3_held"));
    const CliResult r = runCli("identify --data " + log);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NEAR(after(r.out, "payload: {mass: "), 0.5, 0.005) << r.out;
    EXPECT_NEAR(after(r.out, "com: ["), 0.012, 1e-4) << r.out;
    EXPECT_NEAR(after(r.out, "], inertia: "), 2e-4, 2e-6) << r.out;
    // the same log with its forces renamed as measured ones identifies differently: the name counts
    std::string text = readWhole(log);
    text.replace(0, text.find('\n'), "t,u1,u2,u3,tau1,tau2,tau3");
    std::ofstream(dir / "measured.csv") << text;
    const CliResult measured = runCli("identify --data " + (dir / "measured.csv").string());
    ASSERT_EQ(measured.exit_code, 0) << measured.err;
    EXPECT_NE(after(measured.out, "], inertia: "), after(r.out, "], inertia: "));
    std::ofstream(dir / "both.csv") << "t,u1,u2,u3,tau1,tau2,tau3,tau1_held\n";
    const CliResult both = runCli("identify --data " + (dir / "both.csv").string());
    EXPECT_EQ(both.exit_code, 1);
    EXPECT_NE(both.err.find("both tau1 and tau1_held"), std::string::npos) << both.err;
}

}  // namespace
}  // namespace nocdyn::test
