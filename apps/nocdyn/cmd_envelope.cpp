// nocdyn envelope: binds app::EnvelopeOptions and renders the envelope as a table on stdout (then
// the third bound's summary line), CSV and a figure.
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include "app/envelope.hpp"
#include "app/outputs.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace envelope_command {

struct Options : app::EnvelopeOptions {
    std::string output, figure;  ///< no figure unless asked for
};

/// "actuator 2 (limb 2, joint 1)", "limb 3, joint 2 (passive)", "limb 1", or "-".
std::string where(const EnvelopePoint& p) {
    if (p.limb < 0) return "-";
    std::string s;
    if (p.actuator >= 0) s = "actuator " + std::to_string(p.actuator + 1) + " (";
    s += "limb " + std::to_string(p.limb + 1);
    if (p.joint >= 0) s += ", joint " + std::to_string(p.joint + 1);
    if (p.actuator >= 0)
        s += ")";
    else if (p.joint >= 0)
        s += " (passive)";
    return s;
}

void run(const Options& options) {
    if (options.max_frequency < options.min_frequency) {
        throw CLI::ValidationError("--max-frequency", "must be at least --min-frequency");
    }
    TerminalObserver terminal("nocdyn envelope");
    const app::EnvelopeResult result = app::runEnvelope(options, quiet() ? app::silent() : terminal);
    terminal.finish();
    if (!options.output.empty()) writeTable(result.table, options.output);
    if (!options.figure.empty()) app::writeEnvelopeFigure(result, options.figure);
    // the table is the answer when no file is named; the summary line is left out when quiet
    if (options.output.empty() && !result.spatial_points.empty()) {
        std::fputs(app::spatialEnvelopeText(result).c_str(), stdout);
    } else if (options.output.empty()) {
        std::printf("axis   f [Hz]    amplitude        limit      peak |tau|/effort  where\n");
        for (const auto& p : result.points) {
            const bool angle = p.axis == EnvelopeAxis::theta;
            std::printf("%-5s  %8.3f  %10.5g %-4s  %-9s  %8.3f           %s\n", axisName(p.axis), p.frequency,
                        angle ? p.amplitude * 180.0 / std::numbers::pi : p.amplitude * 1e3, angle ? "deg" : "mm",
                        limitName(p.limit), p.peak_effort_ratio, where(p).c_str());
        }
    }
    if (!quiet()) std::printf("%s\n", result.summary.c_str());
}

}  // namespace envelope_command

void addEnvelopeCommand(CLI::App& app) {
    auto options = std::make_shared<envelope_command::Options>();
    CLI::App* command = app.add_subcommand(
        "envelope",
        "Operating envelope of any robot: for each axis (x, y, theta; x, y of a two-DOF robot; x, y, z, roll,\n"
        "pitch, yaw of a spatial robot, x, y, z for motion translation) and log-spaced\n"
        "frequencies, the largest amplitude A of A sin(2 pi f t) about the home posture within every joint's\n"
        "range and velocity limits,\n"
        "every actuator's effort (inverse dynamics over one period, gravity and friction included) and the\n"
        "workspace (reach, limb and actuation singularities), and which limit binds, named with its actuator.\n"
        "The band's third bound: when the robot file declares compliance, the lumped model at home with its\n"
        "modal damping (damping_ratio, 0.02 by default): per axis, at and above the lowest frequency where the\n"
        "dynamic amplification leaves [1/A, A] (--amplification) the limit is resonance (the summary line names\n"
        "each axis' band end and the first natural frequency, in Hz). With elastic links, where the lumped\n"
        "model does not hold at home (its f_1 more than 5 % from the elastodynamic one), the elastodynamic\n"
        "model's modes and f_1 instead, named in the summary.\n"
        "Writes CSV (axis x, y or theta; limit range, velocity, effort, workspace, resonance, or none up to\n"
        "the search bound; limb, joint, actuator 1-based, 0 when not applicable; peak_effort_ratio =\n"
        "max |tau|/effort at that amplitude; first_natural_frequency [Hz] when known) and, with --figure, a\n"
        "figure (amplitude versus frequency, log axes, the first natural frequency as a vertical line; a spatial\n"
        "robot's binding limits as markers). A spatial robot has no resonance bound (--amplification is refused).");
    addRobotOption(*command, options->robot);
    command->add_option("--output,-o", options->output, "CSV file [default: a table on stdout]")->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Figure stem (STEM.png, STEM.svg) [default: none]");
    command->add_option("--min-frequency", options->min_frequency, "[Hz]")
        ->check(within(app::kEnvelopeFrequencyRange))
        ->capture_default_str();
    command->add_option("--max-frequency", options->max_frequency, "[Hz], at least --min-frequency")
        ->check(within(app::kEnvelopeFrequencyRange))
        ->capture_default_str();
    command->add_option("--points", options->points, "Frequencies per axis")
        ->check(CLI::Range(1, kEnvelopeMaxPoints))
        ->capture_default_str();
    command
        ->add_option("--samples-per-period", options->samples_per_period,
                     "Samples of each period the limits are checked on")
        ->check(within(app::kSamplesPerPeriodRange))
        ->capture_default_str();
    command
        ->add_option("--relative-tolerance", options->relative_tolerance,
                     "The amplitude's bisection stops at (hi - lo) <= tolerance * hi")
        ->check(within(app::kEnvelopeToleranceRange))
        ->capture_default_str();
    command
        ->add_option("--amplification", options->amplification,
                     "The band's third bound: the largest dynamic amplification of an axis accepted (the lumped\n"
                     "compliant model's motion along the axis per unit of the rigid motion commanded); at and above\n"
                     "the lowest frequency where it leaves [1/A, A] the limit is resonance")
        ->check(within(app::kAmplificationRange))
        ->capture_default_str();
    command->callback([options] { envelope_command::run(*options); });
}

}  // namespace nocdyn::cli
