// nocdyn excite: binds app::ExciteOptions, prints the design's report and writes the trajectory
// file (the application layer designs it; Ctrl-C ends the process).
#include <iostream>
#include <memory>
#include <string>

#include "app/excite.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace excite_command {

struct Options : app::ExciteOptions {
    std::string output;  ///< the trajectory file
};

void run(const Options& options) {
    TerminalObserver observer("nocdyn excite");
    const app::ExciteResult result = app::runExcite(options, observer);
    observer.finish();
    io::writeTextFile(options.output, result.yaml);
    std::cout << result.text << "wrote " << options.output << "\n";
    std::cout.flush();
    if (!std::cout) throw Error("cannot write to standard output");
}

}  // namespace excite_command

void addExciteCommand(CLI::App& app) {
    auto options = std::make_shared<excite_command::Options>();
    CLI::App* command = app.add_subcommand(
        "excite",
        "Design an excitation trajectory for `nocdyn identify`: per pose axis a Fourier series of --harmonics\n"
        "harmonics of --frequency, starting and ending each period at home at rest, scaled to the largest motion\n"
        "for which every joint stays within its range and velocity limit and every actuator within its effort\n"
        "(inverse dynamics with the guessed payload), all with --margin to spare, and the limb Jacobians and the\n"
        "actuation away from singularity (scaled condition numbers at most --max-condition). Among such shapes\n"
        "it minimises the condition number of the column-scaled stacked regressor of the payload parameters\n"
        "(or, with --base, of the robot's base parameters): a seeded random search, then Nelder-Mead (or, with\n"
        "--optimizer gradient, a descent on the exact gradient), bounded by\n"
        "--evaluations. Prints the condition number reached next to the paper's trajectories 1 and 2 (moved to\n"
        "the robot's home) and each one's use of the limits (percent of the allowed value), and writes the\n"
        "trajectory file (YAML, usable as --trajectory). A two-DOF robot (motion: translation) moves on x, y\n"
        "only (theta stays at home) and its payload is a point mass at the tool point (its mass the one unknown).");
    addRobotOption(*command, options->robot);
    auto* output = command->add_option("--output,-o", options->output, "Trajectory YAML file to write (required)");
    auto* old_output = addOldSpelling(*command, "--out", output, options->output);
    command
        ->add_option("--payload-guess", options->payload_guess,
                     "Guessed payload: MASS [kg] COM_X COM_Y [m, platform frame] INERTIA [kg m^2, about its c.o.m.]; "
                     "the actuators must carry it within their effort (a two-DOF robot's: MASS 0 0 0, a point mass)")
        ->expected(4)
        ->check(within(app::kPayloadGuessRange));
    command->add_flag_callback(
        "--base", [options] { options->parameters = ExcitedParameters::base; },
        "Design for the robot's base parameters (calibration without payload; see nocdyn regressor)");
    command->add_flag("--friction", options->friction,
                      "With the payload: also the actuated joints' damping and Coulomb friction (identify --friction)");
    command->add_option("--duration", options->duration, "Duration [s]: a whole number of base periods")
        ->check(within(app::kExciteDurationRange))
        ->capture_default_str();
    auto* base_frequency = command->add_option("--base-frequency", options->base_frequency, "Base frequency f0 [Hz]")
                               ->check(within(app::kExciteFrequencyRange))
                               ->capture_default_str();
    addOldSpelling(*command, "--frequency", base_frequency, options->base_frequency);
    command->add_option("--harmonics", options->harmonics, "Harmonics per axis (k f0, k = 1..H)")
        ->check(CLI::Range(3, 20))
        ->capture_default_str();
    command
        ->add_option("--margin", options->margin,
                     "Fraction of each range (from home), velocity and effort limit kept free")
        ->check(within(app::kExciteMarginRange))
        ->capture_default_str();
    command
        ->add_option("--max-condition", options->max_condition,
                     "Largest scaled condition number of the limb Jacobians and the actuation map")
        ->check(within(app::kMaxConditionRange))
        ->capture_default_str();
    command->add_option("--evaluations", options->evaluations, "Objective evaluations in all")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    auto* random_shapes = command
                              ->add_option("--random-shapes", options->random_shapes,
                                           "Random shapes tried before Nelder-Mead (at most --evaluations)")
                              ->check(CLI::Range(1, 1000000))
                              ->capture_default_str();
    addOldSpelling(*command, "--random", random_shapes, options->random_shapes);
    command->add_option("--samples", options->samples, "Samples per period in the design (0: 25 per harmonic)")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    command
        ->add_option("--check-samples", options->check_samples,
                     "Samples per period in the final check of the limits and the reported numbers")
        ->check(CLI::Range(24, 1000000))
        ->capture_default_str();
    command->add_option("--seed", options->seed, "Seed of the random search")->capture_default_str();
    addChoiceOption(*command, "--optimizer", options->optimizer,
                    "Refinement after the random search: nelder-mead (derivative-free) or gradient (descent on the "
                    "exact gradient of the log condition number, from the inverse dynamics' derivatives)");
    command->callback([options, output, old_output] {
        // either spelling gives the required output (a parse error, exit 2, without one)
        if (output->count() + old_output->count() == 0) throw CLI::RequiredError("--output");
        excite_command::run(*options);
    });
}

}  // namespace nocdyn::cli
