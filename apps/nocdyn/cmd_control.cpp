// nocdyn control: closed-loop tracking of a pose trajectory by computed torque or PD in the
// platform coordinates (control.hpp), on the Simbody plant generated from the robot
// file (when built in) or nocdyn's own forward dynamics. Any robot file of either form (the
// short form is the general robot it expands to); none: the paper's prototype.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "plants.hpp"
#include "reproduce_dynamics.hpp"

namespace nocdyn::cli {

namespace {

struct ControlOptions {
    std::string trajectory, robot, output, figure;
    std::optional<double> duration;
    std::string controller = "computed-torque";  ///< "computed-torque" or "pd"
    double natural_frequency = 50.0;             ///< f_n of the error dynamics [Hz]
    std::string plant = defaultPlantName();
    double rate = 10000.0;            ///< controller ticks per second [Hz]
    double payload_mass = 0.0;        ///< [kg], on the plant's platform only (model mismatch)
    double payload_inertia = 0.0;     ///< about the payload's c.o.m. [kg m^2]
    std::vector<double> payload_com;  ///< [x, y] in the platform frame [m]
    double noise_u = 0.0;             ///< encoder noise [m or rad]
    double noise_du = 0.0;            ///< encoder rate noise [m/s or rad/s]
    unsigned seed = 1;
    bool no_saturation = false;
    double noise_pose = 0.0;       ///< [m and rad]
    double noise_rate = 0.0;       ///< [m/s and rad/s]
    double noise_tau = 0.0;        ///< force measurement noise in the log [N or N m]
    std::string log;               ///< the sensors' log t,u1..un,tau1..taun
    std::string measure = "pose";  ///< pose (a pose sensor) or encoders (u, du and the tracker)
};

void checkDuration(double duration, double rate, const std::string& trajectory) {
    if (!(duration <= kMaxSimulatedDuration)) {
        throw Error(trajectory + ": duration " + std::to_string(duration) + " s; control accepts at most " +
                    std::to_string(kMaxSimulatedDuration) + " s (give --duration)");
    }
    if (!(duration * rate <= kMaxSimulatedSamples)) {
        throw Error("duration " + std::to_string(duration) + " s at --rate " + std::to_string(rate) +
                    " Hz gives more than 1e7 ticks, the most control accepts");
    }
}

/// A reference beyond a joint's range or an actuator's effort is a warning on standard error:
/// the closed loop still tries to track it (a reference out of reach is the loop's error).
void warnReferenceBeyondLimits(const Model& model, const PoseTrajectory& trajectory, double duration, double rate) {
    LimitSummary summary;
    try {
        summary = streamInverseDynamics(model, trajectory, sampleGrid(duration, rate), LimitPolicy::record,
                                        [](const InverseDynamicsSample&) {});
    } catch (const Error&) {
        return;
    }
    for (const std::string& violation : summary.limit_violations) {
        std::cerr << "nocdyn: warning: the reference trajectory: " << io::terminalText(violation) << "\n";
    }
}

/// Task-space computed torque or PD on the pose measured from the plant (or through the
/// encoders and the tracker).
void run(const ControlOptions& options) {
    const bool encoders = options.measure == "encoders";
    if (encoders && (options.noise_pose > 0.0 || options.noise_rate > 0.0)) {
        throw Error(
            "--measure encoders measures u and du: use --noise-u and --noise-du, not --noise-pose and "
            "--noise-rate");
    }
    if (options.noise_du > 0.0 && !encoders) {
        throw Error(
            "--noise-du is the encoder-rate noise of --measure encoders; the controller measures the pose: use "
            "--noise-rate (--noise-u is the encoder noise of --log)");
    }
    if (options.noise_u > 0.0 && options.log.empty() && !encoders) {
        throw Error(
            "--noise-u is the encoder noise of --log or of --measure encoders; the controller measures the pose: "
            "use --noise-pose and --noise-rate");
    }
    const RobotDescription robot = loadRobotDescriptionOrDefault(options.robot);
    const Model model(robot);
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    PoseLoopOptions loop;
    loop.rate = options.rate;
    loop.duration = chooseDuration(options.duration, trajectory);
    checkDuration(loop.duration, loop.rate, options.trajectory);
    warnReferenceBeyondLimits(model, trajectory, loop.duration, loop.rate);
    Payload payload;
    payload.mass = options.payload_mass;
    payload.inertia = options.payload_inertia;
    if (options.payload_com.size() == 2) payload.com = Vector2(options.payload_com[0], options.payload_com[1]);
    const std::unique_ptr<RobotPlant> plant = makePlant(options.plant, withPayload(robot, payload));
    PoseController controller(model, options.controller == "pd" ? ControlLaw::pd : ControlLaw::computed_torque,
                              taskCriticallyDamped(options.natural_frequency));
    loop.saturation = !options.no_saturation;
    loop.noise_angle = options.noise_pose;
    loop.noise_position = options.noise_pose;
    loop.noise_rate = options.noise_rate;
    loop.seed = options.seed;
    loop.encoders = encoders;
    loop.noise_u = encoders ? options.noise_u : 0.0;
    loop.noise_du = options.noise_du;
    Progress progress(loop.duration);  // on a terminal only: the Simbody plant runs a few s per 0.2 s
    loop.progress = [&progress](double t) { progress.update(t); };
    const PoseLoopResult result = runPoseLoop(controller, *plant, trajectory, loop);
    progress.finish();
    if (!options.output.empty()) writeTable(io::toTable(result), options.output);
    if (!options.log.empty()) {
        io::writeCsvFile(options.log,
                         io::toTable(sensorLog(result, options.noise_u, options.noise_tau, options.seed + 1)));
    }
    if (!options.figure.empty()) {
        renderFigure(trackingErrorFigure(literalText(trajectory.name) + ": actuator tracking errors", {result}),
                     options.figure);
    }
    std::printf("%s on the %s plant, %s, %s, %g s at %g Hz (f_n = %g Hz)%s\n", result.controller.c_str(),
                result.plant.c_str(), io::terminalText(robot.name).c_str(), io::terminalText(trajectory.name).c_str(),
                loop.duration, loop.rate, options.natural_frequency,
                payload.mass > 0.0 || payload.inertia > 0.0 ? ", payload unknown to the controller" : "");
    std::printf("pose: RMS error x %.4g um, y %.4g um, theta %.4g urad; peak x %.4g um, y %.4g um, theta %.4g urad\n",
                result.pose_rms_error(1) * 1e6, result.pose_rms_error(2) * 1e6, result.pose_rms_error(0) * 1e6,
                result.pose_peak_error(1) * 1e6, result.pose_peak_error(2) * 1e6, result.pose_peak_error(0) * 1e6);
    std::printf("pose, second half: peak x %.4g um, y %.4g um, theta %.4g urad\n", result.pose_late_peak_error(1) * 1e6,
                result.pose_late_peak_error(2) * 1e6, result.pose_late_peak_error(0) * 1e6);
    for (int a = 0; a < model.actuators; ++a) {
        const auto ia = static_cast<std::size_t>(a);
        const LimbModel& limb = model.limb[static_cast<std::size_t>(model.actuator_limb[ia])];
        const bool revolute = limb.type[static_cast<std::size_t>(model.actuator_joint[ia])] == JointType::revolute;
        const double effort = controller.effort()(a);
        char limit[64] = "none";
        if (std::isfinite(effort)) std::snprintf(limit, sizeof limit, "%g %s", effort, revolute ? "N m" : "N");
        std::printf("actuator %d (%s): RMS error %.4g %s, peak error %.4g %s, peak |tau| %.4g %s (effort %s)\n", a + 1,
                    model.limbName(model.actuator_limb[ia]).c_str(), result.rms_error[ia] * 1e6,
                    revolute ? "urad" : "um", result.peak_error[ia] * 1e6, revolute ? "urad" : "um",
                    result.peak_tau[ia], revolute ? "N m" : "N", limit);
    }
    std::printf("saturated ticks: %zu of %zu\n", result.saturated_ticks, result.t.size());
    if (encoders) {
        std::printf(
            "measured through the encoders and the tracker: pose error RMS x %.4g um, y %.4g um, theta %.4g urad; "
            "peak x %.4g um, y %.4g um, theta %.4g urad; at most %d Newton steps per tick\n",
            result.measurement_rms_error(1) * 1e6, result.measurement_rms_error(2) * 1e6,
            result.measurement_rms_error(0) * 1e6, result.measurement_peak_error(1) * 1e6,
            result.measurement_peak_error(2) * 1e6, result.measurement_peak_error(0) * 1e6,
            result.tracker_max_iterations);
    }
}

}  // namespace

void addControlCommand(CLI::App& app) {
    auto options = std::make_shared<ControlOptions>();
    CLI::App* command = app.add_subcommand(
        "control",
        "Closed-loop tracking of a platform trajectory by any robot (either form of robot file; none: the paper's\n"
        "prototype), in the platform coordinates p = [theta, x, y] measured from the plant (or through the encoders,\n"
        "--measure encoders). computed-torque: A_p^T tau = M_p(p) (ddp_d + Kd e' + Kp e) + h_p(p, dp), e = p_d - p,\n"
        "Kp = w^2, Kd = 2w, w = 2 pi f_n; pd: A_p^T tau = M_p(home) (Kp e + Kd e'); tau minimum-norm when redundant.\n"
        "Forces held between ticks, each clipped at its joint's effort. Prints RMS and peak errors.\n"
        "CSV: " +
            io::columnList(io::TableId::closed_loop) +
            ".\n"
            "Example: nocdyn control --trajectory paper1 --payload-mass 0.5 --payload-com 0.012 -0.007 --log log.csv");
    command
        ->add_option("--trajectory", options->trajectory,
                     "paper1, paper2 (eqs. 33-34), a trajectory file (YAML, harmonics) or samples (.csv: t and "
                     "x,y,theta or ax,ay,alpha)")
        ->required();
    addRobotOption(*command, options->robot);
    command->add_option("--controller", options->controller, "computed-torque or pd")
        ->check(CLI::IsMember({"computed-torque", "pd"}))
        ->capture_default_str();
    addPlantOption(*command, options->plant);
    command->add_option("--rate", options->rate, "Controller rate [Hz]")
        ->check(finiteIn(kMinRate, 1e7, "Hz"))
        ->capture_default_str();
    command->add_option("--duration", options->duration, "Seconds [default: the file's duration, else 0.2]")
        ->check(finiteIn(kMinDuration, kMaxSimulatedDuration, "s"));
    command->add_option("--natural-frequency", options->natural_frequency, "f_n of the error dynamics [Hz]")
        ->check(finiteIn(1e-3, 1e4, "Hz"))
        ->capture_default_str();
    command
        ->add_option("--payload-mass", options->payload_mass,
                     "Model mismatch: mass added to the plant's platform only [kg]")
        ->check(finiteIn(0.0, 1e6, "kg"));
    command
        ->add_option("--payload-inertia", options->payload_inertia,
                     "Model mismatch: the payload's inertia about its c.o.m., on the plant's platform only [kg m^2]")
        ->check(finiteIn(0.0, 1e12, "kg m^2"));
    command
        ->add_option("--payload-com", options->payload_com,
                     "The payload's c.o.m. X Y in the platform frame [m] (default 0 0, at C)")
        ->expected(2)
        ->check(finiteIn(-1e3, 1e3, "m"));
    command
        ->add_option("--noise-pose", options->noise_pose,
                     "Std. dev. of the pose measurement noise [m for x, y; rad for theta]")
        ->check(finiteIn(0.0, 1.0, "m"));
    command->add_option("--noise-rate", options->noise_rate, "Std. dev. of the dp/dt measurement noise [m/s, rad/s]")
        ->check(finiteIn(0.0, 1e3, "m/s"));
    command
        ->add_option("--noise-tau", options->noise_tau, "Std. dev. of the force measurement noise in --log [N or N m]")
        ->check(finiteIn(0.0, 1e6, "N"));
    command
        ->add_option("--measure", options->measure,
                     "What the controller measures. pose: the plant's pose and rate (a pose\n"
                     "sensor, + --noise-pose, --noise-rate); encoders: u and du (+ --noise-u, --noise-du) as a robot\n"
                     "without a pose sensor, the pose by the direct-kinematics tracker (the working mode, from the\n"
                     "reference's start) and dp/dt from A_p dp/dt = du (least squares when redundant)")
        ->check(CLI::IsMember({"pose", "encoders"}))
        ->capture_default_str();
    command
        ->add_option("--log", options->log,
                     "The experiment's log as the sensors see it, CSV t,u1..un,tau1..taun "
                     "(u with --noise-u: with --measure encoders the very readings the controller used; tau the "
                     "applied force with --noise-tau, the force sensor's own noise), ready for `nocdyn identify`")
        ->check(nonEmptyPath());
    command
        ->add_option("--noise-u", options->noise_u,
                     "Std. dev. of the encoder noise in --log and, with --measure encoders, of the controller's "
                     "encoders [m or rad]")
        ->check(finiteIn(0.0, 1.0, "m"));
    command
        ->add_option("--noise-du", options->noise_du,
                     "Std. dev. of the encoder-rate noise with --measure encoders [m/s or rad/s]")
        ->check(finiteIn(0.0, 1e3, "m/s"));
    command->add_option("--seed", options->seed, "Noise seed")->capture_default_str();
    command->add_flag("--no-saturation", options->no_saturation, "Do not clip the forces at each joint's effort");
    command->add_option("--output,-o", options->output, "CSV: " + io::columnList(io::TableId::closed_loop) + " (SI)")
        ->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Tracking-error figure: writes STEM.png and STEM.svg")
        ->check(nonEmptyPath());
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
