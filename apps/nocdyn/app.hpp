// The whole `nocdyn` command line, shared by the executable (main.cpp) and the Python package
// (python/src/module.cpp), so that both run the very same commands, defaults and checks.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace nocdyn::cli {

/// Every command, grouped for `nocdyn --help`, with --version.
[[nodiscard]] std::unique_ptr<CLI::App> makeApp();

/// `nocdyn` with these arguments (argv[0] the program): messages on stderr as the command line
/// prints them; returns the exit status (0, 1 for an error, 2 for a malformed argument).
int runCommandLine(int argc, const char* const* argv);

/// One command for a library caller, arguments without the program name (e.g. {"pose", "0",
/// "0", "0"}): throws CLI::ParseError for a malformed argument and nocdyn::Error (or another
/// std::exception) for a failure, instead of printing them.
void runCommand(const std::vector<std::string>& arguments);

/// Every command's options as JSON: names, default, flag, positional, hidden (an old spelling).
[[nodiscard]] std::string optionsJson();

}  // namespace nocdyn::cli
