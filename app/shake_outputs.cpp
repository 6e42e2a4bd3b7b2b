// The files and text of a replay (see shake_outputs.hpp).
#include "app/shake_outputs.hpp"

#include <algorithm>
#include <ostream>

#include <nlohmann/json.hpp>

#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

constexpr std::array<const char*, 3> kReplayAxes = {"alpha", "ax", "ay"};

const std::vector<double>& replayTarget(const FittedRecord& fit, int axis) {
    return axis == 0 ? fit.alpha : axis == 1 ? fit.ax : fit.ay;
}

}  // namespace

render::PlotPanel accelerationPanel(const std::string& name, const char* unit, std::span<const double> t,
                                    std::span<const double> target, std::span<const double> achieved,
                                    const std::string& plant) {
    render::PlotPanel panel{name, "t [s]", name + " [" + unit + "]", {}};
    render::PlotSeries tgt{
        "target", {t.begin(), t.end()}, {target.begin(), target.end()}, "lines lw 2 lc rgb '#1f4e79'"};
    render::PlotSeries ach{std::string("achieved (").append(plant).append(" plant)"),
                           {t.begin(), t.end()},
                           {achieved.begin(), achieved.end()},
                           "lines dt 2 lw 2 lc rgb '#d62728'"};
    panel.series = {tgt, ach};
    panel.key_below = true;  // the plant's long name in one row under the plot, not beside it
    return panel;
}

render::PlotPanel spectrumPanel(const std::string& name, const char* unit, const ShakeScore& s) {
    render::PlotPanel sp{name, "period T [s] (replay time)", std::string("S_a [") + unit + "]", {}};
    sp.log_x = true;
    sp.key_below = true;
    // the tolerance band 0.9 S_a to 1.1 S_a of the target, shaded under both curves
    render::PlotSeries band{"target \u00b110 %", s.periods, {}, "filledcurves fs solid 0.35 noborder lc rgb '#9ecae1'"};
    band.extra.emplace_back();
    for (double v : s.target_sa) {
        band.y.push_back(0.9 * v);
        band.extra[0].push_back(1.1 * v);
    }
    render::PlotSeries st{"target", s.periods, s.target_sa, "lines lw 2 lc rgb '#1f4e79'"};
    render::PlotSeries sa{"achieved", s.periods, s.achieved_sa, "lines dt 2 lw 2 lc rgb '#d62728'"};
    sp.series = {band, st, sa};
    return sp;
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
    if (model.task_dimension == 2) {
        // a two-DOF table: the tool point's x, y, no theta or alpha column
        for (const char* name : {"theta_achieved", "alpha_achieved", "alpha", "theta"}) {
            const auto at = std::find(table.columns.begin(), table.columns.end(), name);
            if (at == table.columns.end()) continue;
            const auto c = at - table.columns.begin();
            table.columns.erase(at);
            for (std::vector<double>& row : table.rows) row.erase(row.begin() + c);
        }
    }
    return table;
}

std::string shakeJson(const ShakeOutcome& outcome) {
    const FittedRecord& fit = outcome.fit;
    const PoseLoopResult& loop = outcome.loop;
    // every error a percentage, with _percent in its name (the text prints the same numbers)
    std::vector<double> pass_percent;
    pass_percent.reserve(outcome.pass_rms.size());
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
        metrics[kReplayAxes[axis]] = {{"rms_error_percent", 100.0 * s.rms_error},
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

void shakeFiles(const ShakeOutcome& outcome, const Model& model, const std::string& folder, const std::string& title,
                FileSink& files) {
    files.folder(folder);
    const FittedRecord& fit = outcome.fit;
    const PoseLoopResult& loop = outcome.loop;
    const io::Table table = shakeTable(outcome, model);
    files.table(inFolder(folder, "shake.csv"), table);
    files.text(inFolder(folder, "shake.json"), shakeJson(outcome));

    // figures: target against achieved acceleration, and both spectra, per driven axis
    render::Figure accel{render::literalText(title) + ": target and achieved acceleration", {}};
    render::Figure spectra{render::literalText(title) + ": 5 %-damped pseudo-acceleration spectra", {}};
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!outcome.driven[axis]) continue;
        const std::vector<double>& a = replayTarget(fit, static_cast<int>(axis));
        const char* unit = axis == 0 ? "rad/s^2" : "m/s^2";
        const std::size_t n = table.rows.size();
        accel.panels.push_back(accelerationPanel(kReplayAxes[axis], unit, std::span(fit.t).first(n),
                                                 std::span(a).first(n), std::span(outcome.achieved[axis]).first(n),
                                                 loop.plant));
        spectra.panels.push_back(spectrumPanel(kReplayAxes[axis], unit, outcome.score[axis]));
    }
    files.figure(inFolder(folder, "shake_acceleration"), accel);
    files.figure(inFolder(folder, "shake_spectrum"), spectra);
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
            kReplayAxes[axis], 100.0 * s.rms_error, 100.0 * s.peak_error, 100.0 * s.share_outside, s.counted,
            outcome.period_min, outcome.period_max, 100.0 * s.displacement_error, 100.0 * s.velocity_error);
        out << line;
    }
}

}  // namespace nocdyn::app
