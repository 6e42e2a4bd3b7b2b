// nocdyn --help: one line per command, grouped, within a screen; each command's own --help
// carries its whole description; --version prints the project's version.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "cli_support.hpp"

namespace nocdyn::test {
namespace {

TEST(CliHelp, TopLevelHelpListsEveryCommandOnOneLineInGroups) {
    const CliResult r = runCli("--help");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::istringstream lines(r.out);
    int count = 0;
    for (std::string line; std::getline(lines, line);) {
        ++count;
        EXPECT_LE(line.size(), 140U) << line;
    }
    EXPECT_LE(count, 45) << r.out;
    for (const char* group : {"Model:", "Motion:", "Control:", "Purposes:", "Files:"})
        EXPECT_NE(r.out.find(group), std::string::npos) << group;
    for (const char* command : {"pose", "inverse-dynamics", "loads", "simulate", "control", "identify", "shake",
                                "reproduce", "convert", "envelope", "workspace", "animate", "excite", "regressor"})
        EXPECT_NE(r.out.find("\n  " + std::string(command) + " "), std::string::npos) << command;
    EXPECT_EQ(r.out.find("The robot is the 3-PRR"), std::string::npos);
}

TEST(CliHelp, ACommandsHelpKeepsItsWholeDescription) {
    const CliResult r = runCli("loads --help");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("Example: nocdyn loads"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("--envelope"), std::string::npos) << r.out;
}

TEST(CliHelp, OneVocabularyForOutputsTheOldSpellingsHidden) {
    const CliResult top = runCli("--help");
    EXPECT_NE(top.out.find("-o/--output FILE"), std::string::npos) << top.out;
    EXPECT_NE(top.out.find("--out-dir DIR"), std::string::npos) << top.out;
    for (const char* command : {"animate", "excite", "convert"}) {
        const CliResult r = runCli(std::string(command) + " --help");
        EXPECT_NE(r.out.find("-o,--output"), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("--out "), std::string::npos) << r.out;
    }
    for (const char* command : {"shake", "reproduce"}) {
        const CliResult r = runCli(std::string(command) + " --help");
        EXPECT_NE(r.out.find("--out-dir"), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("--out "), std::string::npos) << r.out;
    }
    // every plant wherever a plant is chosen
    for (const char* command : {"control", "shake"}) {
        const CliResult r = runCli(std::string(command) + " --help");
        EXPECT_NE(r.out.find("nocdyn-rk4"), std::string::npos) << r.out;
    }
    EXPECT_NE(runCli("convert --help").out.find("--robot"), std::string::npos);
}

TEST(CliHelp, VersionIsTheProjectVersion) {
    const CliResult r = runCli("--version");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // then the commit built (cli_common_options_test: CommonOptions.VersionNamesTheCommitBuilt)
    EXPECT_EQ(r.out.rfind("nocdyn " NOCDYN_PROJECT_VERSION " (commit ", 0), 0U) << r.out;
}

}  // namespace
}  // namespace nocdyn::test
