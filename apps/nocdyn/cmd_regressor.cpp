// nocdyn regressor: binds app::RegressorOptions and prints (or writes) the report: the robot's
// standard inertial and friction parameters, and which combinations of them (base parameters)
// the actuator forces can identify.
#include <memory>

#include "app/regressor.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace regressor_command {

struct Options : app::RegressorOptions {
    std::string output;
};

void run(const Options& options) {
    TerminalObserver observer("nocdyn regressor");
    writeText(app::runRegressor(options, observer).text, options.output);
}

}  // namespace regressor_command

void addRegressorCommand(CLI::App& app) {
    auto options = std::make_shared<regressor_command::Options>();
    CLI::App* command = app.add_subcommand(
        "regressor",
        "The dynamics are linear in each body's planar inertial parameters [m, m c_x, m c_y, I_O] (body frame:\n"
        "a limb body's is the base frame at home, moving with it; the platform's has its origin at C) and in each\n"
        "joint's damping and Coulomb friction: tau = Y(q, dq, ddq) pi. Prints pi from the robot file, then the\n"
        "base parameters (the combinations the actuator forces identify) found by a column-pivoted QR of Y over\n"
        "random motions around home, and the parameters that have no effect or only act in combination. A\n"
        "two-DOF robot's (motion: translation) platform is a point mass at the tool point: of its parameters only\n"
        "m acts.");
    addRobotOption(*command, options->robot);
    command->add_option("--samples", options->samples, "Random motions stacked")
        ->check(CLI::Range(20, 100000))
        ->capture_default_str();
    command->add_option("--seed", options->seed, "Seed of the random motions")->capture_default_str();
    command->add_option("--output,-o", options->output, "Text file to write [default: stdout]")->check(nonEmptyPath());
    command->callback([options] { regressor_command::run(*options); });
}

}  // namespace nocdyn::cli
