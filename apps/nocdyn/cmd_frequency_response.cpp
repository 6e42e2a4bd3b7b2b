// nocdyn frequency-response: the rigid robot linearised at an operating point (exact
// derivatives of the forward dynamics) and its frequency response from the actuator forces
// to the platform acceleration (or to the actuator variables): CSV, Bode figure, -3 dB
// bandwidth of each channel.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "plot.hpp"

namespace nocdyn::cli {

namespace {

struct FrequencyResponseOptions {
    std::string robot, output, figure, summary;
    std::vector<double> pose, rate;
    std::string output_kind = "acceleration";
    double f_min = 1.0, f_max = 1000.0;
    int points = 200;
};

const char* const kPoseNames[3] = {"theta", "x", "y"};

void run(const FrequencyResponseOptions& options) {
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    Data data(model);
    const Pose p = options.pose.empty() ? model.home : Pose(options.pose[0], options.pose[1], options.pose[2]);
    const Twist dp = options.rate.empty() ? Twist::Zero() : Twist(options.rate[0], options.rate[1], options.rate[2]);
    // the operating point: the forces that hold the state without acceleration
    if (const Status status = inverseDynamics(model, data, p, dp, Twist::Zero()); !status) {
        throw Error("operating point: " + describe(status, model));
    }
    const ActuatorVector tau = data.tau;
    const LinearOutput kind =
        options.output_kind == "actuators" ? LinearOutput::actuator_variables : LinearOutput::platform_acceleration;
    StateSpace system;
    if (const Status status = linearize(model, data, p, dp, tau, kind, system); !status) {
        throw Error("operating point: " + describe(status, model));
    }
    const FrequencyResponse r = frequencyResponse(system, logGrid(options.f_min, options.f_max, options.points));
    const auto outputName = [&](int o) {
        return kind == LinearOutput::platform_acceleration ? std::string("dd") + kPoseNames[o]
                                                           : "u" + std::to_string(o + 1);
    };
    io::Table table;
    table.columns.push_back("f");
    for (int o = 0; o < r.outputs; ++o) {
        for (int i = 0; i < r.inputs; ++i) {
            const std::string channel = outputName(o) + "_tau" + std::to_string(i + 1);
            table.columns.push_back(channel + "_db");
            table.columns.push_back(channel + "_deg");
        }
    }
    for (std::size_t k = 0; k < r.frequency.size(); ++k) {
        std::vector<double> row{r.frequency[k]};
        for (Eigen::Index c = 0; c < r.magnitude_db.cols(); ++c) {
            row.push_back(r.magnitude_db(static_cast<Eigen::Index>(k), c));
            row.push_back(r.phase_deg(static_cast<Eigen::Index>(k), c));
        }
        table.rows.push_back(row);
    }
    writeTable(table, options.output);

    std::string text =
        "# frequency response of " + model.description.name + " from the actuator forces to " +
        (kind == LinearOutput::platform_acceleration ? "the platform acceleration" : "the actuator variables") +
        " (rigid model)\n";
    char line[200];
    std::snprintf(line, sizeof line, "# operating point p = [%.6g, %.6g, %.6g], dp = [%.6g, %.6g, %.6g]\n", p(0), p(1),
                  p(2), dp(0), dp(1), dp(2));
    text += line;
    text += "# channel  |H| at f_min [dB]  |H| at f_max [dB]  -3 dB bandwidth [Hz]\n";
    for (int o = 0; o < r.outputs; ++o) {
        for (int i = 0; i < r.inputs; ++i) {
            const Eigen::Index c = o * r.inputs + i;
            const double bw = bandwidth3dB(r, o, i);
            std::snprintf(line, sizeof line, "%s/tau%d  %.4f  %.4f  %s\n", outputName(o).c_str(), i + 1,
                          r.magnitude_db(0, c), r.magnitude_db(r.magnitude_db.rows() - 1, c),
                          std::isnan(bw) ? "beyond the grid" : std::to_string(bw).c_str());
            text += line;
        }
    }
    if (!options.summary.empty()) {
        io::writeTextFile(options.summary, text);
    } else if (!options.output.empty()) {
        std::cout << text;
        std::cout.flush();
        if (!std::cout) throw Error("cannot write to standard output");
    }

    if (!options.figure.empty()) {
        report::Figure figure;
        figure.title = "Frequency response of " + report::literalText(model.description.name);
        report::PlotPanel magnitude{"", "frequency [Hz]", "magnitude [dB]", {}, true, false, false};
        report::PlotPanel phase{"", "frequency [Hz]", "phase [deg]", {}, true, false, false};
        for (int o = 0; o < r.outputs; ++o) {
            for (int i = 0; i < r.inputs; ++i) {
                const Eigen::Index c = o * r.inputs + i;
                report::PlotSeries m{
                    report::literalText(outputName(o) + "/tau" + std::to_string(i + 1)), r.frequency, {}};
                report::PlotSeries ph = m;
                for (std::size_t k = 0; k < r.frequency.size(); ++k) {
                    m.y.push_back(r.magnitude_db(static_cast<Eigen::Index>(k), c));
                    ph.y.push_back(r.phase_deg(static_cast<Eigen::Index>(k), c));
                }
                magnitude.series.push_back(m);
                phase.series.push_back(ph);
            }
        }
        figure.panels = {magnitude, phase};
        report::renderFigure(figure, options.figure);
    }
}

}  // namespace

void addFrequencyResponseCommand(CLI::App& app) {
    auto options = std::make_shared<FrequencyResponseOptions>();
    CLI::App* command = app.add_subcommand(
        "frequency-response",
        "The rigid robot linearised at an operating point (pose, rate; the forces that hold it) by the exact\n"
        "derivatives of the forward dynamics, and its frequency response H(j w) = C (j w I - A)^-1 B + D from\n"
        "each actuator force to each platform acceleration (or actuator variable): a CSV of magnitude [dB] and\n"
        "phase [deg] per channel, a summary with each channel's -3 dB bandwidth, and a Bode figure.\n"
        "Joint and drive compliance are not modelled. Example:\n"
        "  nocdyn frequency-response --f-min 1 --f-max 1000 --points 100 -o plant.csv --figure plant");
    addRobotOption(*command, options->robot);
    command->add_option("--pose", options->pose, "Operating pose THETA X Y [rad, m, m] (default: home)")->expected(3);
    command->add_option("--rate", options->rate, "Operating pose rate [rad/s, m/s, m/s] (default: at rest)")
        ->expected(3);
    command->add_option("--output-kind", options->output_kind, "What the output is")
        ->check(CLI::IsMember({"acceleration", "actuators"}))
        ->capture_default_str();
    command->add_option("--f-min", options->f_min, "Lowest frequency [Hz]")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    command->add_option("--f-max", options->f_max, "Highest frequency [Hz]")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    command->add_option("--points", options->points, "Frequencies, log-spaced")
        ->check(CLI::Range(2, 100000))
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV file to write [default: stdout]")->check(nonEmptyPath());
    command->add_option("--summary", options->summary, "Summary text file [default: stdout when -o is given]")
        ->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Bode figure: writes STEM.png and STEM.svg (gnuplot)")
        ->check(nonEmptyPath());
    command->callback([options] {
        if (!(options->f_max > options->f_min)) throw Error("--f-max must be above --f-min");
        run(*options);
    });
}

}  // namespace nocdyn::cli
