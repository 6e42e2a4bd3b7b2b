// nocdyn identify: binds app::IdentifyOptions and prints the identification's report (YAML); the
// application layer reads the log and solves, and this command writes --output and --figure.
#include <memory>
#include <string>

#include "app/identify.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/layouts.hpp"
#include "render/plot.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace identify_command {

struct Options : app::IdentifyOptions {
    std::string output;  ///< the robot with the payload merged, or the calibration (YAML)
    std::string figure;  ///< STEM of the held-out forces' figure
};

void run(const Options& options) {
    TerminalObserver observer("nocdyn identify");
    const app::IdentifyResult result = app::runIdentify(options, observer);
    observer.finish();
    if (!options.output.empty()) io::writeTextFile(options.output, result.yaml);
    if (!options.figure.empty()) render::renderFigure(result.figure, options.figure);
    printText(result.text);
}

}  // namespace identify_command

void addIdentifyCommand(CLI::App& app) {
    auto options = std::make_shared<identify_command::Options>();
    CLI::App* command = app.add_subcommand(
        "identify",
        "Identify a payload fixed to the platform (mass, c.o.m. [x, y] in the platform frame, moment of inertia\n"
        "about its own c.o.m.; the robot's own parameters from the robot file) or the robot's base parameters\n"
        "(--base; see `nocdyn regressor`) from a log of actuator positions and forces. The CSV holds\n"
        "t,u1..un and the forces: tau1..taun measured at each sample, or tau1_held..taun_held, commands held until\n"
        "the next sample (as `nocdyn control --log` writes them; other columns ignored); with du1..dun,ddu1..ddun\n"
        "they are used as given, else u and\n"
        "tau are low-pass filtered (zero phase) and u differentiated. The platform pose comes from the\n"
        "direct-kinematics tracker; weighted least squares (weights from each actuator's residual), then the\n"
        "physically consistent solution (mass > 0, inertia about the c.o.m. >= 0, and the bounds of --prior: the\n"
        "bounded least-squares solution, the bounds it lies on reported as active_bounds); standard deviations\n"
        "from the residuals; the last --holdout of the samples is held out to check the fit. Prints YAML. A\n"
        "two-DOF robot's (motion: translation) payload is a point mass at the tool point: its mass only (no c.o.m.\n"
        "offset, no inertia; --prior may bound only the mass).\n"
        "Example: nocdyn control --trajectory paper2 --payload-mass 0.5 --log log.csv && nocdyn identify --data "
        "log.csv");
    addRobotOption(*command, options->robot);
    command->add_option("--data", options->data, "Measured CSV: " + io::columnList(io::TableId::measurements))
        ->required()
        ->check(CLI::ExistingFile);
    command->add_flag("--payload", options->payload, "Identify a payload (the default)");
    command->add_flag("--base", options->base, "Identify the robot's base parameters (calibration, no payload)");
    command->add_flag("--friction", options->friction,
                      "With --payload: identify the actuated joints' damping and Coulomb friction alongside");
    command->add_flag("--held-forces", options->held_forces,
                      "The logged tau1..taun are commands held until the next sample (zero-order hold): each "
                      "sample's force is taken as the mean of the holds around it. Not needed for columns named "
                      "tau1_held..taun_held (as `nocdyn control --log` writes them), which are taken so anyway");
    command
        ->add_option("--cutoff", options->cutoff,
                     "Low-pass cut-off when du, ddu are not given [Hz] (default: rate/10, at most 50)")
        ->check(within(app::kCutoffRange));
    command->add_option("--holdout", options->holdout, "Fraction of the samples (the last) held out")
        ->check(within(app::kHoldoutRange))
        ->capture_default_str();
    command
        ->add_option("--output,-o", options->output,
                     "YAML to write: the robot file with the payload merged into the platform (--payload), or "
                     "the calibration file of the base parameters (--base)")
        ->check(nonEmptyPath());
    command
        ->add_option("--calibration", options->calibration,
                     "With --payload: a calibration file (identify --base --output on data without payload) whose "
                     "base parameters replace the robot file's own parameters (the robot file still gives the "
                     "geometry)")
        ->check(CLI::ExistingFile);
    command
        ->add_option("--prior", options->prior,
                     "With --payload: a YAML file of bounds on the payload's parameters, e.g. 'payload: {mass: [0.4, "
                     "0.6], com_x: [-0.02, 0.02], com_y: [-0.02, 0.02], inertia: [0, 2e-3]}' (kg, m in the platform "
                     "frame, kg m^2 about the payload's c.o.m.; every key optional, ~ for an open side, equal bounds "
                     "fix a parameter). The estimate is the weighted least-squares solution within them. Not with "
                     "--base: base parameters are combinations of the robot's parameters, which have no such bounds")
        ->check(CLI::ExistingFile);
    command->add_option("--figure", options->figure,
                        "Measured against predicted forces on the held-out samples: writes STEM.png and STEM.svg");
    command->callback([options] { identify_command::run(*options); });
}

}  // namespace nocdyn::cli
