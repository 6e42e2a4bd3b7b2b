// nocdyn frequency-response: binds app::FrequencyResponseOptions and writes the table (CSV),
// its summary and the Bode figure.
#include <memory>

#include "app/frequency_response.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"
#include "nocdyn/io/csv.hpp"
#include "render/plot.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace frequency_response_command {

struct Options : app::FrequencyResponseOptions {
    std::string output, figure, summary;
};

io::Table toTable(const app::FrequencyResponseResult& r) {
    io::Table table{r.columns, {}};
    for (Eigen::Index k = 0; k < r.table.rows(); ++k) {
        const Eigen::VectorXd row = r.table.row(k);
        table.rows.emplace_back(row.data(), row.data() + row.size());
    }
    return table;
}

void run(const Options& options) {
    TerminalObserver observer("nocdyn frequency-response");
    app::FrequencyResponseResult result;
    result = app::runFrequencyResponse(options, observer);
    writeTable(toTable(result), options.output);
    // the summary to --summary, or to stdout when the table went to a file (--output)
    if (!options.summary.empty()) {
        io::writeTextFile(options.summary, result.summary);
    } else if (!options.output.empty()) {
        printText(result.summary);
    }
    if (!options.figure.empty()) render::renderFigure(app::bodeFigure(result), options.figure);
}

}  // namespace frequency_response_command

void addFrequencyResponseCommand(CLI::App& app) {
    auto options = std::make_shared<frequency_response_command::Options>();
    CLI::App* command = app.add_subcommand(
        "frequency-response",
        "The rigid robot linearised at an operating point (pose, rate; the forces that hold it) by the exact\n"
        "derivatives of the forward dynamics, and its frequency response H(j w) = C (j w I - A)^-1 B + D from\n"
        "each actuator force to each platform acceleration (or actuator variable): a CSV of magnitude [dB] and\n"
        "phase [deg] per channel (axes x, y, theta), a summary with each channel's -3 dB bandwidth, and a Bode\n"
        "figure. When the robot file declares compliance (joint or drive stiffness, elastic links) the plant is\n"
        "the lumped compliant model (massless springs, rigid bodies: the model of `nocdyn pose`'s natural\n"
        "frequencies) from each drive's commanded position uc (a drive with a stiffness: its servo's set point)\n"
        "or force tau (stiffness 0) to the platform acceleration; --compliance rigid forces the rigid model.\n"
        "The shake table's closed loop, on the same plant (the lumped one: the drives' set points follow the\n"
        "forces' rigid motion), with each axis' usable band (|H| within [1/A, A], --amplification): --closed-loop,\n"
        "e.g.\n"
        "  nocdyn frequency-response --closed-loop --payload-mass 5 --min-frequency 0.1 --max-frequency 4000 -o "
        "loop.csv\n"
        "Example: nocdyn frequency-response --min-frequency 1 --max-frequency 1000 --points 100 -o plant.csv --figure "
        "plant");
    addRobotOption(*command, options->robot);
    command
        ->add_option("--pose", options->pose,
                     "Operating pose X Y THETA [m, m, rad], X Y of a two-DOF robot (default: home)")
        ->expected(2, 3)
        ->check(within(app::kLengthRange));
    command
        ->add_option("--rate", options->rate,
                     "Operating pose rate DX DY DTHETA [m/s, m/s, rad/s], DX DY of a two-DOF robot (default: at rest)")
        ->expected(2, 3);
    addChoiceOption(*command, "--output-kind", options->output_kind, "What the output is");
    addChoiceOption(*command, "--compliance", options->compliance,
                    "The plant's model: auto (lumped when the robot file declares compliance, else rigid), rigid,\n"
                    "or lumped (inputs: commanded drive positions uc [m or rad], forces tau for stiffness-0 drives;\n"
                    "with --closed-loop the loop's plant)");
    const CLI::Validator frequency = within(app::kResponseFrequencyRange);
    auto* min_frequency = command->add_option("--min-frequency", options->min_frequency, "Lowest frequency [Hz]")
                              ->check(frequency)
                              ->capture_default_str();
    auto* max_frequency = command->add_option("--max-frequency", options->max_frequency, "Highest frequency [Hz]")
                              ->check(frequency)
                              ->capture_default_str();
    addOldSpelling(*command, "--f-min", min_frequency, options->min_frequency);
    addOldSpelling(*command, "--f-max", max_frequency, options->max_frequency);
    command->add_option("--points", options->points, "Frequencies, log-spaced")
        ->check(CLI::Range(app::kMinPoints, app::kMaxPoints))
        ->capture_default_str();
    command->add_flag("--closed-loop", options->closed_loop,
                      "The shake-table loop instead (encoders, accelerometers, Kalman estimator, model feed-forward,\n"
                      "pose feedback; discrete at the controller's tick, forces held) linearised at rest: from the\n"
                      "reference to the achieved platform acceleration per axis, and the loop transfer");
    auto* payload_mass =
        command
            ->add_option("--payload-mass", options->payload_mass,
                         "A point mass at C on the plant [kg]; with --closed-loop, one the controller's model does not "
                         "carry")
            ->check(within(app::kPayloadMassRange))
            ->capture_default_str();
    addOldSpelling(*command, "--payload", payload_mass, options->payload_mass);
    command
        ->add_option("--controller-rate", options->controller_rate,
                     "With --closed-loop: controller ticks [Hz] (as shake's --rate)")
        ->check(within(app::kShakeRateRange))
        ->capture_default_str();
    command
        ->add_option("--natural-frequency", options->natural_frequency,
                     "With --closed-loop: f_n of the pose feedback [Hz] (as shake's); a loop it makes unstable is "
                     "refused")
        ->check(within(app::kShakeNaturalFrequencyRange))
        ->capture_default_str();
    command
        ->add_option("--amplification", options->amplification,
                     "With --closed-loop: the usable band of an axis ends where |achieved/reference| leaves [1/A, A]\n"
                     "(as envelope's --amplification)")
        ->check(within(app::kAmplificationRange))
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV file to write [default: stdout]")->check(nonEmptyPath());
    command->add_option("--summary", options->summary, "Summary text file [default: stdout when -o is given]")
        ->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Bode figure: writes STEM.png and STEM.svg (gnuplot)")
        ->check(nonEmptyPath());
    command->callback([options] { frequency_response_command::run(*options); });
}

}  // namespace nocdyn::cli
