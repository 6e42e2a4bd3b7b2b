// nocdyn: kinematics and dynamics of any planar parallel robot by the natural orthogonal
// complement. Every sub-command is in its own cmd_*.cpp file; this file groups them for --help.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/output.hpp"

namespace {

/// The first sentence of a command's description on one line, at most 100 characters (cut at a
/// word, with "...").
std::string summary(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    // a sentence ends at ". " before a capital (not "c.o.m. x" or "eq. 23")
    for (std::size_t stop = text.find(". "); stop != std::string::npos; stop = text.find(". ", stop + 1)) {
        if (stop > 0 && text[stop - 1] != '.' && text[stop - 1] != ' ' && stop + 2 < text.size() &&
            std::isupper(static_cast<unsigned char>(text[stop + 2])) != 0) {
            text.resize(stop);
            break;
        }
    }
    if (!text.empty() && text.back() == '.') text.pop_back();
    constexpr std::size_t kWidth = 100;
    if (text.size() > kWidth) {
        const std::size_t space = text.rfind(' ', kWidth - 4);
        text = text.substr(0, space == std::string::npos ? kWidth - 4 : space) + " ...";
    }
    return text;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "nocdyn: kinematics and dynamics of planar parallel robots by the natural orthogonal complement.\n"
        "Any robot file (--robot; default: the paper's 3-PRR vibration generator). SI units: m, kg, s, rad, N.\n"
        "Run `nocdyn <command> --help` for a command's details, options and an example.",
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
    nocdyn::cli::addDesignCommand(app);
#ifdef NOCDYN_HAS_ENGINES
    nocdyn::cli::addValidateCommand(app);
#endif
    nocdyn::io::removeTemporariesOnSignals();
    app.set_version_flag("--version", std::string("nocdyn ") + NOCDYN_VERSION);
    // one line per command in `nocdyn --help`, grouped; the rest of each description is shown
    // by the command's own --help
    const std::pair<const char*, std::vector<std::string>> groups[] = {
        {"Model", {"pose", "inverse-dynamics", "forward-kinematics", "loads", "regressor"}},
        {"Motion", {"simulate", "envelope", "workspace", "animate"}},
        {"Control", {"control", "excite", "identify"}},
        {"Purposes", {"shake", "reproduce", "validate", "design"}},
        {"Files", {"convert"}},
    };
    for (CLI::App* command : app.get_subcommands({})) {
        const std::string text = command->get_description();
        if (text.find('\n') != std::string::npos) {
            command->description(summary(text));
            command->footer(text);
        }
        for (const auto& [group, names] : groups) {
            if (std::find(names.begin(), names.end(), command->get_name()) != names.end()) command->group(group);
        }
    }
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
