// Playing a ground-motion record on a robot (see shake_replay.hpp).
#include "shake_replay.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "nocdyn/error.hpp"
#include "nocdyn/sim/closed_loop.hpp"
#include "nocdyn/sim/excitation.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/text.hpp"
#include "plants.hpp"
#include "plot.hpp"

namespace nocdyn::report {

/// The El Centro record compiled in (generated from data/elcentro_1940_ns.AT2).
extern const char* const kElCentroAt2;

namespace {

constexpr std::array<const char*, 3> kAxisNames = {"alpha", "ax", "ay"};

const std::vector<double>& target(const FittedRecord& fit, int axis) {
    return axis == 0 ? fit.alpha : axis == 1 ? fit.ax : fit.ay;
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

}  // namespace

namespace {

/// The payload on the platform, estimated as a shake table does before the test: the
/// excitation designed for the payload's parameters (excitation.hpp), played by the table
/// controller on the plant, its encoder log and forces through the identification
/// (identification.hpp).
PayloadIdentification identifyTablePayload(const RobotDescription& robot, RobotPlant& plant,
                                           const ShakeSettings& settings) {
    const Model model(robot);
    ExcitationOptions excitation;
    excitation.seed = settings.table.seed;
    const ExcitationResult design = designExcitation(model, settings.excitation_duration, excitation);
    ShakeLoopOptions loop = settings.table;
    loop.rate = settings.rate;
    loop.duration = settings.excitation_duration;
    loop.seed = settings.table.seed + 1000;  // a run of its own, before the replay's
    const PoseLoopResult run = runShakeLoop(model, plant, design.trajectory, loop);
    IdentificationOptions options;
    options.held_forces = true;
    PayloadIdentification out;
    out.estimate = identifyPayload(model, reconstructMotion(model, sensorLog(run, 0.0, 0.0), options), options);
    out.excitation_use = runUse(model, run);
    out.done = true;
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

double replayBytesPerTick(const std::string& controller) {
    // t, p, p_d, the loop's tick times, and the scores' displacement and rate series of one axis
    const double kept = sizeof(double) + 2.0 * sizeof(Pose) + sizeof(double) + 4.0 * sizeof(double);
    return controller == "table" ? kept : kept + 4.0 * sizeof(ActuatorVector);
}

ShakeOutcome runShake(const RobotDescription& robot, const GroundRecord& record, const ShakeSettings& settings) {
    const Model model(robot);
    ShakeOutcome out;
    if (!(settings.amplitude > 0.0 && std::isfinite(settings.amplitude))) throw Error("--amplitude must be positive");
    out.amplitude = settings.amplitude;
    out.drive_model = settings.drive_model;
    out.drive_specimen = settings.drive_specimen && settings.drive_model != DriveModel::identity;
    GroundRecord scaled = record;
    for (auto* a : {&scaled.ax, &scaled.ay, &scaled.alpha}) {
        for (double& v : *a) v *= settings.amplitude;
    }
    out.fit = fitRecord(model, scaled, settings.fit);
    out.margin = settings.fit.margin;
    const FittedRecord& fit = out.fit;
    {
        // the memory the closed loop will hold, refused before it is taken
        const double ticks = std::floor(fit.t.back() * settings.rate) + 1.0;
        const double bytes = ticks * replayBytesPerTick(settings.controller);
        if (!(bytes <= kMaxReplayBytes)) {
            const double record_seconds = record.dt * static_cast<double>(fit.t.size() - 1);
            std::string text;
            text = text::format(
                "the replay of this %.6g s record is too long to hold: time scale L = %.4g gives %.6g s "
                "of replay, %.4g million ticks at %.6g Hz, about %.0f MB (%.3g MB per second of record); "
                "the limit is %.0f MB per replay: play part of the record (--window) or lower --rate",
                record_seconds, fit.time_scale, fit.t.back(), ticks / 1e6, settings.rate, bytes / 1e6,
                bytes / 1e6 / record_seconds, kMaxReplayBytes / 1e6);
            throw Error(text);
        }
    }
    out.driven = {!fit.alpha.empty(), !fit.ax.empty(), !fit.ay.empty()};
    const std::unique_ptr<RobotPlant> plant =
        makePlant(settings.plant, withPayload(robot, settings.payload), settings.accuracy);
    RobotDescription known = robot;
    if (settings.controller == "table" && settings.identify_payload) {
        out.payload = identifyTablePayload(robot, *plant, settings);
        const PayloadResult& e = out.payload.estimate;
        known = withPayload(robot, Payload{e.mass, e.inertia, e.com});
    }
    const Model controller_model(known);
    // one pass of a drive (a fitted motion) on the plant; each pass draws its own sensor noise
    // (a new run of the table), so that the iteration corrects the table's repeatable error only.
    // Its actuators go to `actuators` as the loop runs (only t, p and p_d of each tick are kept).
    const auto play = [&](const PoseTrajectory& drive, EstimatorReport* report, int pass, PassActuators& actuators) {
        actuators = PassActuators{};
        if (settings.controller == "table") {
            ShakeLoopOptions loop = settings.table;
            loop.rate = settings.rate;
            loop.duration = fit.t.back();
            loop.seed = settings.table.seed + static_cast<unsigned>(pass);
            loop.keep_actuators = false;
            loop.on_tick = [&](std::size_t k, double t, const ActuatorVector& u, const ActuatorVector& tau) {
                actuators.tick(model, fit.t, settings.rate, k, t, u, tau);
            };
            return runShakeLoop(controller_model, *plant, drive, loop, report);
        }
        if (settings.controller != "pose")
            throw Error("--controller " + settings.controller + ": expected table or pose");
        if (settings.identify_payload) throw Error("--identify-payload needs --controller table");
        PoseController controller(model, ControlLaw::computed_torque, taskCriticallyDamped(settings.natural_frequency));
        PoseLoopOptions loop;
        loop.rate = settings.rate;
        loop.duration = fit.t.back();
        loop.noise_angle = settings.noise_pose;
        loop.noise_position = settings.noise_pose;
        loop.noise_rate = settings.noise_rate;
        loop.seed = settings.seed + static_cast<unsigned>(pass);
        loop.progress = settings.table.progress;
        PoseLoopResult result = runPoseLoop(controller, *plant, drive, loop);
        for (std::size_t k = 0; k < result.t.size(); ++k)
            actuators.tick(model, fit.t, settings.rate, k, result.t[k], result.u[k], result.tau[k]);
        for (auto* v : {&result.u, &result.u_d, &result.tau, &result.u_measured})
            std::vector<ActuatorVector>().swap(*v);
        return result;
    };
    const int scored_axis = out.driven[1] ? 1 : out.driven[2] ? 2 : 0;
    const auto passRms = [&](const PoseLoopResult& loop, std::array<std::vector<double>, 3>& achieved) {
        achieved = poseAcceleration(loop.p, 1.0 / settings.rate, fit.t, settings.difference_span);
        const std::size_t n = std::min(fit.t.size(), static_cast<std::size_t>(loop.t.back() / fit.dt) + 1);
        return relativeRmsError(std::span(target(fit, scored_axis)).first(n),
                                std::span(achieved[static_cast<std::size_t>(scored_axis)]).first(n));
    };
    const auto start = std::chrono::steady_clock::now();
    PassActuators kept;
    out.loop = play(fit.trajectory, &out.estimator, 0, kept);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out.pass_rms.push_back(passRms(out.loop, out.achieved));
    // drive-signal iteration (time waveform replication)
    std::array<std::vector<double>, 3> drive = {fit.alpha, fit.ax, fit.ay};
    std::array<std::vector<double>, 3> last_achieved = out.achieved;
    DriveInverse inverse;
    if (settings.iterations > 0 && settings.drive_model != DriveModel::identity) {
        if (settings.controller != "table")
            throw Error("--drive-model " + std::string(name(settings.drive_model)) + " needs --controller table");
        // the closed loop the table knows, at home: the controller's model, the plant's the same or
        // the robot carrying the weighed specimen (the payload, which the controller's model does
        // not carry, or carries as identified)
        ShakeLoopOptions options = settings.table;
        options.rate = settings.rate;
        const Model specimen(settings.drive_specimen ? withPayload(robot, settings.payload) : known);
        const ShakeLoopLinearization linear = linearizeShakeLoop(
            controller_model, specimen, controller_model.home, options,
            settings.drive_model == DriveModel::exact ? LoopDerivatives::exact : LoopDerivatives::central_difference);
        // corrected up to the samples' Nyquist frequency, as the identity correction is
        inverse = driveInverse(settings.drive_model, linear, fit.dt, fit.t.size(), 0.5 / fit.dt, out.driven);
    }
    for (int pass = 1; pass <= settings.iterations; ++pass) {
        GroundRecord next;
        next.dt = record.dt;
        if (settings.drive_model == DriveModel::identity) {
            for (int axis = 0; axis < 3; ++axis) {
                const auto ia = static_cast<std::size_t>(axis);
                if (!out.driven[ia]) continue;
                const std::vector<double>& a = target(fit, axis);
                for (std::size_t i = 0; i < drive[ia].size(); ++i) {
                    drive[ia][i] += settings.iteration_gain * (a[i] - last_achieved[ia][i]);
                }
            }
        } else {
            std::array<std::vector<double>, 3> error;
            for (int axis = 0; axis < 3; ++axis) {
                const auto ia = static_cast<std::size_t>(axis);
                if (!out.driven[ia]) continue;
                const std::vector<double>& a = target(fit, axis);
                error[ia].resize(a.size());
                for (std::size_t i = 0; i < a.size(); ++i) error[ia][i] = a[i] - last_achieved[ia][i];
            }
            if (const Status status = correctDrive(inverse, error, settings.iteration_gain, drive); !status) {
                throw Error("drive iteration: pass " + std::to_string(pass) + ": the acceleration error is not finite");
            }
        }
        next.alpha = drive[0];
        next.ax = drive[1];
        next.ay = drive[2];
        // the drive may use half of the reserve the target keeps (margin): its corrections make up
        // for what the plant does not follow
        FitOptions options = settings.fit;
        options.time_scale = fit.time_scale;
        options.margin = 0.5 * settings.fit.margin;
        options.highpass = 0.0;  // the target is filtered already
        const FittedRecord refit = fitRecord(model, next, options);
        if (refit.amplitude_scale < 1.0) {
            out.iteration_stop = "pass " + std::to_string(pass) + "'s drive would leave the limits";
            break;
        }
        PassActuators actuators;
        PoseLoopResult loop = play(refit.trajectory, nullptr, pass, actuators);
        std::array<std::vector<double>, 3> achieved;
        const double rms = passRms(loop, achieved);
        out.pass_rms.push_back(rms);
        const double best = out.pass_rms[static_cast<std::size_t>(out.best_pass)];
        if (rms < best) {
            out.best_pass = pass;
            out.loop = std::move(loop);
            out.achieved = achieved;
            kept = std::move(actuators);
        }
        last_achieved = std::move(achieved);
        if (!(rms < (1.0 - settings.iteration_tolerance) * best)) {
            out.iteration_stop = "pass " + std::to_string(pass) + " improved the RMS error by less than " +
                                 std::to_string(static_cast<int>(100.0 * settings.iteration_tolerance)) + " %";
            break;
        }
    }
    if (settings.iterations > 0 && out.iteration_stop.empty()) out.iteration_stop = "the last pass asked";
    std::string text;
    if (settings.controller == "table") {
        const TableSensors& s = settings.table.sensors;
        text = text::format(
            "encoders: noise %.3g (m or rad) per actuator (pose noise at home %.3g rad, %.3g m, %.3g m); "
            "accelerometers: %s",
            s.encoder_noise, out.estimator.sigma_q(0), out.estimator.sigma_q(1), out.estimator.sigma_q(2),
            s.accelerometer ? "" : "none");
        out.sensing = text;
        if (s.accelerometer) {
            text = text::format(
                "noise density %.3g ug/sqrt(Hz) (ADXL355 default 22.5), bandwidth %.4g Hz (first-order), "
                "so %.3g m/s^2 RMS per axis; a pair %.3g m apart for alpha (%.3g rad/s^2 RMS); rates from "
                "the estimator",
                s.accel_noise_density / kGravity * 1e6, s.accel_bandwidth, out.estimator.sigma_y(1), s.accel_baseline,
                out.estimator.sigma_y(0));
            out.sensing += text;
        }
    } else {
        text = text::format("pose sensor: noise %.3g (m, rad); rate sensor: noise %.3g (m/s, rad/s)",
                            settings.noise_pose, settings.noise_rate);
        out.sensing = text;
    }
    // the record's passband, in the replay's time: [2 f_highpass (or 2 / duration), 0.4 / dt]
    const double record_duration = record.dt * static_cast<double>(fit.t.size() - 1);
    const double f_lo = std::max(2.0 * settings.fit.highpass, 2.0 / record_duration);
    const double f_hi = 0.4 / record.dt;
    out.period_min = 1.0 / (fit.time_scale * f_hi);
    out.period_max = 1.0 / (fit.time_scale * f_lo);
    // the samples the loop covered (its last tick is before the record's end)
    const std::size_t n = std::min(fit.t.size(), static_cast<std::size_t>(out.loop.t.back() / fit.dt) + 1);
    const double tick = 1.0 / settings.rate;
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
    out.achieved_use = kept.use;
    out.u_at_samples = std::move(kept.u);
    out.tau_at_samples = std::move(kept.tau);
    return out;
}

io::Table shakeTable(const ShakeOutcome& outcome, const Model& model) {
    const FittedRecord& fit = outcome.fit;
    const int n = model.actuators;
    // the record's (scaled) samples; u and tau from the nearest tick
    io::Table table;
    table.columns = io::columnNames(io::TableId::shake, {.actuators = n});
    const auto un = static_cast<std::size_t>(n);
    const std::size_t samples =
        un == 0 || outcome.loop.t.empty() ? 0 : std::min(fit.t.size(), outcome.u_at_samples.size() / un);
    Pose p, dp, ddp;
    const std::vector<double>& ticks = outcome.loop.t;
    for (std::size_t i = 0; i < samples; ++i) {
        const double t = fit.t[i];
        fit.trajectory.evaluate(t, p, dp, ddp);
        // the achieved pose at the tick nearest t (the loop's ticks are increasing)
        auto k = static_cast<std::size_t>(std::lower_bound(ticks.begin(), ticks.end(), t) - ticks.begin());
        if (k == ticks.size() || (k > 0 && t - ticks[k - 1] < ticks[k] - t)) --k;
        const Pose& achieved = outcome.loop.p[k];
        std::vector<double> row = {t,
                                   p(1),
                                   p(2),
                                   p(0),
                                   ddp(1),
                                   ddp(2),
                                   ddp(0),
                                   outcome.achieved[1][i],
                                   outcome.achieved[2][i],
                                   outcome.achieved[0][i],
                                   achieved(1),
                                   achieved(2),
                                   achieved(0)};
        for (std::size_t a = 0; a < un; ++a) row.push_back(outcome.u_at_samples[i * un + a]);
        for (std::size_t a = 0; a < un; ++a) row.push_back(outcome.tau_at_samples[i * un + a]);
        table.rows.push_back(std::move(row));
    }
    return table;
}

std::string shakeJson(const ShakeOutcome& outcome) {
    const FittedRecord& fit = outcome.fit;
    const PoseLoopResult& loop = outcome.loop;
    // every error a percentage, with _percent in its name (the text prints the same numbers)
    std::vector<double> pass_percent;
    for (double e : outcome.pass_rms) pass_percent.push_back(100.0 * e);
    nlohmann::json json;
    json["time_scale"] = fit.time_scale;
    json["amplitude_scale"] = fit.amplitude_scale;
    json["margin"] = outcome.margin;
    json["fitted_limit_use"] = {{"ratio", fit.use.ratio}, {"what", fit.use.what}, {"t", fit.use.t}};
    json["achieved_limit_use"] = {
        {"ratio", outcome.achieved_use.ratio}, {"what", outcome.achieved_use.what}, {"t", outcome.achieved_use.t}};
    json["passband_periods"] = {outcome.period_min, outcome.period_max};
    json["saturated_ticks"] = loop.saturated_ticks;
    json["duration"] = loop.t.empty() ? 0.0 : loop.t.back();
    json["amplitude_requested"] = outcome.amplitude;
    json["pass_rms_error_percent"] = pass_percent;
    json["pass_kept"] = outcome.best_pass;
    if (outcome.drive_model != DriveModel::identity) {
        json["drive_model"] = name(outcome.drive_model);
        json["drive_specimen"] = outcome.drive_specimen;
    }
    json["controller"] = loop.controller;
    json["sensors"] = outcome.sensing;
    if (outcome.payload.done) {
        const PayloadResult& e = outcome.payload.estimate;
        json["payload_estimate"] = {{"mass", e.mass},
                                    {"mass_sd", e.mass_sd},
                                    {"com", {e.com.x(), e.com.y()}},
                                    {"inertia", e.inertia},
                                    {"inertia_sd", e.inertia_sd}};
    }
    nlohmann::json metrics = nlohmann::json::object();
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!outcome.driven[axis]) continue;
        const ShakeScore& s = outcome.score[axis];
        metrics[kAxisNames[axis]] = {{"rms_error_percent", 100.0 * s.rms_error},
                                     {"peak_error_percent", 100.0 * s.peak_error},
                                     {"spectrum_outside_band_percent", 100.0 * s.share_outside},
                                     {"spectrum_periods_counted", s.counted},
                                     {"displacement_error_percent", 100.0 * s.displacement_error},
                                     {"velocity_error_percent", 100.0 * s.velocity_error},
                                     {"periods", s.periods},
                                     {"target_sa", s.target_sa},
                                     {"achieved_sa", s.achieved_sa}};
    }
    json["metrics"] = metrics;
    return json.dump(2) + "\n";
}

void writeShakeOutputs(const ShakeOutcome& outcome, const Model& model, const std::string& dir,
                       const std::string& title) {
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) throw Error("cannot create the folder '" + dir + "': " + error.message());
    const std::filesystem::path folder(dir);
    const FittedRecord& fit = outcome.fit;
    const PoseLoopResult& loop = outcome.loop;
    const io::Table table = shakeTable(outcome, model);
    io::writeCsvFile((folder / "shake.csv").string(), table);
    io::writeTextFile((folder / "shake.json").string(), shakeJson(outcome));

    // figures: target against achieved acceleration, and both spectra, per driven axis
    Figure accel{literalText(title) + ": target and achieved acceleration", {}};
    Figure spectra{literalText(title) + ": 5 %-damped pseudo-acceleration spectra", {}};
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!outcome.driven[axis]) continue;
        const std::vector<double>& a = target(fit, static_cast<int>(axis));
        const char* unit = axis == 0 ? "rad/s^2" : "m/s^2";
        PlotPanel panel{kAxisNames[axis], "t [s]", std::string(kAxisNames[axis]) + " [" + unit + "]", {}};
        PlotSeries tgt{"target", {}, {}, "lines lw 2 lc rgb '#1f4e79'"};
        PlotSeries ach{
            std::string("achieved (").append(loop.plant).append(" plant)"), {}, {}, "lines dt 2 lw 2 lc rgb '#d62728'"};
        for (std::size_t i = 0; i < table.rows.size(); ++i) {
            tgt.x.push_back(fit.t[i]);
            tgt.y.push_back(a[i]);
            ach.x.push_back(fit.t[i]);
            ach.y.push_back(outcome.achieved[axis][i]);
        }
        panel.series = {tgt, ach};
        panel.key_below = true;  // the plant's long name in one row under the plot, not beside it
        accel.panels.push_back(panel);
        const ShakeScore& s = outcome.score[axis];
        PlotPanel sp{kAxisNames[axis], "period T [s] (replay time)", std::string("S_a [") + unit + "]", {}};
        sp.log_x = true;
        sp.key_below = true;
        // the tolerance band 0.9 S_a to 1.1 S_a of the target, shaded under both curves
        PlotSeries band{"target \u00b110 %", s.periods, {}, "filledcurves fs solid 0.35 noborder lc rgb '#9ecae1'"};
        band.extra.emplace_back();
        for (double v : s.target_sa) {
            band.y.push_back(0.9 * v);
            band.extra[0].push_back(1.1 * v);
        }
        PlotSeries st{"target", s.periods, s.target_sa, "lines lw 2 lc rgb '#1f4e79'"};
        PlotSeries sa{"achieved", s.periods, s.achieved_sa, "lines dt 2 lw 2 lc rgb '#d62728'"};
        sp.series = {band, st, sa};
        spectra.panels.push_back(sp);
    }
    renderFigure(accel, (folder / "shake_acceleration").string());
    renderFigure(spectra, (folder / "shake_spectrum").string());
}

void printShakeSummary(const ShakeOutcome& outcome, std::ostream& out, bool with_timing) {
    const FittedRecord& fit = outcome.fit;
    std::string line;
    line = text::format(
        "time scale L = %.4g (time compressed %.4g times, displacement / L^2), amplitude scale A = %.4g\n"
        "fitted motion: worst limit use %.1f %% of the allowed (%s at t = %.4g s)\n",
        fit.time_scale, fit.time_scale, fit.amplitude_scale, 100.0 * fit.use.ratio, fit.use.what.c_str(), fit.use.t);
    out << line;
    if (outcome.amplitude != 1.0) {
        line = text::format("amplitude: the record's accelerations times %.4g before the fit, as asked (--amplitude)\n",
                            outcome.amplitude);
        out << line;
    }
    out << "controller: " << outcome.loop.controller << "\nsensors: " << outcome.sensing << "\n";
    if (outcome.payload.done) {
        const PayloadResult& e = outcome.payload.estimate;
        line = text::format(
            "payload identified first: m = %.4g +- %.2g kg, c.o.m. [%.3g, %.3g] m, I_zz = %.3g +- %.2g kg "
            "m^2 (excitation within %.1f %% of the limits); the controller's model carries it\n",
            e.mass, e.mass_sd, e.com.x(), e.com.y(), e.inertia, e.inertia_sd,
            100.0 * outcome.payload.excitation_use.ratio);
        out << line;
    }
    if (outcome.pass_rms.size() > 1 || !outcome.iteration_stop.empty()) {
        out << "drive iteration";
        if (outcome.drive_model != DriveModel::identity) {
            out << " (correction through the inverse closed loop, " << name(outcome.drive_model) << " derivatives"
                << (outcome.drive_specimen ? ", the plant carrying the weighed specimen" : "") << ")";
        }
        out << ": RMS error per pass";
        for (std::size_t k = 0; k < outcome.pass_rms.size(); ++k) {
            line = text::format(" %zu: %.2f %%", k, 100.0 * outcome.pass_rms[k]);
            out << (k > 0 ? "," : "") << line;
        }
        out << "; stopped: " << outcome.iteration_stop << "; pass " << outcome.best_pass << " kept\n";
    }
    const double duration = outcome.loop.t.back();
    if (with_timing) {
        line = text::format("closed loop: %.4g s of motion in %.3g s (%.3g x real time), ", duration, outcome.seconds,
                            duration / outcome.seconds);
    } else {
        line = text::format("closed loop: %.4g s of motion, ", duration);
    }
    out << line;
    line = text::format("%zu saturated ticks; worst use of a limit %.1f %% (%s)\n", outcome.loop.saturated_ticks,
                        100.0 * outcome.achieved_use.ratio, outcome.achieved_use.what.c_str());
    out << line;
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!outcome.driven[axis]) continue;
        const ShakeScore& s = outcome.score[axis];
        line = text::format(
            "%s: RMS error %.2f %% of the target RMS, peak error %+.2f %%, spectrum: %.0f %% of the %d "
            "periods %.3g-%.3g s with S_a >= 10 %% of its peak outside +-10 %%; displacement error %.2f "
            "%%, velocity error %.2f %%\n",
            kAxisNames[axis], 100.0 * s.rms_error, 100.0 * s.peak_error, 100.0 * s.share_outside, s.counted,
            outcome.period_min, outcome.period_max, 100.0 * s.displacement_error, 100.0 * s.velocity_error);
        out << line;
    }
}

void reproduceShake(const std::string& out_dir, std::ostream& summary) {
    summary << "## Earthquake record: El Centro 1940 N-S on the prototype\n\n";
    const io::GroundMotionRecord record = io::parseAt2(kElCentroAt2, "data/elcentro_1940_ns.AT2");
    // the strong part only keeps the replay short
    constexpr double kWindow = 3.0;  // [s] of record time: the onset and the peak (2.1 s)
    GroundRecord r;
    r.dt = record.dt;
    const auto n = std::min(record.acceleration.size(), static_cast<std::size_t>(kWindow / record.dt) + 1);
    r.ax.assign(record.acceleration.begin(), record.acceleration.begin() + static_cast<std::ptrdiff_t>(n));
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    ShakeSettings settings;
    // nocdyn's own plant keeps the replay within seconds (and under the sanitizers); `nocdyn shake`
    // plays on nocdyn's RK4 plant (nocdyn-rk4) by default, which scores the same motion alike
    settings.plant = "nocdyn";
    // the pose-sensor controller this section has always described
    settings.controller = "pose";
    const ShakeOutcome outcome = runShake(robot, r, settings);
    writeShakeOutputs(outcome, Model(robot), (std::filesystem::path(out_dir) / "elcentro").string(),
                      "El Centro 1940 N-S, x");
    std::ostringstream text;
    printShakeSummary(outcome, text, false);
    // the wall-clock time differs from run to run: on the console only, not in summary.md
    std::cout << "El Centro replay: " << outcome.loop.t.back() << " s of motion in " << outcome.seconds
              << " s of wall-clock time\n";
    summary << "The first " << kWindow << " s of the record along x, high-passed at " << settings.fit.highpass
            << " Hz (zero-phase Butterworth, order " << kHighPassOrder
            << " run forward and backward), scaled in time to fit the actuators with a " << 100.0 * settings.fit.margin
            << " % margin, then tracked by computed torque at " << settings.rate / 1000.0
            << " kHz (f_n = " << settings.natural_frequency
            << " Hz) on nocdyn's own forward dynamics (`--plant nocdyn`; `nocdyn shake` plays on its RK4 plant,"
            << " `nocdyn-rk4`, by default, and `--plant simbody` on the independent Simbody model) carrying a "
            << settings.payload.mass << " kg payload the controller does not know, with pose noise "
            << settings.noise_pose << " m (rad) and rate noise " << settings.noise_rate << " m/s (rad/s):\n\n```\n"
            << text.str() << "```\n\n"
            << "Files: `elcentro/shake.csv`, `elcentro/shake.json`, `elcentro/shake_acceleration.{png,svg}`,"
            << " `elcentro/shake_spectrum.{png,svg}`. `nocdyn shake --robot robots/paper-3prr-general.yaml --record"
            << " data/elcentro_1940_ns.AT2 --window " << kWindow << " --plant nocdyn --controller pose` reproduces"
            << " them (the pose-sensor controller; `nocdyn shake`'s default is the table controller).\n\n";
}

}  // namespace nocdyn::report
