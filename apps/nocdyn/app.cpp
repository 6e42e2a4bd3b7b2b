// The `nocdyn` command line as a library (the executable and the Python package both run it):
// every sub-command is in its own cmd_*.cpp file; this file groups them for --help.
#include "app.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

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
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/layouts.hpp"
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

/// Every command's options as JSON, for the Python parity test: per command, per option its
/// names, its default as the command line prints it, whether it is a flag, positional or
/// hidden (an old spelling).
std::string describeOptions(CLI::App& app) {
    nlohmann::json commands = nlohmann::json::object();
    for (CLI::App* command : app.get_subcommands({})) {
        nlohmann::json options = nlohmann::json::array();
        for (CLI::Option* option : command->get_options()) {
            if (option == command->get_help_ptr()) continue;
            option->capture_default_str();
            options.push_back({{"name", option->get_single_name()},
                               {"long", option->get_lnames()},
                               {"short", option->get_snames()},
                               {"positional", option->get_positional() && option->get_lnames().empty()},
                               {"flag", option->get_expected_max() == 0},
                               {"hidden", option->get_group().empty()},
                               {"required", option->get_required()},
                               {"default", option->get_default_str()}});
        }
        commands[command->get_name()] = options;
    }
    return commands.dump(1);
}

}  // namespace

namespace nocdyn::cli {

std::unique_ptr<CLI::App> makeApp() {
    auto owned = std::make_unique<CLI::App>(
        "nocdyn: kinematics and dynamics of planar parallel robots by the natural orthogonal complement.\n"
        "Any robot file (--robot; default: the paper's 3-PRR vibration generator). SI units: m, kg, s, rad, N.\n"
        "Output files: -o/--output FILE for a command's one output file (a table: stdout without it),\n"
        "--out-dir DIR for the folder of a command with several, --figure STEM for a figure (STEM.png,\n"
        "STEM.svg): figures only when asked for.\n"
        "Run `nocdyn <command> --help` for a command's details, options and an example.",
        "nocdyn");
    CLI::App& app = *owned;
    app.require_subcommand(1);
    addPoseCommand(app);
    addInverseDynamicsCommand(app);
    addReproduceCommand(app);
    addForwardKinematicsCommand(app);
    addSimulateCommand(app);
    addControlCommand(app);
    addEnvelopeCommand(app);
    addWorkspaceCommand(app);
    addConvertCommand(app);
    addAnimateCommand(app);
    addShakeCommand(app);
    addRegressorCommand(app);
    addIdentifyCommand(app);
    addExciteCommand(app);
    addLoadsCommand(app);
    addDesignCommand(app);
#ifdef NOCDYN_HAS_ENGINES
    addValidateCommand(app);
#endif
    app.set_version_flag("--version", std::string("nocdyn ") + NOCDYN_VERSION);
    requireFiniteFloats(app);
    // before the chosen command runs: none may write over its own input
    app.parse_complete_callback([&app] {
        for (const CLI::App* command : app.get_subcommands()) refuseOutputOverInput(*command);
    });
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
    return owned;
}

std::string optionsJson() {
    const std::unique_ptr<CLI::App> app = makeApp();
    return describeOptions(*app);
}

void runCommand(const std::vector<std::string>& arguments) {
    // --set of an earlier command run in this process must not reach this one
    clearParameterOverrides();
    const std::unique_ptr<CLI::App> app = makeApp();
    std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());  // CLI11 parses from the back
    app->parse(reversed);
}

int runCommandLine(int argc, const char* const* argv) {
    nocdyn::io::removeTemporariesOnSignals();
    clearParameterOverrides();
    const std::unique_ptr<CLI::App> owned = makeApp();
    CLI::App& app = *owned;
    // hidden: the options of every command as JSON (tests/python/test_parity.py)
    if (argc == 2 && std::string(argv[1]) == "--help-json") {
        std::cout << describeOptions(app) << "\n";
        return 0;
    }
    // hidden: docs/output-formats.md, the CSV layouts from their registry (its test compares)
    if (argc == 2 && std::string(argv[1]) == "--output-formats") {
        std::cout << nocdyn::io::outputFormatsMarkdown();
        return 0;
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

}  // namespace nocdyn::cli
