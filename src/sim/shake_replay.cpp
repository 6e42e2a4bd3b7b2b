// Playing a ground-motion record on a robot: fit, play, score (see shake_replay.hpp).
#include "nocdyn/sim/shake_replay.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "nocdyn/error.hpp"
#include "nocdyn/sim/closed_loop.hpp"
#include "nocdyn/sim/excitation.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

namespace {

const std::vector<double>& target(const FittedRecord& fit, int axis) {
    return axis == 0 ? fit.alpha : axis == 1 ? fit.ax : fit.ay;
}

/// The fit's options: the high-pass, the time scale asked (if any), the margin.
FitOptions fitOptions(const ShakeReplayOptions& o) {
    FitOptions fit;
    static_cast<FitSettings&>(fit) = o;
    return fit;
}

/// f_n of the feedback: the one asked, else the controller's default.
double naturalFrequency(const ShakeReplayOptions& o) {
    if (o.natural_frequency) return *o.natural_frequency;
    if (o.controller == ShakeController::pose) return kPoseNaturalFrequency;
    return o.identify_payload ? kIdentifiedNaturalFrequency : ShakeLoopOptions{}.natural_frequency;
}

/// The table controller's loop: rate, feedback, sensors.
ShakeLoopOptions tableLoop(const ShakeReplayOptions& o, const std::function<void(double)>& progress) {
    ShakeLoopOptions loop;
    loop.rate = planarRate(o);
    loop.natural_frequency = naturalFrequency(o);
    loop.acceleration_gain = o.acceleration_gain;
    loop.sensors = o;  // the table's sensors as given (TableSensors)
    loop.seed = o.seed;
    loop.progress = progress;
    return loop;
}

/// What one pass keeps of its actuators, tick by tick as the loop runs: the worst limit use and
/// u, tau at the tick nearest each record sample (fit.t).
struct PassActuators {
    LimitUse use;
    std::vector<double> u, tau;  // n per sample
    std::size_t next = 0;        // the next sample of fit.t to capture

    void tick(const Model& model, const std::vector<double>& sample_t, double rate, std::size_t k, double t,
              const ActuatorVector& u_k, const ActuatorVector& tau_k) {
        // worst |u - centre| / half range and |tau| / effort (no margin; du is not recorded)
        accumulateLimitUse(model, t, u_k, nullptr, tau_k, 0.0, use);
        if (k == 0) {
            u.reserve(sample_t.size() * static_cast<std::size_t>(model.actuators));
            tau.reserve(u.capacity());
        }
        const double tick = 1.0 / rate;
        while (next < sample_t.size() && static_cast<std::size_t>(std::lround(sample_t[next] / tick)) <= k) {
            for (int a = 0; a < model.actuators; ++a) {
                u.push_back(u_k(a));
                tau.push_back(tau_k(a));
            }
            ++next;
        }
    }
};

/// Worst |u - centre| / half range and |tau| / effort over the run (no margin; the loop does not
/// record du).
LimitUse runUse(const Model& model, const PoseLoopResult& loop) {
    LimitUse worst;
    for (std::size_t k = 0; k < loop.t.size(); ++k) {
        accumulateLimitUse(model, loop.t[k], loop.u[k], nullptr, loop.tau[k], 0.0, worst);
    }
    return worst;
}

/// The payload on the platform, estimated as a shake table does before the test: the
/// excitation designed for the payload's parameters (excitation.hpp), played by the table
/// controller on the plant, its encoder log and forces through the identification
/// (identification.hpp).
PayloadIdentification identifyTablePayload(const RobotDescription& robot, RobotPlant& plant,
                                           const ShakeReplayOptions& options,
                                           const std::function<void(double)>& progress) {
    const Model model(robot);
    ExcitationOptions excitation;
    excitation.seed = options.seed;
    const ExcitationResult design = designExcitation(model, options.excitation_duration, excitation);
    ShakeLoopOptions loop = tableLoop(options, progress);
    loop.duration = options.excitation_duration;
    loop.seed = options.seed + 1000;  // a run of its own, before the replay's
    const PoseLoopResult run = runShakeLoop(model, plant, design.trajectory, loop);
    IdentificationOptions identification;
    identification.held_forces = true;
    PayloadIdentification out;
    out.estimate =
        identifyPayload(model, reconstructMotion(model, sensorLog(run, 0.0, 0.0), identification), identification);
    out.excitation_use = runUse(model, run);
    out.done = true;
    return out;
}

/// What the passes of one replay share.
struct Bench {
    const Model& model;             ///< the robot, as the controller is scored on it
    const Model& controller_model;  ///< nominal, or carrying the identified payload
    RobotPlant& plant;
    const FittedRecord& fit;
    const ShakeReplayOptions& options;
    const std::function<void(double)>& progress;
    int scored_axis = 1;  ///< x, else the first driven axis
};

/// One pass of a drive (a fitted motion) on the plant; each pass draws its own sensor noise (a
/// new run of the table), so that the iteration corrects the table's repeatable error only. Its
/// actuators go to `actuators` as the loop runs (only t, p and p_d of each tick are kept).
PoseLoopResult playPass(const Bench& b, const PoseTrajectory& drive, EstimatorReport* report, int pass,
                        PassActuators& actuators) {
    const ShakeReplayOptions& o = b.options;
    actuators = PassActuators{};
    if (o.controller == ShakeController::table) {
        ShakeLoopOptions loop = tableLoop(o, b.progress);
        loop.duration = b.fit.t.back();
        loop.seed = o.seed + static_cast<unsigned>(pass);
        loop.keep_actuators = false;
        loop.on_tick = [&](std::size_t k, double t, const ActuatorVector& u, const ActuatorVector& tau) {
            actuators.tick(b.model, b.fit.t, planarRate(o), k, t, u, tau);
        };
        return runShakeLoop(b.controller_model, b.plant, drive, loop, report);
    }
    if (o.identify_payload) throw Error("--identify-payload needs --controller table");
    PoseController controller(b.model, ControlLaw::computed_torque, taskCriticallyDamped(naturalFrequency(o)));
    PoseLoopOptions loop;
    loop.rate = planarRate(o);
    loop.duration = b.fit.t.back();
    // each pass of the drive iteration draws its own noise
    static_cast<PoseSensorNoise&>(loop) =
        poseSensorNoise(o.noise_pose, o.noise_rate, o.seed + static_cast<unsigned>(pass));
    loop.progress = b.progress;
    PoseLoopResult result = runPoseLoop(controller, b.plant, drive, loop);
    for (std::size_t k = 0; k < result.t.size(); ++k)
        actuators.tick(b.model, b.fit.t, planarRate(o), k, result.t[k], result.u[k], result.tau[k]);
    for (auto* v : {&result.u, &result.u_d, &result.tau, &result.u_measured}) std::vector<ActuatorVector>().swap(*v);
    return result;
}

/// A pass's achieved accelerations at fit.t, and its relative RMS error on the scored axis over
/// the samples the loop covered.
double passRms(const Bench& b, const PoseLoopResult& loop, std::array<std::vector<double>, 3>& achieved) {
    const FittedRecord& fit = b.fit;
    achieved = poseAcceleration(loop.p, 1.0 / planarRate(b.options), fit.t, b.options.difference_span);
    const std::size_t n = std::min(fit.t.size(), static_cast<std::size_t>(loop.t.back() / fit.dt) + 1);
    return relativeRmsError(std::span(target(fit, b.scored_axis)).first(n),
                            std::span(achieved[static_cast<std::size_t>(b.scored_axis)]).first(n));
}

/// H^-1 of the closed loop the table knows, at home: the controller's model, the plant's the same
/// or the robot carrying the weighed specimen (the payload, which the controller's model does not
/// carry, or carries as identified). Identity unless a drive model is asked.
DriveInverse driveInverseOf(const Bench& b, const RobotDescription& robot, const RobotDescription& known,
                            const std::array<bool, 3>& driven) {
    const ShakeReplayOptions& o = b.options;
    if (o.iterations == 0 || o.drive_model == DriveModel::identity) return {};
    if (o.controller != ShakeController::table)
        throw Error("--drive-model " + std::string(name(o.drive_model)) + " needs --controller table");
    const Model specimen(o.drive_specimen ? withPayload(robot, Payload{o.payload_mass, 0.0, Vector2::Zero()}) : known);
    const ShakeLoopLinearization linear = linearizeShakeLoop(
        b.controller_model, specimen, b.controller_model.home, tableLoop(o, b.progress),
        o.drive_model == DriveModel::exact ? LoopDerivatives::exact : LoopDerivatives::central_difference);
    // corrected up to the samples' Nyquist frequency, as the identity correction is
    return driveInverse(o.drive_model, linear, b.fit.dt, b.fit.t.size(), 0.5 / b.fit.dt, driven);
}

/// The next pass's drive: the last drive plus the gain times the acceleration error, directly
/// (identity) or through the inverse closed loop.
void nextDrive(const Bench& b, const DriveInverse& inverse, const std::array<bool, 3>& driven,
               const std::array<std::vector<double>, 3>& last_achieved, int pass,
               std::array<std::vector<double>, 3>& drive) {
    const double gain = b.options.iteration_gain;
    std::array<std::vector<double>, 3> error;
    for (int axis = 0; axis < 3; ++axis) {
        const auto ia = static_cast<std::size_t>(axis);
        if (!driven[ia]) continue;
        const std::vector<double>& a = target(b.fit, axis);
        if (b.options.drive_model == DriveModel::identity) {
            addDriveCorrection(drive[ia], a, last_achieved[ia], gain);
            continue;
        }
        error[ia].resize(a.size());
        for (std::size_t i = 0; i < a.size(); ++i) error[ia][i] = a[i] - last_achieved[ia][i];
    }
    if (b.options.drive_model == DriveModel::identity) return;
    if (const Status status = correctDrive(inverse, error, gain, drive); !status) {
        throw Error("drive iteration: pass " + std::to_string(pass) + ": the acceleration error is not finite");
    }
}

/// Drive-signal iteration (time waveform replication) after the first pass: each pass's drive
/// refitted within half the margin, played, kept when its RMS error is the best so far.
void iterateDrive(const Bench& b, const DriveInverse& inverse, ShakeOutcome& out, PassActuators& kept) {
    const ShakeReplayOptions& o = b.options;
    const FittedRecord& fit = b.fit;
    std::array<std::vector<double>, 3> drive = {fit.alpha, fit.ax, fit.ay};
    std::array<std::vector<double>, 3> last_achieved = out.achieved;
    for (int pass = 1; pass <= o.iterations; ++pass) {
        nextDrive(b, inverse, out.driven, last_achieved, pass, drive);
        GroundRecord next;
        next.dt = out.record_dt;
        next.alpha = drive[0];
        next.ax = drive[1];
        next.ay = drive[2];
        const FittedRecord refit = fitRecord(b.model, next, driveFitOptions(fitOptions(o), fit.time_scale));
        if (refit.amplitude_scale < 1.0) {
            out.iteration_stop = driveLeavesLimits(pass);
            break;
        }
        PassActuators actuators;
        PoseLoopResult loop = playPass(b, refit.trajectory, nullptr, pass, actuators);
        std::array<std::vector<double>, 3> achieved;
        const double rms = passRms(b, loop, achieved);
        out.pass_rms.push_back(rms);
        const PassJudgement judged =
            judgePass(pass, rms, out.pass_rms[static_cast<std::size_t>(out.best_pass)], o.iteration_tolerance);
        if (judged.kept) {
            out.best_pass = pass;
            out.loop = std::move(loop);
            out.achieved = achieved;
            kept = std::move(actuators);
        }
        last_achieved = std::move(achieved);
        if (!judged.stop.empty()) {
            out.iteration_stop = judged.stop;
            break;
        }
    }
    if (o.iterations > 0 && out.iteration_stop.empty()) out.iteration_stop = kLastPassAsked;
}

/// The sensors, their noise and resolution, in words.
std::string sensingText(const ShakeReplayOptions& o, const EstimatorReport& estimator, int task_dimension) {
    if (o.controller != ShakeController::table) {
        return text::format("pose sensor: noise %.3g (m, rad); rate sensor: noise %.3g (m/s, rad/s)", o.noise_pose,
                            o.noise_rate);
    }
    const TableSensors& s = o;  // the sensors the table loop takes whole (tableLoop)
    if (task_dimension == 2) {
        // a two-DOF table: the tool point's x, y only, no angular accelerometer pair
        std::string out = text::format(
            "encoders: noise %.3g (m or rad) per actuator (pose noise at home %.3g m, %.3g m); accelerometers: %s",
            s.noise_u, estimator.sigma_q(1), estimator.sigma_q(2), s.accelerometer() ? "" : "none");
        if (s.accelerometer()) {
            out += text::format(
                "noise density %.3g ug/sqrt(Hz) (ADXL355 default 22.5), bandwidth %.4g Hz (first-order), so %.3g "
                "m/s^2 RMS per axis; rates from the estimator",
                s.accel_noise_density, s.accel_bandwidth, estimator.sigma_y(1));
        }
        return out;
    }
    std::string out = text::format(
        "encoders: noise %.3g (m or rad) per actuator (pose noise at home %.3g rad, %.3g m, %.3g m); "
        "accelerometers: %s",
        s.noise_u, estimator.sigma_q(0), estimator.sigma_q(1), estimator.sigma_q(2), s.accelerometer() ? "" : "none");
    if (s.accelerometer()) {
        out += text::format(
            "noise density %.3g ug/sqrt(Hz) (ADXL355 default 22.5), bandwidth %.4g Hz (first-order), "
            "so %.3g m/s^2 RMS per axis; a pair %.3g m apart for alpha (%.3g rad/s^2 RMS); rates from "
            "the estimator",
            s.accel_noise_density, s.accel_bandwidth, estimator.sigma_y(1), s.accel_baseline, estimator.sigma_y(0));
    }
    return out;
}

/// Central differences of the pose coordinate `axis` over the ticks (one-sided at the ends).
std::vector<double> rateOf(const std::vector<Pose>& p, int axis, double tick) {
    std::vector<double> v(p.size(), 0.0);
    if (p.size() < 2) return v;
    for (std::size_t k = 0; k < p.size(); ++k) {
        const std::size_t a = k == 0 ? 0 : k - 1, b = std::min(k + 1, p.size() - 1);
        v[k] = (p[b](axis) - p[a](axis)) / (static_cast<double>(b - a) * tick);
    }
    return v;
}

}  // namespace

double replayBytesPerTick(ShakeController controller) {
    // t, p, p_d, the loop's tick times, and the scores' displacement and rate series of one axis
    const double kept = sizeof(double) + 2.0 * sizeof(Pose) + sizeof(double) + 4.0 * sizeof(double);
    return controller == ShakeController::table ? kept : kept + 4.0 * sizeof(ActuatorVector);
}

void fitReplay(const Model& model, const GroundRecord& record, const ShakeReplayOptions& options, ShakeOutcome& out) {
    if (!(options.amplitude > 0.0 && std::isfinite(options.amplitude))) throw Error("--amplitude must be positive");
    out.amplitude = options.amplitude;
    out.record_dt = record.dt;
    out.drive_model = options.drive_model;
    out.drive_specimen = options.drive_specimen && options.drive_model != DriveModel::identity;
    GroundRecord scaled = record;
    for (auto* a : {&scaled.ax, &scaled.ay, &scaled.alpha}) {
        for (double& v : *a) v *= options.amplitude;
    }
    out.fit = fitRecord(model, scaled, fitOptions(options));
    out.margin = options.margin;
    const FittedRecord& fit = out.fit;
    // the memory the closed loop will hold, refused before it is taken
    const double ticks = std::floor(fit.t.back() * planarRate(options)) + 1.0;
    const double bytes = ticks * replayBytesPerTick(options.controller);
    if (!(bytes <= kMaxReplayBytes)) {
        const double record_seconds = record.dt * static_cast<double>(fit.t.size() - 1);
        throw Error(
            text::format("the replay of this %.6g s record is too long to hold: time scale L = %.4g gives %.6g s "
                         "of replay, %.4g million ticks at %.6g Hz, about %.0f MB (%.3g MB per second of record); "
                         "the limit is %.0f MB per replay: play part of the record (--window) or lower --rate",
                         record_seconds, fit.time_scale, fit.t.back(), ticks / 1e6, planarRate(options), bytes / 1e6,
                         bytes / 1e6 / record_seconds, kMaxReplayBytes / 1e6));
    }
    out.driven = {!fit.alpha.empty(), !fit.ax.empty(), !fit.ay.empty()};
}

void playReplay(const RobotDescription& robot, const ShakeReplayOptions& options, const PlantFactory& make_plant,
                const std::function<void(double)>& progress, ShakeOutcome& out) {
    const Model model(robot);
    const std::unique_ptr<RobotPlant> plant =
        make_plant(withPayload(robot, Payload{options.payload_mass, 0.0, Vector2::Zero()}));
    RobotDescription known = robot;
    if (options.controller == ShakeController::table && options.identify_payload) {
        out.payload = identifyTablePayload(robot, *plant, options, progress);
        const PayloadResult& e = out.payload.estimate;
        known = withPayload(robot, Payload{e.mass, e.inertia, e.com});
    }
    const Model controller_model(known);
    const Bench bench{
        model, controller_model, *plant, out.fit, options, progress, out.driven[1] ? 1 : out.driven[2] ? 2 : 0};
    const auto start = std::chrono::steady_clock::now();
    PassActuators kept;
    out.loop = playPass(bench, out.fit.trajectory, &out.estimator, 0, kept);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.pass_rms.push_back(passRms(bench, out.loop, out.achieved));
    iterateDrive(bench, driveInverseOf(bench, robot, known, out.driven), out, kept);
    out.sensing = sensingText(options, out.estimator, model.task_dimension);
    out.achieved_use = kept.use;
    out.u_at_samples = std::move(kept.u);
    out.tau_at_samples = std::move(kept.tau);
}

void scoreReplay(const Model& model, const ShakeReplayOptions& options, ShakeOutcome& out) {
    const FittedRecord& fit = out.fit;
    const double record_dt = out.record_dt;
    // the record's passband, in the replay's time: [2 f_highpass (or 2 / duration), 0.4 / dt]
    const double record_duration = record_dt * static_cast<double>(fit.t.size() - 1);
    const double f_lo = std::max(2.0 * options.highpass, 2.0 / record_duration);
    const double f_hi = 0.4 / record_dt;
    out.period_min = 1.0 / (fit.time_scale * f_hi);
    out.period_max = 1.0 / (fit.time_scale * f_lo);
    // the samples the loop covered (its last tick is before the record's end)
    const std::size_t n = std::min(fit.t.size(), static_cast<std::size_t>(out.loop.t.back() / fit.dt) + 1);
    const double tick = 1.0 / planarRate(options);
    for (int axis = 0; axis < 3; ++axis) {
        if (!out.driven[static_cast<std::size_t>(axis)]) continue;
        const std::vector<double>& a = target(fit, axis);
        const std::vector<double>& b = out.achieved[static_cast<std::size_t>(axis)];
        ShakeScore& score = out.score[static_cast<std::size_t>(axis)];
        score = scoreShake(std::span(a).first(n), std::span(b).first(n), fit.dt, out.period_min, out.period_max);
        // displacement and velocity over the ticks
        std::vector<double> d_target, d_achieved;
        d_target.reserve(out.loop.t.size());
        d_achieved.reserve(out.loop.t.size());
        for (std::size_t k = 0; k < out.loop.t.size(); ++k) {
            d_target.push_back(out.loop.p_d[k](axis));
            d_achieved.push_back(out.loop.p[k](axis));
        }
        score.displacement_error = relativeRmsError(d_target, d_achieved, model.home(axis));
        score.velocity_error = relativeRmsError(rateOf(out.loop.p_d, axis, tick), rateOf(out.loop.p, axis, tick));
    }
}

ShakeOutcome runShakeReplay(const RobotDescription& robot, const GroundRecord& record,
                            const ShakeReplayOptions& options, const PlantFactory& make_plant,
                            const std::function<void(double)>& progress) {
    const Model model(robot);
    ShakeOutcome out;
    fitReplay(model, record, options, out);
    playReplay(robot, options, make_plant, progress, out);
    scoreReplay(model, options, out);
    return out;
}

}  // namespace nocdyn
