// nocdyn: kinematics and dynamics of the paper's 3-PRR planar parallel robot by the
// natural orthogonal complement. Every sub-command is in its own cmd_*.cpp file.
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>

#include "commands.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/output.hpp"

int main(int argc, char** argv) {
    CLI::App app{
        "nocdyn: kinematics and dynamics of planar parallel robots by the natural orthogonal complement.\n"
        "The robot is the 3-PRR vibration generator of the paper (SI units throughout: m, kg, s, rad, N).\n"
        "Run `nocdyn <command> --help` for the options of a command.",
        "nocdyn"};
    app.require_subcommand(1);
    nocdyn::cli::addPoseCommand(app);
    nocdyn::cli::addInverseDynamicsCommand(app);
    nocdyn::cli::addReproduceCommand(app);
    nocdyn::cli::addForwardKinematicsCommand(app);
    nocdyn::cli::addSimulateCommand(app);
    nocdyn::cli::addControlCommand(app);
    nocdyn::cli::addEnvelopeCommand(app);
    nocdyn::cli::addWorkspaceCommand(app);
    nocdyn::cli::addConvertCommand(app);
    nocdyn::cli::addAnimateCommand(app);
    nocdyn::cli::addShakeCommand(app);
    nocdyn::cli::addRegressorCommand(app);
    nocdyn::cli::addIdentifyCommand(app);
    nocdyn::cli::addExciteCommand(app);
    nocdyn::cli::addLoadsCommand(app);
#ifdef NOCDYN_HAS_ENGINES
    nocdyn::cli::addValidateCommand(app);
#endif
    nocdyn::io::removeTemporariesOnSignals();
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version exit 0; a malformed argument is one line on stderr and exit 2
        // (README, "Command line").
        if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
        std::cerr << "nocdyn: error: " << nocdyn::io::terminalMessage(e.what()) << " (see --help)\n";
        return 2;
    } catch (const nocdyn::Error& e) {
        std::cerr << "nocdyn: error: " << nocdyn::io::terminalMessage(e.what()) << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "nocdyn: error: " << nocdyn::io::terminalMessage(e.what()) << "\n";
        return 1;
    }
    // What went to stdout through stdio (tables of pose, control, envelope) is checked too.
    if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
        std::cerr << "nocdyn: error: cannot write standard output: " << std::strerror(errno) << "\n";
        return 1;
    }
    return 0;
}
