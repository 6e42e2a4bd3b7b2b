// Running the `nocdyn` binary from a test: exit code, stdout and stderr, per-test scratch files.
#pragma once

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace nocdyn::test {

struct CliResult {
    int exit_code = -1;
    std::string out, err;
};

inline std::string readWhole(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// A name private to the running test: ctest runs the tests in parallel processes. A value-
/// parametrised test's name ("Test/param") becomes one file name ("Test_param").
inline std::string perTest(const std::string& name) {
    std::string test = testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : test) c = c == '/' ? '_' : c;
    return test + "_" + name;
}

/// An empty directory private to the running test.
inline std::filesystem::path freshScratchDirectory(const std::string& suite) {
    const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / suite / perTest("dir");
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// Runs `nocdyn ARGUMENTS` through the shell (ARGUMENTS may redirect stdout).
inline CliResult runCli(const std::string& arguments) {
    const std::filesystem::path err_file = std::filesystem::path(testing::TempDir()) / perTest("stderr.txt");
    const std::string command = std::string(NOCDYN_CLI) + " " + arguments + " 2>" + err_file.string();
    CliResult result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.out.append(buffer, n);
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.err = readWhole(err_file);
    return result;
}

}  // namespace nocdyn::test
