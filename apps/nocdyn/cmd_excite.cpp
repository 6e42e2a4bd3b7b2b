// nocdyn excite: an excitation trajectory for identification (excitation.hpp), its condition
// number next to the paper's trajectories 1 and 2, written as a trajectory file.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/excitation.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"

namespace nocdyn::cli {

namespace {

struct ExciteOptions {
    std::string robot, output;
    std::vector<double> payload;  ///< mass, com x, com y, inertia about the com
    double duration = 5.0;
    bool base = false;
    ExcitationOptions excitation;
};

std::string number(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

std::string percent(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.1f", 100.0 * v);
    return buffer;
}

std::string useText(const ExcitationLimitUse& use) {
    return "{range: " + percent(use.range) + ", velocity: " + percent(use.velocity) +
           ", effort: " + percent(use.effort) + ", condition: " + percent(use.condition) + ", binding: '" +
           use.binding + "'}";
}

/// One baseline line: the paper's trajectory about home, its condition number and limit use.
std::string baseline(const Model& model, const char* key, const PoseTrajectory& paper,
                     const ExcitationOptions& options) {
    const ExcitationAssessment a =
        assessExcitation(model, aboutHome(model, paper), *paper.duration, options.check_samples, options);
    std::string text = key + std::string(": {condition_number: ") + number(a.condition) +
                       ", limit_use_percent: " + useText(a.use) + "}";
    if (!a.feasible) text += "   # outside the limits: " + a.failure;
    return text + "\n";
}

void run(ExciteOptions options) {
    RobotDescription robot = loadRobotDescriptionOrDefault(options.robot);
    Payload payload;
    if (!options.payload.empty()) {
        if (options.base) throw Error("--payload-guess is for a payload; --base designs for the robot without one");
        payload = Payload{options.payload[0], options.payload[3], Vector2(options.payload[1], options.payload[2])};
        robot = withPayload(robot, payload);
    }
    options.excitation.parameters = options.base ? ExcitedParameters::base : ExcitedParameters::payload;
    const Model model(robot);
    const ExcitationResult result = designExcitation(model, options.duration, options.excitation);
    const ExcitationOptions& o = options.excitation;
    const std::string what =
        options.base ? "the base parameters" : (o.friction ? "the payload and the actuators' friction" : "the payload");
    std::string report = "# " + robot.name + ": excitation for " + what + ", " + std::to_string(o.harmonics) +
                         " harmonics of " + number(o.base_frequency) + " Hz per axis, " + number(options.duration) +
                         " s, margin " + percent(o.margin) + " %, condition numbers of J_j and A at most " +
                         number(o.max_condition) + "\n";
    if (!options.payload.empty()) {
        report += "# payload guess: " + number(payload.mass) + " kg at [" + number(payload.com.x()) + ", " +
                  number(payload.com.y()) + "] m, " + number(payload.inertia) + " kg m^2 about its c.o.m.\n";
    }
    report += "# " + std::to_string(result.evaluations) + " evaluations (" + std::to_string(o.random_shapes) +
              " random shapes, then Nelder-Mead), seed " + std::to_string(o.seed) +
              "; condition number of the column-scaled stacked regressor (as identify reports it)\n";
    report += "designed: {condition_number: " + number(result.assessment.condition) +
              ", limit_use_percent: " + useText(result.assessment.use) + "}\n";
    report += baseline(model, "paper_trajectory_1", paperTrajectory1(), o);
    report += baseline(model, "paper_trajectory_2", paperTrajectory2(), o);

    std::string file = "# Excitation trajectory by `nocdyn excite` for " + what + " of " + robot.name +
                       ": condition number " + number(result.assessment.condition) +
                       "; starts and ends each period at home, at rest.\n";
    for (std::size_t start = 0; start < report.size();) {
        const std::size_t end = report.find('\n', start);
        const std::string line = report.substr(start, end - start);
        file += (line.rfind('#', 0) == 0 ? line : "# " + line) + "\n";
        start = end == std::string::npos ? report.size() : end + 1;
    }
    file += io::trajectoryToYaml(result.trajectory);
    io::writeTextFile(options.output, file);
    std::cout << report << "wrote " << options.output << "\n";
    std::cout.flush();
    if (!std::cout) throw Error("cannot write to standard output");
}

}  // namespace

void addExciteCommand(CLI::App& app) {
    auto options = std::make_shared<ExciteOptions>();
    CLI::App* command = app.add_subcommand(
        "excite",
        "Design an excitation trajectory for `nocdyn identify`: per pose axis a Fourier series of --harmonics\n"
        "harmonics of --frequency, starting and ending each period at home at rest, scaled to the largest motion\n"
        "for which every joint stays within its range and velocity limit and every actuator within its effort\n"
        "(inverse dynamics with the guessed payload), all with --margin to spare, and the limb Jacobians and the\n"
        "actuation away from singularity (scaled condition numbers at most --max-condition). Among such shapes\n"
        "it minimises the condition number of the column-scaled stacked regressor of the payload parameters\n"
        "(or, with --base, of the robot's base parameters): a seeded random search, then Nelder-Mead, bounded by\n"
        "--evaluations. Prints the condition number reached next to the paper's trajectories 1 and 2 (moved to\n"
        "the robot's home) and each one's use of the limits (percent of the allowed value), and writes the\n"
        "trajectory file (YAML, usable as --trajectory).");
    addRobotOption(*command, options->robot);
    auto* output = command->add_option("--output,-o", options->output, "Trajectory YAML file to write (required)");
    auto* old_output = command->add_option("--out", options->output)->group("");  // the old spelling, hidden
    command
        ->add_option("--payload-guess", options->payload,
                     "Guessed payload: MASS [kg] COM_X COM_Y [m, platform frame] INERTIA [kg m^2, about its c.o.m.]; "
                     "the actuators must carry it within their effort")
        ->expected(4)
        ->check(finiteIn(-1e6, 1e6, ""));
    command->add_flag("--base", options->base,
                      "Design for the robot's base parameters (calibration without payload; see nocdyn regressor)");
    command->add_flag("--friction", options->excitation.friction,
                      "With the payload: also the actuated joints' damping and Coulomb friction (identify --friction)");
    command->add_option("--duration", options->duration, "Duration [s]: a whole number of base periods")
        ->check(finiteIn(1e-3, 1e6, "s"))
        ->capture_default_str();
    command->add_option("--frequency", options->excitation.base_frequency, "Base frequency f0 [Hz]")
        ->check(finiteIn(1e-3, 1e3, "Hz"))
        ->capture_default_str();
    command->add_option("--harmonics", options->excitation.harmonics, "Harmonics per axis (k f0, k = 1..H)")
        ->check(CLI::Range(3, 20))
        ->capture_default_str();
    command
        ->add_option("--margin", options->excitation.margin,
                     "Fraction of each range (from home), velocity and effort limit kept free")
        ->check(finiteIn(0.0, 0.9, ""))
        ->capture_default_str();
    command
        ->add_option("--max-condition", options->excitation.max_condition,
                     "Largest scaled condition number of the limb Jacobians and the actuation map")
        ->check(finiteIn(1.0001, 1e8, ""))
        ->capture_default_str();
    command->add_option("--evaluations", options->excitation.evaluations, "Objective evaluations in all")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    command
        ->add_option("--random", options->excitation.random_shapes,
                     "Random shapes tried before Nelder-Mead (at most --evaluations)")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    command
        ->add_option("--samples", options->excitation.samples, "Samples per period in the design (0: 25 per harmonic)")
        ->check(CLI::Range(0, 100000))
        ->capture_default_str();
    command
        ->add_option("--check-samples", options->excitation.check_samples,
                     "Samples per period in the final check of the limits and the reported numbers")
        ->check(CLI::Range(24, 1000000))
        ->capture_default_str();
    command->add_option("--seed", options->excitation.seed, "Seed of the random search")->capture_default_str();
    command->callback([options, output, old_output] {
        // either spelling gives the required output (a parse error, exit 2, without one)
        if (output->count() + old_output->count() == 0) throw CLI::RequiredError("--output");
        run(*options);
    });
}

}  // namespace nocdyn::cli
