// The whole `nocdyn` command line, shared by the executable (main.cpp) and `python -m nocdyn`
// (python/src/cli_main.cpp). Both it and the Python functions stand on the application layer.
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

/// `nocdyn --version`: "nocdyn VERSION (commit HASH)", HASH the short commit the build was configured
/// from ("unknown" when the source was not a git checkout).
[[nodiscard]] std::string versionText();

/// Every command's options as JSON: names, default, flag, positional, hidden (an old spelling).
[[nodiscard]] std::string optionsJson();

}  // namespace nocdyn::cli
