// nocdyn control: closed-loop tracking of a pose trajectory by computed torque or PD, on the
// Simbody plant (when built in) or nocdyn's own forward dynamics. The paper's 3-PRR (short
// form) is controlled in actuator space (control.hpp, on the general model it expands to); any
// other robot file in the platform coordinates (general_control.hpp).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/general_control.hpp"
#include "nocdyn/identification.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "reproduce_dynamics.hpp"
#ifdef NOCDYN_HAS_SIMBODY
#include "simbody_plant.hpp"
#endif

namespace nocdyn::cli {

namespace {

struct ControlOptions {
    std::string trajectory, robot, output, figure;
    std::optional<double> duration;
    ControlCase c;
    bool no_saturation = false;
    // general robot files only
    std::vector<double> payload_com;  ///< [x, y] in the platform frame [m]
    double noise_pose = 0.0;          ///< [m and rad]
    double noise_rate = 0.0;          ///< [m/s and rad/s]
    double noise_tau = 0.0;           ///< force measurement noise in the log [N or N m]
    std::string log;                  ///< the sensors' log t,u1..un,tau1..taun
    std::string measure = "pose";     ///< pose (a pose sensor) or encoders (u, du and the tracker)
};

void checkDuration(const ControlOptions& options, const std::string& trajectory) {
    if (!(options.c.loop.duration <= kMaxSimulatedDuration)) {
        throw Error(trajectory + ": duration " + std::to_string(options.c.loop.duration) +
                    " s; control accepts at most " + std::to_string(kMaxSimulatedDuration) + " s (give --duration)");
    }
    if (!(options.c.loop.duration * options.c.loop.rate <= kMaxSimulatedSamples)) {
        throw Error("duration " + std::to_string(options.c.loop.duration) + " s at --rate " +
                    std::to_string(options.c.loop.rate) + " Hz gives more than 1e7 ticks, the most control accepts");
    }
}

std::unique_ptr<RobotPlant> makeRobotPlant(const std::string& name, const RobotDescription& robot) {
    if (name == "nocdyn") return std::make_unique<SimulatorRobotPlant>(Model(robot));
#ifdef NOCDYN_HAS_SIMBODY
    if (name == "simbody") return std::make_unique<SimbodyMechanismPlant>(robot);
#endif
    throw Error("--plant " + name + ": not built in (use --plant nocdyn)");
}

/// Any robot file: task-space computed torque or PD on the pose measured from the plant.
void runGeneral(ControlOptions options) {
    const bool encoders = options.measure == "encoders";
    if (encoders && (options.noise_pose > 0.0 || options.noise_rate > 0.0)) {
        throw Error(
            "--measure encoders measures u and du: use --noise-u and --noise-du, not --noise-pose and "
            "--noise-rate");
    }
    if (options.c.loop.noise_du > 0.0 && !encoders) {
        throw Error(
            "--noise-du is for the 3-PRR short form; a general robot file measures the pose: use --noise-rate "
            "(--noise-u is the encoder noise of --log)");
    }
    if (options.c.loop.noise_u > 0.0 && options.log.empty() && !encoders) {
        throw Error(
            "--noise-u on a general robot file is the encoder noise of --log (give --log); the controller "
            "measures the pose: use --noise-pose and --noise-rate");
    }
    if (!options.figure.empty())
        throw Error("--figure is for the 3-PRR short form; use --output for a general robot file");
    const RobotDescription robot = loadRobotDescriptionOrDefault(options.robot);
    const Model model(robot);
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    options.c.loop.duration = chooseDuration(options.duration, trajectory);
    checkDuration(options, options.trajectory);
    Payload payload;
    payload.mass = options.c.payload_mass;
    payload.inertia = options.c.payload_inertia;
    if (options.payload_com.size() == 2) payload.com = Vector2(options.payload_com[0], options.payload_com[1]);
    const std::unique_ptr<RobotPlant> plant = makeRobotPlant(options.c.plant, withPayload(robot, payload));
    PoseController controller(model, options.c.controller == "pd" ? ControlLaw::pd : ControlLaw::computed_torque,
                              taskCriticallyDamped(options.c.natural_frequency));
    PoseLoopOptions loop;
    loop.rate = options.c.loop.rate;
    loop.duration = options.c.loop.duration;
    loop.saturation = !options.no_saturation;
    loop.noise_angle = options.noise_pose;
    loop.noise_position = options.noise_pose;
    loop.noise_rate = options.noise_rate;
    loop.seed = options.c.loop.seed;
    loop.encoders = encoders;
    loop.noise_u = encoders ? options.c.loop.noise_u : 0.0;
    loop.noise_du = options.c.loop.noise_du;
    const PoseLoopResult result = runPoseLoop(controller, *plant, trajectory, loop);
    if (!options.output.empty()) writeTable(toTable(result), options.output);
    if (!options.log.empty()) {
        io::writeCsvFile(options.log, toTable(sensorLog(result, options.c.loop.noise_u, options.noise_tau,
                                                        options.c.loop.seed + 1)));
    }
    std::printf("%s on the %s plant, %s, %s, %g s at %g Hz (f_n = %g Hz)%s\n", result.controller.c_str(),
                result.plant.c_str(), robot.name.c_str(), trajectory.name.c_str(), loop.duration, loop.rate,
                options.c.natural_frequency,
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

void run(ControlOptions options) {
    if (!options.robot.empty() && io::isGeneralForm(io::readRobotFileText(options.robot), options.robot)) {
        runGeneral(std::move(options));
        return;
    }
    if (!options.payload_com.empty() || options.noise_pose > 0.0 || options.noise_rate > 0.0 ||
        options.noise_tau > 0.0 || !options.log.empty() || options.measure != "pose") {
        throw Error(
            "--payload-com, --noise-pose, --noise-rate, --noise-tau, --log and --measure are for general robot files "
            "(convert "
            "the short form with `nocdyn convert`); the 3-PRR short form measures u (use --noise-u and --noise-du)");
    }
    const RobotParameters robot = loadRobotOrDefault(options.robot, "control");
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    options.c.loop.duration = chooseDuration(options.duration, trajectory);
    checkDuration(options, options.trajectory);
    options.c.loop.peak_force = options.no_saturation ? 0.0 : robot.peak_force;
    const control::ClosedLoopResult result = runControlCase(robot, trajectory, options.c);
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
        "reference posture. Forces held between ticks, clipped at the peak force. Prints RMS and peak errors.\n"
        "Any other robot file (general form, any number of actuators) is controlled in the platform coordinates\n"
        "p = [theta, x, y], measured from the plant: computed-torque: A_p^T tau = M_p(p) (ddp_d + Kd e' + Kp e) + "
        "h_p(p, dp),\n"
        "pd: A_p^T tau = M_p(home) (Kp e + Kd e'), e = p_d - p, tau minimum-norm when redundant; each force clipped "
        "at\n"
        "its joint's effort. CSV: t,theta_d,x_d,y_d,theta,x,y,e_theta,e_x,e_y,u1..un,u1_d..un_d,tau1..taun.");
    command
        ->add_option("--trajectory", options->trajectory,
                     "paper1, paper2 (eqs. 33-34), a trajectory file (YAML, harmonics) or samples (.csv: t and "
                     "x,y,theta or ax,ay,alpha)")
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
                     "Model mismatch: inertia added to the plant's platform only [kg m^2] (3-PRR: about C; "
                     "general robot file: about the payload's c.o.m.)")
        ->check(finiteIn(0.0, 1e12, "kg m^2"));
    command
        ->add_option("--payload-com", options->payload_com,
                     "General robot file: the payload's c.o.m. X Y in the platform frame [m] (default 0 0, at C)")
        ->expected(2)
        ->check(finiteIn(-1e3, 1e3, "m"));
    command
        ->add_option("--noise-pose", options->noise_pose,
                     "General robot file: std. dev. of the pose measurement noise [m for x, y; rad for theta]")
        ->check(finiteIn(0.0, 1.0, "m"));
    command
        ->add_option("--noise-rate", options->noise_rate,
                     "General robot file: std. dev. of the dp/dt measurement noise [m/s, rad/s]")
        ->check(finiteIn(0.0, 1e3, "m/s"));
    command
        ->add_option("--noise-tau", options->noise_tau,
                     "General robot file: std. dev. of the force measurement noise in --log [N or N m]")
        ->check(finiteIn(0.0, 1e6, "N"));
    command
        ->add_option("--measure", options->measure,
                     "General robot file: what the controller measures. pose: the plant's pose and rate (a pose\n"
                     "sensor, + --noise-pose, --noise-rate); encoders: u and du (+ --noise-u, --noise-du) as a robot\n"
                     "without a pose sensor, the pose by the direct-kinematics tracker (the working mode, from the\n"
                     "reference's start) and dp/dt from A_p dp/dt = du (least squares when redundant)")
        ->check(CLI::IsMember({"pose", "encoders"}))
        ->capture_default_str();
    command->add_option("--log", options->log,
                        "General robot file: the experiment's log as the sensors see it, CSV t,u1..un,tau1..taun "
                        "(u with --noise-u: with --measure encoders the very readings the controller used; tau the "
                        "applied force with --noise-tau, the force sensor's own noise), ready for `nocdyn identify`");
    command
        ->add_option("--noise-u", options->c.loop.noise_u,
                     "Std. dev. of the u measurement noise [m] (general robot file: the encoder noise in --log "
                     "and, with --measure encoders, of the controller's encoders [m or rad])")
        ->check(finiteIn(0.0, 1.0, "m"));
    command
        ->add_option("--noise-du", options->c.loop.noise_du,
                     "Std. dev. of the du measurement noise [m/s] (general robot file: with --measure encoders "
                     "[m/s or rad/s])")
        ->check(finiteIn(0.0, 1e3, "m/s"));
    command->add_option("--seed", options->c.loop.seed, "Noise seed")->capture_default_str();
    command->add_flag("--no-saturation", options->no_saturation,
                      "Do not clip the forces at the peak force (general robot file: at each joint's effort)");
    command->add_option("--output,-o", options->output,
                        "CSV: t,x,y,theta,x_d,y_d,theta_d,u1..u3,u1_d..u3_d,e1..e3,tau1..tau3 (SI)");
    command->add_option("--figure", options->figure, "Tracking-error figure: writes STEM.png and STEM.svg");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
