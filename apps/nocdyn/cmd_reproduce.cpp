// nocdyn reproduce: the options, the progress line and the closing line around the application
// layer's runReproduce() (app/reproduce.hpp).
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/reproduce.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace reproduce_command {

void run(const app::ReproduceOptions& options) {
    // about two minutes in all: one progress line on a terminal names the section running
    // (none with --quiet)
    TerminalObserver observer("nocdyn reproduce");
    app::OutputFolder files(options.out_dir, app::OutputFolder::Wording::output_folder);
    const app::ReproduceResult result = app::runReproduce(options, observer, files);
    observer.finish();
    if (quiet()) return;
    std::cout << "nocdyn reproduce: wrote " << result.summary.string() << ", CSV files and figures in "
              << result.folder.string() << "/\n";
}

}  // namespace reproduce_command

void addReproduceCommand(CLI::App& app) {
    auto options = std::make_shared<app::ReproduceOptions>();
    CLI::App* command = app.add_subcommand(
        "reproduce",
        "The main job: reproduce the paper's results for its prototype. Both paper trajectories over\n"
        "0.2 s at 10 kHz: one CSV each, figures like the paper's Figs. 5 and 6 (motor displacements and\n"
        "forces, PNG and SVG, drawn by gnuplot, with the Simbody curves overlaid and their difference\n"
        "plotted), and summary.md with: peak stroke and force per actuator against the actuator limits;\n"
        "the measured agreement with Simbody and MuJoCo; the forward-dynamics round trip; closed-loop\n"
        "computed-torque and PD control on the Simbody plant; the operating envelope (stroke and force);\n"
        "and the example robots of other architectures (3-RRR, 3-RPR, redundant 4-RRR) against both engines;\n"
        "and the payload identification experiment, simulated on the Simbody plant (identification/).");
    auto* out_dir =
        command->add_option("--out-dir", options->out_dir, "Output folder (created if missing)")->capture_default_str();
    addOldSpelling(*command, "--out", out_dir, options->out_dir);
    command
        ->add_option("--closed-loop-duration", options->closed_loop_duration,
                     "Seconds of each closed-loop run on a Simbody plant (the paper's trajectories and the\n"
                     "example robots; about 0.3-0.6 ms of CPU per 10 kHz tick). A shorter run is a quick check of\n"
                     "the same code, its peak errors over less of the trajectory")
        ->check(within(app::kClosedLoopDurationRange))
        ->capture_default_str();
    command
        ->add_option("--identification-duration", options->identification_duration,
                     "Seconds of data of each identification experiment (designed excitation with and without\n"
                     "slider friction, paper trajectories 1 and 2; 10 kHz on the Simbody plant). A shorter run\n"
                     "is a quick check of the same code, its estimates from less data")
        ->check(within(app::kIdentificationDurationRange))
        ->capture_default_str();
    command->callback([options] { reproduce_command::run(*options); });
}

}  // namespace nocdyn::cli
