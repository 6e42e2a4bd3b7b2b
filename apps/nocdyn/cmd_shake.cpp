// nocdyn shake: play a ground-motion record (PEER AT2) on a robot within its limits and score
// the reproduction (shake_replay.hpp).
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "plants.hpp"
#include "shake_replay.hpp"

namespace nocdyn::cli {

namespace {

struct ShakeOptions {
    std::string robot, record_x, record_y, record_theta, time_scale = "auto", out = "shake";
    double window = 0.0;
    ShakeSettings settings;
};

/// The record's first `window` seconds (all of it when 0), as accelerations in SI.
std::vector<double> readAxis(const std::string& path, double window, double& dt, bool angular) {
    const io::GroundMotionRecord record = io::readAt2File(path);
    if (dt != 0.0 && record.dt != dt) {
        throw Error(path + ": time step " + std::to_string(record.dt) + " s differs from the other records' " +
                    std::to_string(dt) + " s");
    }
    dt = record.dt;
    std::vector<double> a = record.acceleration;
    if (window > 0.0) a.resize(std::min(a.size(), static_cast<std::size_t>(window / dt) + 1));
    // nothing to replay: every score would be a perfect 0 % error of a motion that never moves
    if (std::all_of(a.begin(), a.end(), [](double v) { return v == 0.0; })) {
        throw Error(path + ": every acceleration" + (window > 0.0 ? " of the window" : std::string()) +
                    " is zero: no ground motion to replay");
    }
    if (angular) {
        for (double& v : a) v /= io::kStandardGravity;  // the file's numbers are rad/s^2
    }
    return a;
}

void run(ShakeOptions options) {
    const RobotDescription robot = loadRobotDescriptionOrDefault(options.robot);
    if (options.time_scale != "auto") {
        std::size_t used = 0;
        double value = 0.0;
        try {
            value = std::stod(options.time_scale, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != options.time_scale.size() || !(value >= 1e-3 && value <= 1e4)) {
            throw Error("--time-scale: expected auto or a number from 0.001 to 10000, got '" + options.time_scale +
                        "'");
        }
        options.settings.fit.time_scale = value;
    }
    GroundRecord record;
    record.ax = readAxis(options.record_x, options.window, record.dt, false);
    if (!options.record_y.empty()) record.ay = readAxis(options.record_y, options.window, record.dt, false);
    if (!options.record_theta.empty()) record.alpha = readAxis(options.record_theta, options.window, record.dt, true);
    const std::size_t n = std::min({record.ax.size(), record.ay.empty() ? record.ax.size() : record.ay.size(),
                                    record.alpha.empty() ? record.ax.size() : record.alpha.size()});
    for (auto* a : {&record.ax, &record.ay, &record.alpha}) {
        if (!a->empty()) a->resize(n);  // records of one event may differ by a few samples
    }
    const ShakeOutcome outcome = runShake(robot, record, options.settings);
    writeShakeOutputs(outcome, Model(robot), options.out, robot.name + ": " + options.record_x);
    printShakeSummary(outcome, std::cout);
    std::cout << "wrote " << options.out << "/shake.csv, shake.json, shake_acceleration.{png,svg}, "
              << "shake_spectrum.{png,svg}\n";
}

}  // namespace

void addShakeCommand(CLI::App& app) {
    auto options = std::make_shared<ShakeOptions>();
    CLI::App* command = app.add_subcommand(
        "shake",
        "Play a ground-motion record (PEER AT2, values in g) on a robot. The record is high-passed (zero-phase\n"
        "Butterworth, order 4 forward and backward, odd-reflection padding), integrated to velocity and\n"
        "displacement, and scaled by similitude: time compressed by L with accelerations kept (displacement / L^2),\n"
        "L the least compression that keeps every actuator within (1 - margin) of its range, velocity and effort\n"
        "(inverse dynamics of the fitted motion), else the amplitude is scaled down. The motion is then tracked by\n"
        "computed torque on the plant carrying a payload the controller does not know, with sensor noise.\n"
        "Writes DIR/shake.csv (t,x,y,theta,ax,ay,alpha,ax_achieved,ay_achieved,alpha_achieved,u1..un,tau1..taun),\n"
        "DIR/shake.json (time_scale, amplitude_scale, metrics: RMS and peak acceleration errors, 5 %-damped\n"
        "pseudo-acceleration spectra) and figures DIR/shake_acceleration.{png,svg}, DIR/shake_spectrum.{png,svg}.");
    addRobotOption(*command, options->robot);
    command->add_option("--record", options->record_x, "AT2 record driving x (values in g)")
        ->required()
        ->check(CLI::ExistingFile);
    command->add_option("--record-y", options->record_y, "AT2 record driving y (values in g), same time step")
        ->check(CLI::ExistingFile);
    command
        ->add_option("--record-theta", options->record_theta,
                     "AT2-format file driving theta, its values in rad/s^2 (not g), same time step")
        ->check(CLI::ExistingFile);
    command
        ->add_option("--time-scale", options->time_scale,
                     "auto (the least time compression L >= 1 that fits) or L (the amplitude is then scaled "
                     "down if the motion does not fit)")
        ->capture_default_str();
    command->add_option("--highpass", options->settings.fit.highpass, "High-pass cutoff in record time [Hz]; 0: none")
        ->check(CLI::Range(0.0, 1e3))
        ->capture_default_str();
    command->add_option("--margin", options->settings.fit.margin, "Share of each actuator limit kept in reserve")
        ->check(CLI::Range(0.0, 0.9))
        ->capture_default_str();
    command->add_option("--window", options->window, "Play only the record's first seconds [s]; 0: all")
        ->check(CLI::Range(0.0, 1e5));
    addPlantOption(*command, options->settings.plant);
    command->add_option("--rate", options->settings.rate, "Controller rate [Hz]")
        ->check(CLI::Range(100.0, 1e6))
        ->capture_default_str();
    command->add_option("--natural-frequency", options->settings.natural_frequency, "f_n of the error dynamics [Hz]")
        ->check(CLI::Range(0.1, 1e4))
        ->capture_default_str();
    command->add_option("--payload-mass", options->settings.payload.mass, "Mass on the plant's platform only [kg]")
        ->check(CLI::Range(0.0, 1e4))
        ->capture_default_str();
    command->add_option("--noise-pose", options->settings.noise_pose, "Std. dev. of the pose noise [m, rad]")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    command->add_option("--noise-rate", options->settings.noise_rate, "Std. dev. of the rate noise [m/s, rad/s]")
        ->check(CLI::Range(0.0, 1e3))
        ->capture_default_str();
    command->add_option("--seed", options->settings.seed, "Noise seed")->capture_default_str();
    command->add_option("--accuracy", options->settings.accuracy, "Simbody plant: integrator accuracy")
        ->check(CLI::Range(1e-14, 1e-3))
        ->capture_default_str();
    command->add_option("--out-dir", options->out, "Output folder")->capture_default_str();
    command->add_option("--out", options->out)->group("");  // the old spelling, hidden
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
