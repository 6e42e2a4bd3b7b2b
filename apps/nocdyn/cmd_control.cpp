// nocdyn control: closed-loop tracking of a pose trajectory by computed torque or PD, on the
// Simbody plant (when built in) or nocdyn's own forward dynamics.
#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "reproduce_dynamics.hpp"

namespace nocdyn::cli {

namespace {

struct ControlOptions {
    std::string trajectory, robot, output, figure;
    std::optional<double> duration;
    ControlCase c;
    bool no_saturation = false;
};

void run(ControlOptions options) {
    const prr3::Model model(loadRobotOrDefault(options.robot, "control"));
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    options.c.loop.duration = chooseDuration(options.duration, trajectory);
    if (!(options.c.loop.duration <= kMaxSimulatedDuration)) {
        throw Error(options.trajectory + ": duration " + std::to_string(options.c.loop.duration) +
                    " s; control accepts at most " + std::to_string(kMaxSimulatedDuration) + " s (give --duration)");
    }
    if (!(options.c.loop.duration * options.c.loop.rate <= kMaxSimulatedSamples)) {
        throw Error("duration " + std::to_string(options.c.loop.duration) + " s at --rate " +
                    std::to_string(options.c.loop.rate) + " Hz gives more than 1e7 ticks, the most control accepts");
    }
    options.c.loop.peak_force = options.no_saturation ? 0.0 : model.parameters.peak_force;
    const control::ClosedLoopResult result = runControlCase(model, trajectory, options.c);
    if (!options.output.empty()) writeTable(control::toTable(result), options.output);
    if (!options.figure.empty()) {
        renderFigure(trackingErrorFigure(literalText(trajectory.name) + ": actuator tracking errors", {result}),
                     options.figure);
    }
    std::printf(
        "%s on the %s plant, %s, %g s at %g Hz (f_n = %g Hz)%s\n", result.controller.c_str(), result.plant.c_str(),
        trajectory.name.c_str(), options.c.loop.duration, options.c.loop.rate, options.c.natural_frequency,
        options.c.payload_mass > 0.0 || options.c.payload_inertia > 0.0 ? ", payload unknown to the controller" : "");
    for (int j = 0; j < 3; ++j) {
        std::printf("actuator %d: RMS error %.4g um, peak error %.4g um\n", j + 1, result.rms_error(j) * 1e6,
                    result.peak_error(j) * 1e6);
    }
    std::printf("pose: RMS error x %.4g um, y %.4g um, theta %.4g urad; peak x %.4g um, y %.4g um, theta %.4g urad\n",
                result.pose_rms_error(1) * 1e6, result.pose_rms_error(2) * 1e6, result.pose_rms_error(0) * 1e6,
                result.pose_peak_error(1) * 1e6, result.pose_peak_error(2) * 1e6, result.pose_peak_error(0) * 1e6);
    std::printf("saturated ticks: %zu of %zu\n", result.saturated_ticks, result.t.size());
}

}  // namespace

void addControlCommand(CLI::App& app) {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* command = app.add_subcommand(
        "control",
        "Closed-loop tracking of a platform trajectory. computed-torque: tau = I(u)(ddu_d + Kd e' + Kp e) + C(u,du) "
        "du\n"
        "(eq. 20), Kp = w^2, Kd = 2w, w = 2 pi f_n; pd: tau = Kp' e + Kd' e' with the same gains times diag(I) at the\n"
        "reference posture. Forces held between ticks, clipped at the peak force. Prints RMS and peak errors.");
    command->add_option("--trajectory", options->trajectory, "paper1, paper2 (eqs. 33-34) or a trajectory file (YAML)")
        ->required();
    addRobotOption(*command, options->robot);
    command->add_option("--controller", options->c.controller, "computed-torque or pd")
        ->check(CLI::IsMember({"computed-torque", "pd"}))
        ->capture_default_str();
    command->add_option("--plant", options->c.plant, "simbody (the independent model) or nocdyn (our forward dynamics)")
        ->check(CLI::IsMember({"simbody", "nocdyn"}))
        ->capture_default_str();
    command->add_option("--rate", options->c.loop.rate, "Controller rate [Hz]")
        ->check(finiteIn(kMinRate, 1e7, "Hz"))
        ->capture_default_str();
    command->add_option("--duration", options->duration, "Seconds [default: the file's duration, else 0.2]")
        ->check(finiteIn(kMinDuration, kMaxSimulatedDuration, "s"));
    command->add_option("--natural-frequency", options->c.natural_frequency, "f_n of the error dynamics [Hz]")
        ->check(finiteIn(1e-3, 1e4, "Hz"))
        ->capture_default_str();
    command
        ->add_option("--payload-mass", options->c.payload_mass,
                     "Model mismatch: mass added to the plant's platform only [kg]")
        ->check(finiteIn(0.0, 1e6, "kg"));
    command
        ->add_option("--payload-inertia", options->c.payload_inertia,
                     "Model mismatch: inertia about C added to the plant's platform only [kg m^2]")
        ->check(finiteIn(0.0, 1e12, "kg m^2"));
    command->add_option("--noise-u", options->c.loop.noise_u, "Std. dev. of the u measurement noise [m]")
        ->check(finiteIn(0.0, 1.0, "m"));
    command->add_option("--noise-du", options->c.loop.noise_du, "Std. dev. of the du measurement noise [m/s]")
        ->check(finiteIn(0.0, 1e3, "m/s"));
    command->add_option("--seed", options->c.loop.seed, "Noise seed")->capture_default_str();
    command->add_flag("--no-saturation", options->no_saturation, "Do not clip the forces at the peak force");
    command->add_option("--output,-o", options->output,
                        "CSV: t,x,y,theta,x_d,y_d,theta_d,u1..u3,u1_d..u3_d,e1..e3,tau1..tau3 (SI)");
    command->add_option("--figure", options->figure, "Tracking-error figure: writes STEM.png and STEM.svg");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
