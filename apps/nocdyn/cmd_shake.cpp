// nocdyn shake: binds app::ShakeOptions, prints the replay's summary (one record) or the suite's
// table (several records); the files go to the output module's folder (app/outputs.hpp).
#include <iostream>
#include <memory>
#include <string>

#include "app/shake.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/layouts.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace shake_command {

struct Options : app::ShakeOptions {
    Options() { out_dir = "shake"; }
};

void run(const Options& options) {
    TerminalObserver observer("nocdyn shake");
    app::OutputFolder files(options.out_dir);
    const app::ShakeResult result = app::runShake(options, observer, files);
    observer.finish();
    std::cout << result.text;
    if (result.suite) {
        std::cout << "wrote " << io::terminalText(options.out_dir) << "/summary.md and one folder per record\n";
    } else {
        const char* page = result.animation ? ", shake_animation.html\n" : "\n";
        std::cout << "wrote " << io::terminalText(options.out_dir)
                  << "/shake.csv, shake.json, shake_acceleration.{png,svg}, shake_spectrum.{png,svg}" << page;
    }
}

}  // namespace shake_command

void addShakeCommand(CLI::App& app) {
    auto options = std::make_shared<shake_command::Options>();
    CLI::App* command = app.add_subcommand(
        "shake",
        "Play a ground-motion record (PEER AT2, values in g) on a robot. The record is high-passed (zero-phase\n"
        "Butterworth, order 4 forward and backward, odd-reflection padding), integrated to velocity and\n"
        "displacement, and scaled by similitude: time compressed by L with accelerations kept (displacement / L^2),\n"
        "L the least compression that keeps every actuator within (1 - margin) of its range, velocity and effort\n"
        "(inverse dynamics of the fitted motion), else the amplitude is scaled down. The motion is then played on\n"
        "the plant carrying a payload the controller does not know, measured as a shake table measures it:\n"
        "encoders and platform accelerometers fused by a Kalman estimator, model feed-forward with low-gain pose\n"
        "feedback (--controller table; docs/earthquake-replay.md); optionally the payload identified first and the\n"
        "drive iterated.\n"
        "Writes DIR/shake.csv (" +
            io::columnList(io::TableId::shake) +
            "),\n"
            "DIR/shake.json (time_scale, amplitude_scale, metrics: RMS and peak acceleration errors in percent,\n"
            "rms_error_percent ..., 5 %-damped pseudo-acceleration spectra) and figures "
            "DIR/shake_acceleration.{png,svg},\n"
            "DIR/shake_spectrum.{png,svg}, a six-DOF table's replay in 3-D DIR/shake_animation.html (DIR: --out-dir).\n"
            "The default plant is nocdyn-rk4 (a 40 s record in seconds);\n"
            "--plant simbody replays on the independent Simbody model, about 70 times slower, as a check.");
    addRobotOption(*command, options->robot);
    command
        ->add_option(
            "--record", options->record,
            "AT2 record driving x (--axis; values in g); repeat it, or name a folder (its *.AT2 files), for a suite: "
            "one folder of outputs per record under --out-dir, the records in parallel, one summary table "
            "(DIR/summary.md). Component files of one record (a shared name, each header's azimuth or UP) are "
            "one record: its horizontals drive x and y (a six-DOF table's suite: three components per record, x, y, z)")
        ->required()
        ->check(CLI::ExistingPath);
    addChoiceOption(*command, "--axis", options->axis,
                    "The axis --record drives: x, or y (a two-DOF table's or any robot's; the scores are that axis's)");
    command->add_option("--record-y", options->record_y, "AT2 record driving y (values in g), same time step")
        ->check(CLI::ExistingFile);
    command
        ->add_option("--record-theta", options->record_theta,
                     "AT2-format file driving theta, its values in rad/s^2 (not g), same time step")
        ->check(CLI::ExistingFile);
    command
        ->add_option("--time-scale", options->time_scale_text,
                     "auto (the least time compression L >= 1 that fits) or L (the amplitude is then scaled "
                     "down if the motion does not fit)")
        ->capture_default_str();
    command->add_option("--highpass", options->highpass, "High-pass cutoff in record time [Hz]; 0: none")
        ->check(within(app::kHighpassRange))
        ->capture_default_str();
    command->add_option("--margin", options->margin, "Share of each actuator limit kept in reserve")
        ->check(within(app::kShareRange))
        ->capture_default_str();
    addShakeComponentOptions(*command, *options);
    command->add_option("--window", options->window, "Play only the record's first seconds [s]; 0: all")
        ->check(within(app::kWindowRange));
    addPlantOption(*command, options->plant);
    command
        ->add_option("--rate", options->rate,
                     "Controller rate [Hz] (default: 10000 on a planar table, 1000 on a hexapod)")
        ->check(within(app::kShakeRateRange));
    addChoiceOption(*command, "--controller", options->controller,
                    "table (encoders and platform accelerometers fused by a Kalman filter, model feed-forward, "
                    "low-gain pose feedback, acceleration correction) or pose (computed torque on a noisy pose and "
                    "rate sensor, --noise-pose, --noise-rate)");
    command
        ->add_option("--natural-frequency", options->natural_frequency,
                     "f_n of the pose feedback [Hz] (default: table 6, or 2 with --identify-payload; pose 30)")
        ->check(within(app::kShakeNaturalFrequencyRange));
    command
        ->add_option("--acceleration-gain", options->acceleration_gain,
                     "table: gain g per tick of the acceleration correction (bandwidth about g rate / 2 pi)")
        ->check(within(app::kShareRange))
        ->capture_default_str();
    auto* noise_u =
        command->add_option("--noise-u", options->noise_u, "table: std. dev. of each actuator encoder [m or rad]")
            ->check(within(app::kEncoderNoiseRange))
            ->capture_default_str();
    addOldSpelling(*command, "--encoder-noise", noise_u, options->noise_u);
    command
        ->add_option("--accel-noise-density", options->accel_noise_density,
                     "table: accelerometer noise density [ug/sqrt(Hz)] (ADXL355: 22.5)")
        ->check(within(app::kAccelNoiseDensityRange))
        ->capture_default_str();
    command
        ->add_option("--accel-bandwidth", options->accel_bandwidth,
                     "table: accelerometer bandwidth, a first-order low-pass [Hz] (ADXL355 at 4 kHz ODR: 1000)")
        ->check(within(app::kAccelBandwidthRange))
        ->capture_default_str();
    command
        ->add_option("--accel-baseline", options->accel_baseline,
                     "table: distance of the two accelerometers that give the angular acceleration [m]")
        ->check(within(app::kAccelBaselineRange))
        ->capture_default_str();
    command->add_flag("--no-accelerometer", options->no_accelerometer,
                      "table: encoders only (no acceleration correction)");
    command
        ->add_option("--amplitude", options->amplitude,
                     "Multiply the record's accelerations by this before the fit (a weak record raised above the "
                     "sensor noise; the output says so)")
        ->check(within(app::kAmplitudeRange))
        ->capture_default_str();
    command->add_flag("--identify-payload", options->identify_payload,
                      "table: identify the payload first (an excitation designed for it, played within the limits, "
                      "then least squares) and replay with it in the controller's model");
    command
        ->add_option("--iterations", options->iterations,
                     "Drive-signal iteration: at most N passes after the first, each correcting the drive by "
                     "--iteration-gain times the last pass's acceleration error; stops when a pass improves the RMS "
                     "error by less than --iteration-tolerance or its drive would leave the limits; the best pass is "
                     "kept (a six-DOF table: x, y, z, a pass's error its worst axis's)")
        ->check(CLI::Range(0, app::kMaxIterations))
        ->capture_default_str();
    addDriveIterationOptions(*command, *options);
    addChoiceOption(*command, "--drive-model", options->drive_model,
                    "Drive-signal iteration: identity (the error itself corrects the drive), or the error through the "
                    "inverse frequency response of the table controller's closed loop linearised at home, by exact "
                    "derivatives (exact) or central differences (difference)");
    command->add_flag("--drive-specimen", options->drive_specimen,
                      "--drive-model exact or difference: the linearised loop's plant carries the specimen as weighed "
                      "(--payload-mass at the platform's origin), which the controller's model does not");
    command
        ->add_option("--excitation-duration", options->excitation_duration,
                     "--identify-payload: length of the excitation [s] (whole periods of its 5 Hz base)")
        ->check(within(app::kExcitationDurationRange))
        ->capture_default_str();
    auto* threads =
        command->add_option("--threads", options->threads, "Suite: records played at once (0: one per core)")
            ->check(CLI::Range(0u, app::kMaxThreads))
            ->capture_default_str();
    addOldSpelling(*command, "--jobs", threads, options->threads);
    command
        ->add_option("--max-rms-percent", options->max_rms_percent,
                     "Pass (a suite's rows, a single replay's verdict) when the RMS error is at most this [%]")
        ->check(within(app::kErrorPercentRange))
        ->capture_default_str();
    command->add_option("--max-peak-percent", options->max_peak_percent, "Pass when |peak error| is at most this [%]")
        ->check(within(app::kErrorPercentRange))
        ->capture_default_str();
    command
        ->add_option("--min-spectrum-percent", options->min_spectrum_percent,
                     "Pass when at least this percentage of the counted periods is within +-10 %")
        ->check(within(app::kPercentRange))
        ->capture_default_str();
    command->add_option("--payload-mass", options->payload_mass, "Mass on the plant's platform only [kg]")
        ->check(within(app::kPayloadMassRange))
        ->capture_default_str();
    command->add_option("--noise-pose", options->noise_pose, "pose: std. dev. of the pose noise [m, rad]")
        ->check(within(app::kNoisePoseRange))
        ->capture_default_str();
    command->add_option("--noise-rate", options->noise_rate, "pose: std. dev. of the rate noise [m/s, rad/s]")
        ->check(within(app::kNoiseRateRange))
        ->capture_default_str();
    command->add_option("--seed", options->seed, "Noise seed")->capture_default_str();
    command->add_option("--accuracy", options->accuracy, "Simbody plant: integrator accuracy")
        ->check(within(app::kAccuracyRange))
        ->capture_default_str();
    auto* out_dir = command->add_option("--out-dir", options->out_dir, "Output folder")->capture_default_str();
    addOldSpelling(*command, "--out", out_dir, options->out_dir);
    command->callback([options] { shake_command::run(*options); });
}

}  // namespace nocdyn::cli
