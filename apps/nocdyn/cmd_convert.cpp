// nocdyn convert: any robot file (short or general form) -> the general per-limb form.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn::cli {

namespace {

struct ConvertOptions {
    std::string robot;
    std::string output;
};

void run(const ConvertOptions& options) {
    const RobotDescription robot = io::loadRobotDescription(options.robot, parameterOverrides());
    const Model model(robot);  // the home posture must be regular, as for every command
    std::string text = "# " + io::terminalText(robot.name) + ": " + std::to_string(model.limbs) + " limbs (";
    for (int j = 0; j < model.limbs; ++j) text += (j ? " " : "") + robot.limbs[static_cast<std::size_t>(j)].type();
    text += "), " + std::to_string(model.actuators) + " actuators; general form of " + io::terminalText(options.robot) +
            "\n";
    text += io::descriptionToYaml(robot);
    if (options.output.empty()) {
        std::cout << text;
        std::cout.flush();
        if (!std::cout) throw Error("cannot write to standard output");
    } else {
        io::writeTextFile(options.output, text);
    }
}

}  // namespace

void addConvertCommand(CLI::App& app) {
    auto options = std::make_shared<ConvertOptions>();
    CLI::App* command =
        app.add_subcommand("convert",
                           "Print a robot file in the general per-limb form (the paper's 3-PRR short form expanded:\n"
                           "its stroke and peak force become each P joint's limits). Numbers are written in their\n"
                           "shortest round-trip form, so reading the output back gives the same robot exactly.\n"
                           "A parametric file's expressions are evaluated (--set NAME=VALUE overrides a parameter):\n"
                           "the output is the plain robot file that parameter set means.");
    auto* robot = command->add_option("--robot", options->robot, "Robot file (YAML), short or general form (required)")
                      ->check(CLI::ExistingFile);
    // the robot as a positional argument, the old spelling, still accepted
    auto* positional = command->add_option("ROBOT", options->robot, "The same as --robot")->check(CLI::ExistingFile);
    positional->excludes(robot);
    command->add_option("--output,-o", options->output, "File to write [default: stdout]")->check(nonEmptyPath());
    addParameterOption(*command);
    command->callback([options, robot, positional] {
        if (robot->count() + positional->count() == 0) throw CLI::RequiredError("--robot");
        run(*options);
    });
}

}  // namespace nocdyn::cli
