// nocdyn frequency-response: the rigid robot linearised at an operating point (exact
// derivatives of the forward dynamics) and its frequency response from the actuator forces
// to the platform acceleration (or to the actuator variables): CSV, Bode figure, -3 dB
// bandwidth of each channel. With --closed-loop: the shake-table loop (sim/closed_loop.hpp)
// linearised, from the reference to the achieved platform acceleration per axis, with the loop
// transfer's crossover and phase margin.
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
#include "nocdyn/sim/closed_loop.hpp"
#include "nocdyn/sim/control.hpp"
#include "plot.hpp"

namespace nocdyn::cli {

namespace {

struct FrequencyResponseOptions {
    std::string robot, output, figure, summary;
    std::vector<double> pose, rate;
    std::string output_kind = "acceleration";
    double f_min = 1.0, f_max = 1000.0;
    int points = 200;
    bool closed_loop = false;
    double payload = 0.0, controller_rate = 10000.0, natural_frequency = 6.0;
};

const char* const kPoseNames[3] = {"theta", "x", "y"};

/// The summary to --summary, or to stdout when the table went to a file (--output).
void writeSummary(const FrequencyResponseOptions& options, const std::string& text) {
    if (!options.summary.empty()) {
        io::writeTextFile(options.summary, text);
    } else if (!options.output.empty()) {
        std::cout << text;
        std::cout.flush();
        if (!std::cout) throw Error("cannot write to standard output");
    }
}

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
    writeSummary(options, text);

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

std::string numberOrBeyond(double value) {
    if (std::isnan(value)) return "beyond the grid";
    char text[40];
    std::snprintf(text, sizeof text, "%.4f", value);
    return text;
}

/// The shake-table loop linearised at rest at the pose (see sim/closed_loop.hpp).
void runClosedLoop(const FrequencyResponseOptions& options) {
    const RobotDescription robot = loadRobotDescriptionOrDefault(options.robot);
    const Model model(robot);
    const Model plant_model(withPayload(robot, Payload{options.payload, 0.0, Vector2::Zero()}));
    const Pose p = options.pose.empty() ? model.home : Pose(options.pose[0], options.pose[1], options.pose[2]);
    if (!(options.f_max < 0.5 * options.controller_rate)) {
        throw Error("--f-max must be below half the --controller-rate (the Nyquist frequency)");
    }
    ShakeLoopOptions loop_options;
    loop_options.rate = options.controller_rate;
    loop_options.natural_frequency = options.natural_frequency;
    const ShakeLoopLinearization loop = linearizeShakeLoop(model, plant_model, p, loop_options);
    const ShakeLoopFrequencyResponse r =
        shakeLoopFrequencyResponse(loop, logGrid(options.f_min, options.f_max, options.points));
    io::Table table;
    table.columns.push_back("f");
    for (const char* axis : kPoseNames) {
        for (const char* column : {"_db", "_deg", "_loop_db", "_loop_deg"})
            table.columns.push_back(axis + std::string(column));
    }
    for (std::size_t k = 0; k < r.frequency.size(); ++k) {
        const auto row_index = static_cast<Eigen::Index>(k);
        std::vector<double> row{r.frequency[k]};
        for (int i = 0; i < 3; ++i) {
            row.push_back(r.magnitude_db(row_index, i));
            row.push_back(r.phase_deg(row_index, i));
            row.push_back(r.loop_magnitude_db(row_index, i));
            row.push_back(r.loop_phase_deg(row_index, i));
        }
        table.rows.push_back(row);
    }
    writeTable(table, options.output);

    char line[300];
    std::snprintf(line, sizeof line,
                  "# closed-loop frequency response of %s under the shake-table controller, from the reference to "
                  "the achieved platform acceleration\n# (linearised at rest at p = [%.6g, %.6g, %.6g]; tick %g Hz, "
                  "f_n = %g Hz, payload unknown to the controller %g kg)\n",
                  model.description.name.c_str(), p(0), p(1), p(2), options.controller_rate, options.natural_frequency,
                  options.payload);
    std::string text = line;
    text += "# axis  |H| at f_min [dB]  |H| at f_max [dB]  -3 dB bandwidth [Hz]  crossover [Hz]  phase margin [deg]\n";
    for (int i = 0; i < 3; ++i) {
        const Eigen::Index last = r.magnitude_db.rows() - 1;
        std::snprintf(line, sizeof line, "%s  %.4f  %.4f  %s  %s  %s\n", kPoseNames[i], r.magnitude_db(0, i),
                      r.magnitude_db(last, i), numberOrBeyond(r.bandwidth(i)).c_str(),
                      numberOrBeyond(r.crossover(i)).c_str(), numberOrBeyond(r.phase_margin(i)).c_str());
        text += line;
    }
    writeSummary(options, text);
    if (!options.figure.empty()) {
        report::Figure figure;
        figure.title = "Closed loop of " + report::literalText(model.description.name) + " (shake-table controller)";
        report::PlotPanel magnitude{"", "frequency [Hz]", "magnitude [dB]", {}, true, false, false};
        report::PlotPanel phase{"", "frequency [Hz]", "phase [deg]", {}, true, false, false};
        for (int i = 0; i < 3; ++i) {
            for (const bool open : {false, true}) {
                const Eigen::MatrixXd& m_db = open ? r.loop_magnitude_db : r.magnitude_db;
                const Eigen::MatrixXd& deg = open ? r.loop_phase_deg : r.phase_deg;
                report::PlotSeries m{
                    report::literalText(std::string(open ? "L " : "H ") + kPoseNames[i]), r.frequency, {}};
                report::PlotSeries ph = m;
                for (std::size_t k = 0; k < r.frequency.size(); ++k) {
                    m.y.push_back(m_db(static_cast<Eigen::Index>(k), i));
                    ph.y.push_back(deg(static_cast<Eigen::Index>(k), i));
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
        "Joint and drive compliance are not modelled. The shake table's closed loop: --closed-loop, e.g.\n"
        "  nocdyn frequency-response --closed-loop --payload 5 --f-min 0.1 --f-max 4000 -o loop.csv\n"
        "Example: nocdyn frequency-response --f-min 1 --f-max 1000 --points 100 -o plant.csv --figure plant");
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
    command->add_flag("--closed-loop", options->closed_loop,
                      "The shake-table loop instead (encoders, accelerometers, Kalman estimator, model feed-forward,\n"
                      "pose feedback; discrete at the controller's tick, forces held) linearised at rest: from the\n"
                      "reference to the achieved platform acceleration per axis, and the loop transfer");
    command
        ->add_option("--payload", options->payload,
                     "With --closed-loop: a point mass at C on the plant that the "
                     "controller's model does not carry [kg]")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    command->add_option("--controller-rate", options->controller_rate, "With --closed-loop: controller ticks [Hz]")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    command
        ->add_option("--natural-frequency", options->natural_frequency,
                     "With --closed-loop: f_n of the pose feedback [Hz]")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV file to write [default: stdout]")->check(nonEmptyPath());
    command->add_option("--summary", options->summary, "Summary text file [default: stdout when -o is given]")
        ->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Bode figure: writes STEM.png and STEM.svg (gnuplot)")
        ->check(nonEmptyPath());
    command->callback([options] {
        if (!(options->f_max > options->f_min)) throw Error("--f-max must be above --f-min");
        if (options->closed_loop) {
            if (!options->rate.empty()) throw Error("--closed-loop linearises at rest: --rate does not apply");
            runClosedLoop(*options);
            return;
        }
        run(*options);
    });
}

}  // namespace nocdyn::cli
