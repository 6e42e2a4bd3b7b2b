// nocdyn regressor: the robot's standard inertial and friction parameters, and which
// combinations of them (base parameters) the actuator forces can identify.
#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::cli {

namespace {

struct RegressorOptions {
    std::string robot, output;
    int samples = 200;
    unsigned seed = 1;
};

void run(const RegressorOptions& options) {
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    BaseParameterOptions base_options;
    base_options.samples = options.samples;
    base_options.seed = options.seed;
    const BaseParameters base = baseParameters(model, base_options);
    const ParameterVector pi = standardParameters(model);
    std::string text = "# standard parameters (robot file values)\n";
    char line[160];
    for (int c = 0; c < parameterCount(model); ++c) {
        std::snprintf(line, sizeof line, "%-28s %15.9g %s\n", parameterName(model, c).c_str(), pi(c),
                      parameterUnit(model, c).c_str());
        text += line;
    }
    text += describeBaseParameters(model, base);
    if (options.output.empty()) {
        std::cout << text;
        std::cout.flush();
        if (!std::cout) throw Error("cannot write to standard output");
    } else {
        io::writeTextFile(options.output, text);
    }
}

}  // namespace

void addRegressorCommand(CLI::App& app) {
    auto options = std::make_shared<RegressorOptions>();
    CLI::App* command = app.add_subcommand(
        "regressor",
        "The dynamics are linear in each body's planar inertial parameters [m, m c_x, m c_y, I_O] (body frame:\n"
        "a limb body's is the base frame at home, moving with it; the platform's has its origin at C) and in each\n"
        "joint's damping and Coulomb friction: tau = Y(q, dq, ddq) pi. Prints pi from the robot file, then the\n"
        "base parameters (the combinations the actuator forces identify) found by a column-pivoted QR of Y over\n"
        "random motions around home, and the parameters that have no effect or only act in combination.");
    addRobotOption(*command, options->robot);
    command->add_option("--samples", options->samples, "Random motions stacked")
        ->check(CLI::Range(20, 100000))
        ->capture_default_str();
    command->add_option("--seed", options->seed, "Seed of the random motions")->capture_default_str();
    command->add_option("--output,-o", options->output, "Text file to write [default: stdout]")->check(nonEmptyPath());
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
