// nocdyn loads: binds app::LoadsOptions and renders every joint's design loads as a table on
// stdout, a CSV and a figure of the robot at the worst pose with its joint forces.
#include <cstdio>
#include <memory>
#include <string>

#include "app/loads.hpp"
#include "app/outputs.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace loads_command {

struct Options : app::LoadsOptions {
    std::string output, figure;
};

void run(const Options& options) {
    if (options.envelope && options.max_frequency < options.min_frequency) {
        throw CLI::ValidationError("--max-frequency", "must be at least --min-frequency");
    }
    if (!options.envelope && options.trajectory.empty()) {
        throw CLI::ValidationError("--trajectory", "is required (or give --envelope)");
    }
    if (!options.figure.empty()) app::requireLoadsFigure(options);
    TerminalObserver observer("nocdyn loads");
    const app::LoadsResult result = app::runLoads(options, observer);
    observer.finish();
    if (!options.output.empty()) writeTable(result.table, options.output);
    std::fputs(result.text.c_str(), stdout);
    if (!options.figure.empty()) app::writeLoadsFigure(options, result, options.figure);
}

}  // namespace loads_command

void addLoadsCommand(CLI::App& app) {
    auto options = std::make_shared<loads_command::Options>();
    CLI::App* command = app.add_subcommand(
        "loads",
        "Design loads of every joint (the bearing loads a designer sizes parts by): along a trajectory, or\n"
        "with --envelope over the operating envelope's motions (each axis at log-spaced frequencies, at the\n"
        "largest amplitude within every limit), each joint's peak and RMS reaction force |(fx, fy)| [N] and\n"
        "peak couple |m| [N m], with the time and pose of the peak. Reactions as in `inverse-dynamics\n"
        "--reactions`. Prints a table; --output writes it as CSV (limb and joint 1-based), --figure draws\n"
        "the robot at the worst pose with each joint's force. A two-DOF robot (motion: translation, pose\n"
        "[x, y]) takes a trajectory keyed x, y (no --envelope). A spatial robot (space: spatial) takes a\n"
        "trajectory file keyed x, y, z (roll, pitch, yaw): each listed joint's |force| and |moment| about its\n"
        "point, with its type (R, P, U, S) in the table (no --envelope, no --figure).\n"
        "Example: nocdyn loads --robot robots/3-rrr.yaml --trajectory paper1 --figure loads");
    command->add_option("--trajectory", options->trajectory,
                        "paper1, paper2 (eqs. 33-34), a trajectory file (YAML, harmonics) or samples (.csv)");
    addRobotOption(*command, options->robot);
    command->add_option("--duration", options->duration, "Seconds to sample [default: the file's duration, else 0.2]")
        ->check(within(app::kDurationRange));
    command->add_option("--rate", options->rate, "Samples per second")
        ->check(within(app::kRateRange))
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV file to write [default: none]")->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Figure stem (STEM.png, STEM.svg) [default: none]")
        ->check(nonEmptyPath());
    command->add_flag("--envelope", options->envelope, "Over the operating envelope's motions instead of a trajectory")
        ->excludes("--trajectory");
    command->add_option("--min-frequency", options->min_frequency, "--envelope: [Hz]")
        ->check(within(app::kEnvelopeFrequencyRange))
        ->capture_default_str();
    command->add_option("--max-frequency", options->max_frequency, "--envelope: [Hz]")
        ->check(within(app::kEnvelopeFrequencyRange))
        ->capture_default_str();
    command->add_option("--points", options->points, "--envelope: frequencies per axis")
        ->check(CLI::Range(1, kEnvelopeMaxPoints))
        ->capture_default_str();
    command->callback([options] { loads_command::run(*options); });
}

}  // namespace nocdyn::cli
