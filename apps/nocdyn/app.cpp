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
#include "progress.hpp"
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

/// Every command's options as JSON, for the Python parity test and the vocabulary table
/// (docs/vocabulary.md): per command, per option its names, its default as the command line
/// prints it, whether it is a flag, positional or hidden (an old spelling), its type with the
/// accepted range and unit, and its help.
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
                               {"default", option->get_default_str()},
                               {"type", option->get_type_name()},
                               {"help", option->get_description()}});
        }
        commands[command->get_name()] = options;
    }
    return commands.dump(1);
}

/// Whether everything written to standard output (iostreams and stdio) reached it; else says so
/// on standard error (a closed pipe, a full disk).
bool standardOutputWritten() {
    std::cout.flush();
    if (std::cout && std::fflush(stdout) == 0 && !std::ferror(stdout)) return true;
    std::cerr << "nocdyn: error: cannot write standard output: " << std::strerror(errno) << "\n";
    return false;
}

/// Levenshtein distance (insertions, deletions, substitutions), for "did you mean".
std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

/// The name nearest `typed` among `names` when it is near enough to be a slip (at most a third of
/// its letters wrong, at least 2 allowed) or a prefix of one; empty when none is.
std::string nearest(const std::string& typed, const std::vector<std::string>& names) {
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(2, typed.size() / 3) + 1;
    for (const std::string& name : names) {
        const std::size_t d = name.starts_with(typed) && typed.size() >= 3 ? 1 : editDistance(typed, name);
        if (d < best_distance) {
            best_distance = d;
            best = name;
        }
    }
    return best;
}

/// The command of that name, or nullptr.
CLI::App* findCommand(CLI::App& app, const std::string& name) {
    for (CLI::App* command : app.get_subcommands({})) {
        if (command->get_name() == name) return command;
    }
    return nullptr;
}

std::vector<std::string> commandNames(CLI::App& app) {
    std::vector<std::string> names;
    for (CLI::App* command : app.get_subcommands({})) names.push_back(command->get_name());
    return names;
}

/// A mistyped command or long option named with the nearest one, before CLI11 parses (which
/// would report a missing required option or subcommand instead); empty when all are known.
std::string misspelling(CLI::App& app, const std::vector<std::string>& arguments) {
    if (arguments.empty() || arguments.front().starts_with("-")) return {};
    const std::vector<std::string> commands = commandNames(app);
    const std::string& typed = arguments.front();
    CLI::App* command = findCommand(app, typed);
    if (command == nullptr) {
        const std::string near = nearest(typed, commands);
        std::string list;
        for (const std::string& name : commands) list += (list.empty() ? "" : ", ") + name;
        return "unknown command '" + nocdyn::io::terminalText(typed) + "'" +
               (near.empty() ? " (the commands: " + list + ")" : "; did you mean '" + near + "'?");
    }
    std::vector<std::string> options;
    for (const CLI::Option* option : command->get_options()) {
        for (const std::string& name : option->get_lnames()) options.push_back("--" + name);
    }
    for (std::size_t i = 1; i < arguments.size(); ++i) {
        const std::string& argument = arguments[i];
        if (argument == "--") break;  // the rest are positional
        if (!argument.starts_with("--") || argument.size() == 2) continue;
        const std::string name = argument.substr(0, argument.find('='));
        if (command->get_option_no_throw(name) != nullptr) continue;
        const std::string near = nearest(name, options);
        return "nocdyn " + typed + ": unknown option '" + nocdyn::io::terminalText(name) + "'" +
               (near.empty() ? "" : "; did you mean '" + near + "'?");
    }
    return {};
}

/// Where an error on this command line points the user: the help of the command named first,
/// else the top-level help (the list of commands).
std::string helpPointer(CLI::App& app, const std::vector<std::string>& arguments) {
    if (!arguments.empty() && findCommand(app, arguments.front()) != nullptr)
        return "(see nocdyn " + arguments.front() + " --help)";
    return "(see nocdyn --help)";
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
        "Every command takes --quiet (-q): nothing on standard error but errors and warnings.\n"
        "Run `nocdyn <command> --help` (or `nocdyn help <command>`) for a command's details, options and an\n"
        "example; `nocdyn --version` (-V) for the version and the commit built (the commit of the last\n"
        "configure). Without arguments, nocdyn prints this help on standard error and exits with status 2.",
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
    addFrequencyResponseCommand(app);
#ifdef NOCDYN_HAS_ENGINES
    addValidateCommand(app);
#endif
    app.set_version_flag("--version,-V", versionText());
    // one --quiet for every command, read through progress.hpp's quiet()
    for (CLI::App* command : app.get_subcommands({})) addQuietOption(*command);
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
        {"Control", {"control", "frequency-response", "excite", "identify"}},
        {"Purposes", {"shake", "reproduce", "validate", "design"}},
        {"Files", {"convert"}},
    };
    // an example in every command's --help: the commands whose description has none get theirs
    // here (runnable from the repository's root)
    const std::pair<const char*, const char*> examples[] = {
        {"inverse-dynamics", "nocdyn inverse-dynamics --trajectory paper1 --output paper1.csv"},
        {"forward-kinematics", "nocdyn forward-kinematics 0.001 -0.0005 0.0002 --all-branches"},
        {"simulate",
         "nocdyn inverse-dynamics --trajectory paper1 -o forces.csv && nocdyn simulate --forces forces.csv "
         "-o motion.csv"},
        {"envelope", "nocdyn envelope --output envelope.csv --figure envelope"},
        {"animate",
         "nocdyn animate --trajectory paper1 --output paper1.html   (a replay: --trajectory shake/shake.csv)"},
        {"convert", "nocdyn convert robots/paper-3prr.yaml --output paper-3prr-general.yaml"},
        {"shake", "nocdyn shake --record data/elcentro_1940_ns.AT2 --out-dir shake"},
        {"excite", "nocdyn excite --payload-guess 0.5 0 0 2e-4 --output excitation.yaml"},
        {"regressor", "nocdyn regressor --robot robots/3-rrr.yaml"},
        {"reproduce", "nocdyn reproduce --out-dir results"},
        {"validate", "nocdyn validate --trajectory paper1 --output validation.csv"},
    };
    for (const auto& [name, example] : examples) {
        CLI::App* command = findCommand(app, name);
        if (command != nullptr && command->get_description().find("Example: ") == std::string::npos) {
            command->description(command->get_description() + "\nExample: " + example);
        }
    }
    for (CLI::App* command : app.get_subcommands({})) {
        const std::string text = command->get_description();
        if (text.find('\n') != std::string::npos) {
            command->description(summary(text));
            command->footer(text);
        }
        // a command in no group would be listed under CLI11's own "Subcommands" heading
        command->group("Other");
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

int runCommandLine(int argc, const char* const* argv) {
    nocdyn::io::removeTemporariesOnSignals();
    const std::unique_ptr<CLI::App> owned = makeApp();
    CLI::App& app = *owned;
    // hidden: the options of every command as JSON (tests/python/test_parity.py)
    if (argc == 2 && std::string(argv[1]) == "--help-json") {
        std::cout << describeOptions(app) << "\n";
        return standardOutputWritten() ? 0 : 1;
    }
    // hidden: docs/output-formats.md, the CSV layouts from their registry (its test compares)
    if (argc == 2 && std::string(argv[1]) == "--output-formats") {
        std::cout << nocdyn::io::outputFormatsMarkdown();
        return standardOutputWritten() ? 0 : 1;
    }
    std::vector<std::string> arguments(argv + 1, argv + argc);
    // `nocdyn help [COMMAND]`: the same as `nocdyn [COMMAND] --help`; `help help` is the
    // top-level help, which says how help is used
    if (!arguments.empty() && arguments.front() == "help") {
        if (arguments.size() > 2) {
            std::cerr << "nocdyn: error: help takes one command name, got " << arguments.size() - 1
                      << " arguments (nocdyn help COMMAND; see nocdyn --help)\n";
            return 2;
        }
        if (arguments.size() == 2 && arguments[1] == "help") arguments.pop_back();
        if (arguments.size() == 2 && findCommand(app, arguments[1]) == nullptr) {
            const std::string typo = misspelling(app, {arguments[1]});
            std::cerr << "nocdyn: error: "
                      << (typo.empty() ? "unknown command '" + nocdyn::io::terminalText(arguments[1]) + "'" : typo)
                      << " (see nocdyn --help)\n";
            return 2;
        }
        std::vector<const char*> help{argv[0]};
        if (arguments.size() == 2) help.push_back(argv[2]);
        help.push_back("--help");
        return runCommandLine(static_cast<int>(help.size()), help.data());
    }
    // no command: the help (the list of commands) as the usage message, on standard error, and
    // the status of a malformed command line
    if (arguments.empty()) {
        std::cerr << app.help();
        return 2;
    }
    if (const std::string typo = misspelling(app, arguments); !typo.empty()) {
        std::cerr << "nocdyn: error: " << typo << " " << helpPointer(app, arguments) << "\n";
        return 2;
    }
    announceWrittenFiles();
    setQuiet(false);  // the command's --quiet sets it while parsed (addQuietOption)
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version exit 0; a malformed argument is one line on stderr and exit 2
        // (README, "Command line").
        if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
            app.exit(e);
            // the help or version text is the command's output: a failed write is an error
            return standardOutputWritten() ? 0 : 1;
        }
        std::cerr << "nocdyn: error: " << nocdyn::io::terminalMessage(e.what()) << " " << helpPointer(app, arguments)
                  << "\n";
        return 2;
    } catch (const nocdyn::app::OptionError& e) {
        // a value the command's job refused, under the option's name on the command line
        const std::vector<CLI::App*> parsed = app.get_subcommands();
        const std::string message = commandLineMessage(e, parsed.empty() ? nullptr : parsed.front());
        std::cerr << "nocdyn: error: " << nocdyn::io::terminalMessage(message) << " " << helpPointer(app, arguments)
                  << "\n";
        return 1;
    } catch (const nocdyn::Error& e) {
        std::cerr << "nocdyn: error: " << nocdyn::io::terminalMessage(e.what()) << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "nocdyn: error: " << nocdyn::io::terminalMessage(e.what()) << "\n";
        return 1;
    }
    // What went to stdout through stdio (tables of pose, control, envelope) is checked too.
    return standardOutputWritten() ? 0 : 1;
}

}  // namespace nocdyn::cli
