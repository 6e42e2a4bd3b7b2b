#include "app/control.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "app/control_spatial.hpp"
#include "app/pose_spatial.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/text.hpp"
#include "app/reproduce_dynamics.hpp"

namespace nocdyn::app {

namespace {

void checkDuration(double duration, double rate, const std::string& trajectory) {
    if (!(duration <= kSimulatedDurationRange.hi)) {
        throw Error(trajectory + ": duration " + std::to_string(duration) + " s; control accepts at most " +
                    std::to_string(kSimulatedDurationRange.hi) + " s (give --duration)");
    }
    if (!(duration * rate <= kMaxSimulatedSamples)) {
        throw Error("duration " + std::to_string(duration) + " s at --rate " + std::to_string(rate) +
                    " Hz gives more than 1e7 ticks, the most control accepts");
    }
}

/// A reference beyond a joint's range or an actuator's effort is a warning: the closed loop
/// still tries to track it (a reference out of reach is the loop's error).
void warnReferenceBeyondLimits(const Model& model, const PoseTrajectory& trajectory, double duration, double rate,
                               Observer& observer) {
    LimitSummary summary;
    try {
        summary = streamInverseDynamics(model, trajectory, sampleGrid(duration, rate), LimitPolicy::record,
                                        [](const InverseDynamicsSample&) {});
    } catch (const Error&) {
        return;
    }
    for (const std::string& violation : summary.limit_violations) {
        observer.warning("the reference trajectory: " + violation);
    }
}

/// A two-DOF robot's reference is keyed x, y: a trajectory that moves theta off home is refused.
void refuseTheta(const PoseTrajectory& trajectory, const Model& model, const std::string& source) {
    const bool sampled = trajectory.sampled && trajectory.sampled->theta;
    if (sampled || !trajectory.theta.harmonics.empty() || trajectory.theta.offset != model.home(0)) {
        throw Error(io::terminalText(source) +
                    ": theta: a two-DOF robot (motion: translation) has no theta: its trajectory is keyed x, y");
    }
}

void appendf(std::string& text, const char* format, auto... values) { text += text::format(format, values...); }

std::string report(const ControlOptions& options, const Model& model, const PoseController& controller,
                   const PoseLoopResult& result, const PoseLoopOptions& loop, const std::string& trajectory) {
    std::string text;
    appendf(text, "%s on the %s plant, %s, %s, %g s at %g Hz (f_n = %g Hz)%s\n", result.controller.c_str(),
            result.plant.c_str(), io::terminalText(model.description.name).c_str(),
            io::terminalText(trajectory).c_str(), loop.duration, loop.rate, options.natural_frequency,
            options.payload_mass > 0.0 || options.payload_inertia > 0.0 ? ", payload unknown to the controller" : "");
    if (model.task_dimension == 2) {
        // the pose [x, y] of a two-DOF robot: theta is no coordinate
        appendf(text, "pose: RMS error x %.4g um, y %.4g um; peak x %.4g um, y %.4g um\n",
                result.pose_rms_error(1) * 1e6, result.pose_rms_error(2) * 1e6, result.pose_peak_error(1) * 1e6,
                result.pose_peak_error(2) * 1e6);
        appendf(text, "pose, second half: peak x %.4g um, y %.4g um\n", result.pose_late_peak_error(1) * 1e6,
                result.pose_late_peak_error(2) * 1e6);
    } else {
        appendf(text,
                "pose: RMS error x %.4g um, y %.4g um, theta %.4g urad; peak x %.4g um, y %.4g um, theta %.4g urad\n",
                result.pose_rms_error(1) * 1e6, result.pose_rms_error(2) * 1e6, result.pose_rms_error(0) * 1e6,
                result.pose_peak_error(1) * 1e6, result.pose_peak_error(2) * 1e6, result.pose_peak_error(0) * 1e6);
        appendf(text, "pose, second half: peak x %.4g um, y %.4g um, theta %.4g urad\n",
                result.pose_late_peak_error(1) * 1e6, result.pose_late_peak_error(2) * 1e6,
                result.pose_late_peak_error(0) * 1e6);
    }
    for (int a = 0; a < model.actuators; ++a) {
        const auto ia = static_cast<std::size_t>(a);
        const LimbModel& limb = model.limb[static_cast<std::size_t>(model.actuator_limb[ia])];
        const bool revolute = limb.type[static_cast<std::size_t>(model.actuator_joint[ia])] == JointType::revolute;
        const double effort = controller.effort()(a);
        std::string limit = "none";
        if (std::isfinite(effort)) limit = text::format("%g %s", effort, revolute ? "N m" : "N");
        appendf(text, "actuator %d (%s): RMS error %.4g %s, peak error %.4g %s, peak |tau| %.4g %s (effort %s)\n",
                a + 1, model.limbName(model.actuator_limb[ia]).c_str(), result.rms_error[ia] * 1e6,
                revolute ? "urad" : "um", result.peak_error[ia] * 1e6, revolute ? "urad" : "um", result.peak_tau[ia],
                revolute ? "N m" : "N", limit.c_str());
    }
    appendf(text, "saturated ticks: %zu of %zu\n", result.saturated_ticks, result.t.size());
    if (loop.encoders && model.task_dimension == 2) {
        appendf(text,
                "measured through the encoders and the tracker: pose error RMS x %.4g um, y %.4g um; peak x %.4g um, "
                "y %.4g um; at most %d Newton steps per tick\n",
                result.measurement_rms_error(1) * 1e6, result.measurement_rms_error(2) * 1e6,
                result.measurement_peak_error(1) * 1e6, result.measurement_peak_error(2) * 1e6,
                result.tracker_max_iterations);
    } else if (loop.encoders) {
        appendf(text,
                "measured through the encoders and the tracker: pose error RMS x %.4g um, y %.4g um, theta %.4g "
                "urad; peak x %.4g um, y %.4g um, theta %.4g urad; at most %d Newton steps per tick\n",
                result.measurement_rms_error(1) * 1e6, result.measurement_rms_error(2) * 1e6,
                result.measurement_rms_error(0) * 1e6, result.measurement_peak_error(1) * 1e6,
                result.measurement_peak_error(2) * 1e6, result.measurement_peak_error(0) * 1e6,
                result.tracker_max_iterations);
    }
    return text;
}

}  // namespace

void validate(const ControlOptions& options) {
    if (options.duration) requireIn(*options.duration, kSimulatedDurationRange, "duration");
    requireIn(options.rate, kControllerRateRange, "rate");
    requireIn(options.natural_frequency, kNaturalFrequencyRange, "natural_frequency");
    requireIn(options.payload_mass, kPayloadMassRange, "payload_mass");
    requireIn(options.payload_inertia, kPayloadInertiaRange, "payload_inertia");
    if (!options.payload_com.empty() && options.payload_com.size() != 2) {
        throw OptionError("payload_com", "expected 2 values x, y");
    }
    for (const double v : options.payload_com) requireIn(v, kLengthRange, "payload_com");
    requireIn(options.noise_pose, Range{0.0, 1.0, "m"}, "noise_pose");
    requireIn(options.noise_rate, Range{0.0, 1e3, "m/s"}, "noise_rate");
    requireIn(options.noise_tau, Range{0.0, 1e6, "N"}, "noise_tau");
    requireIn(options.noise_u, Range{0.0, 1.0, "m"}, "noise_u");
    requireIn(options.noise_du, Range{0.0, 1e3, "m/s"}, "noise_du");
    const bool encoders = options.measure == ControlMeasure::encoders;
    if (encoders && (options.noise_pose > 0.0 || options.noise_rate > 0.0)) {
        throw OptionError("measure",
                          "encoders measures u and du: use noise_u and noise_du, not noise_pose and noise_rate");
    }
    if (options.noise_du > 0.0 && !encoders) {
        throw OptionError("noise_du",
                          "the encoder-rate noise of measure encoders; the controller measures the pose: use "
                          "noise_rate (noise_u is the encoder noise of the sensors' log)");
    }
    if (options.noise_u > 0.0 && !options.sensor_log && !encoders) {
        throw OptionError("noise_u",
                          "the encoder noise of the sensors' log or of measure encoders; the controller measures "
                          "the pose: use noise_pose and noise_rate");
    }
}

ControlResult runControl(const ControlOptions& options, Observer& observer) {
    if (isSpatialRobot(options.robot)) return runSpatialControl(options, observer);
    validate(options);
    const bool encoders = options.measure == ControlMeasure::encoders;
    const RobotDescription robot = loadRobot(options.robot);
    PlantKind plant_kind = options.plant;
    if (robot.motion == PlatformMotion::translation && plant_kind == PlantKind::simbody && !options.plant_given)
        plant_kind = PlantKind::nocdyn;  // the default plant of a two-DOF robot
    if (robot.motion == PlatformMotion::translation && plant_kind == PlantKind::simbody) {
        throw OptionError("plant",
                          "the Simbody plant does not take a two-DOF robot (motion: translation) yet (it frees the "
                          "point tool's angle, which has no inertia): give `plant` nocdyn or nocdyn-rk4");
    }
    if (const std::string rigid = rigidPlantWarning(robot, "control"); !rigid.empty()) observer.warning(rigid);
    const Model model(robot);
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    if (model.task_dimension == 2) refuseTheta(trajectory, model, options.trajectory);
    PoseLoopOptions loop;
    loop.rate = options.rate;
    loop.duration = chooseDuration(options.duration, trajectory);
    checkDuration(loop.duration, loop.rate, options.trajectory);
    warnReferenceBeyondLimits(model, trajectory, loop.duration, loop.rate, observer);
    Payload payload;
    payload.mass = options.payload_mass;
    payload.inertia = options.payload_inertia;
    if (options.payload_com.size() == 2) payload.com = Vector2(options.payload_com[0], options.payload_com[1]);
    const std::unique_ptr<RobotPlant> plant = makePlant(plant_kind, withPayload(robot, payload));
    PoseController controller(model, options.controller, taskCriticallyDamped(options.natural_frequency));
    loop.saturation = !options.no_saturation;
    static_cast<PoseSensorNoise&>(loop) = poseSensorNoise(options.noise_pose, options.noise_rate, options.seed);
    loop.encoders = encoders;
    loop.noise_u = encoders ? options.noise_u : 0.0;
    loop.noise_du = options.noise_du;
    Meter meter(observer, loop.duration, "s");  // the Simbody plant runs a few s per 0.2 s
    loop.progress = [&meter](double t) { meter(t); };
    ControlResult out;
    out.loop = runPoseLoop(controller, *plant, trajectory, loop);
    meter.report(loop.duration);
    out.trajectory = trajectory.name;
    out.table = tables::toTable(out.loop, model.task_dimension);
    if (options.sensor_log) {
        out.log = tables::toTable(sensorLog(out.loop, options.noise_u, options.noise_tau, options.seed + 1));
    }
    out.text = report(options, model, controller, out.loop, loop, trajectory.name);
    return out;
}

render::Figure trackingFigure(const ControlResult& result) {
    if (result.loop.t.empty()) throw Error("the tracking figure of a spatial robot is planar for now (--figure)");
    return trackingErrorFigure(render::literalText(result.trajectory) + ": actuator tracking errors", {result.loop});
}

}  // namespace nocdyn::app
