// nocdyn validate: binds app::ValidateOptions, writes the comparison as CSV and the agreement on
// standard error.
#include <iostream>
#include <memory>

#include "app/validate.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace validate_command {

struct Options : app::ValidateOptions {
    std::string output;
};

void run(const Options& options) {
    if (options.trajectory.empty()) {
        // a spatial robot file without a trajectory: read, checked and summarised
        if (const std::optional<std::string> summary = app::checkSpatialRobot(options.robot)) {
            if (!options.output.empty()) {
                throw Error(options.robot.path +
                            ": --output takes the comparison along a trajectory: give --trajectory");
            }
            std::cout << *summary;
            return;
        }
        throw CLI::RequiredError("--trajectory");
    }
    TerminalObserver observer("nocdyn validate");
    const app::ValidateResult result = app::runValidate(options, observer);
    writeTable(result.table, options.output);
    if (quiet()) return;
    std::cerr << "nocdyn validate: " << io::terminalText(result.robot) << ", " << io::terminalText(result.trajectory)
              << ", " << result.samples << " samples\n"
              << result.agreement;
}

}  // namespace validate_command

void addValidateCommand(CLI::App& app) {
    auto options = std::make_shared<validate_command::Options>();
    CLI::App* command = app.add_subcommand(
        "validate",
        "Actuator forces of our NOC model of any robot against two independent multibody engines\n"
        "(Simbody, the reference, and MuJoCo), each built from the same robot file (loops closed at a\n"
        "revolute joint; gravity and joint friction included) and driven by the same platform\n"
        "trajectory. Writes CSV with the columns t,u1..un,tau1..taun,simbody_u1..n,simbody_tau1..n,\n"
        "mujoco_u1..n,mujoco_tau1..n,simbody_dtau1..n,mujoco_dtau1..n and prints on stderr the largest\n"
        "absolute and relative difference per actuator and engine. A spatial robot (space: spatial) is\n"
        "compared with Simbody's and MuJoCo's spatial models (or the one --engine names), in the columns\n"
        "t,x,y,z[,roll,pitch,yaw],u1..n,tau1..n,simbody_tau1..n,mujoco_tau1..n,simbody_dtau1..n,\n"
        "mujoco_dtau1..n; without --trajectory it is read, checked and summarised on stdout.");
    addSamplingOptions(*command, *options);
    // required unless the robot is a spatial one, then only read, checked and summarised (run)
    command->get_option("--trajectory")->required(false);
    addRobotOption(*command, options->robot);
    addChoiceOption(*command, "--engine", options->engine,
                    "Engines a spatial robot is compared with: both, simbody or mujoco (a planar robot: both)");
    command->add_option("--output,-o", options->output, "CSV file to write [default: stdout]")->check(nonEmptyPath());
    command->callback([options] { validate_command::run(*options); });
}

}  // namespace nocdyn::cli
