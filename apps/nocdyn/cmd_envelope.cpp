// nocdyn envelope: the largest sinusoidal amplitude per axis and frequency within the
// actuator stroke and peak force (prr3/envelope.hpp), as CSV and a figure.
#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>

#include "commands.hpp"
#include "common.hpp"
#include "reproduce_dynamics.hpp"

namespace nocdyn::cli {

namespace {

struct EnvelopeOptions {
    std::string robot, output, figure = "envelope";
    prr3::EnvelopeOptions envelope;
};

void run(const EnvelopeOptions& options) {
    if (options.envelope.max_frequency < options.envelope.min_frequency) {
        throw CLI::ValidationError("--max-frequency", "must be at least --min-frequency");
    }
    const prr3::Model model(loadRobotOrDefault(options.robot, "envelope"));
    const auto points = prr3::operatingEnvelope(model, options.envelope);
    if (!options.output.empty()) writeTable(envelopeTable(points), options.output);
    if (!options.figure.empty()) renderFigure(envelopeFigure(points, model.parameters.name), options.figure);
    if (options.output.empty()) {
        std::printf("axis   f [Hz]   amplitude        limit      limb  peak |tau| [N]  peak |u| [mm]\n");
        for (const auto& p : points) {
            const bool angle = p.axis == prr3::Axis::theta;
            std::printf("%-5s  %7.3f  %10.5g %-4s  %-9s  %d     %8.2f        %7.4f\n", prr3::axisName(p.axis),
                        p.frequency, angle ? p.amplitude * 180.0 / std::numbers::pi : p.amplitude * 1e3,
                        angle ? "deg" : "mm", prr3::limitName(p.limit), p.limb + 1, p.peak_force, p.peak_stroke * 1e3);
        }
    }
}

}  // namespace

void addEnvelopeCommand(CLI::App& app) {
    auto options = std::make_shared<EnvelopeOptions>();
    CLI::App* command = app.add_subcommand(
        "envelope",
        "Operating envelope: for each axis (theta, x, y) and log-spaced frequencies, the largest amplitude A of\n"
        "A sin(2 pi f t) about the reference posture within the stroke, the workspace and the peak force (inverse\n"
        "dynamics over one period), and which limit binds. Writes CSV (axis 0 theta, 1 x, 2 y; limit 0 stroke,\n"
        "1 force, 2 workspace) and a figure (amplitude versus frequency, log axes).");
    addRobotOption(*command, options->robot);
    command->add_option("--output,-o", options->output, "CSV file [default: a table on stdout]");
    command->add_option("--figure", options->figure, "Figure stem (STEM.png, STEM.svg); empty: none")
        ->capture_default_str();
    command->add_option("--min-frequency", options->envelope.min_frequency, "[Hz]")
        ->check(finiteIn(prr3::kEnvelopeMinFrequency, prr3::kEnvelopeMaxFrequency, "Hz"))
        ->capture_default_str();
    command->add_option("--max-frequency", options->envelope.max_frequency, "[Hz], at least --min-frequency")
        ->check(finiteIn(prr3::kEnvelopeMinFrequency, prr3::kEnvelopeMaxFrequency, "Hz"))
        ->capture_default_str();
    command->add_option("--points", options->envelope.frequencies, "Frequencies per axis")
        ->check(CLI::Range(1, prr3::kEnvelopeMaxPoints))
        ->capture_default_str();
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
