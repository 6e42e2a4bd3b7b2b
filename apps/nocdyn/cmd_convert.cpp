// nocdyn convert: binds app::ConvertOptions and prints (or writes) any robot file (short or
// general form) in the general per-limb form.
#include <memory>

#include "app/convert.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace convert_command {

struct Options : app::ConvertOptions {
    std::string output;
};

void run(const Options& options) {
    TerminalObserver observer("nocdyn convert");
    writeText(app::runConvert(options, observer).text, options.output);
}

}  // namespace convert_command

void addConvertCommand(CLI::App& app) {
    auto options = std::make_shared<convert_command::Options>();
    CLI::App* command =
        app.add_subcommand("convert",
                           "Print a robot file in the general per-limb form (the paper's 3-PRR short form expanded:\n"
                           "its stroke and peak force become each P joint's limits). Numbers are written in their\n"
                           "shortest round-trip form, so reading the output back gives the same robot exactly.\n"
                           "A parametric file's expressions are evaluated (--set NAME=VALUE overrides a parameter):\n"
                           "the output is the plain robot file that parameter set means.");
    addRobotOption(*command, options->robot);
    CLI::Option* robot = command->get_option("--robot");
    robot->description("Robot file (YAML), short or general form (required)");
    // the robot as a positional argument, the old spelling, still accepted
    auto* positional =
        command->add_option("ROBOT", options->robot.path, "The same as --robot")->check(CLI::ExistingFile);
    positional->excludes(robot);
    command->add_option("--output,-o", options->output, "File to write [default: stdout]")->check(nonEmptyPath());
    command->callback([options, robot, positional] {
        if (robot->count() + positional->count() == 0) throw CLI::RequiredError("--robot");
        convert_command::run(*options);
    });
}

}  // namespace nocdyn::cli
