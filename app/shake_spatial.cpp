#include "app/shake_spatial.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/shake_outputs.hpp"
#include "app/shake_records.hpp"
#include "app/shake_spatial_payload.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/ground_motion3.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/parallel.hpp"
#include "nocdyn/sim/spatial_shake.hpp"
#include "nocdyn/text.hpp"
#include "render/animation3d.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

// this file's helpers under their own name (the folder compiles as unity files)
namespace six_dof_shake {

constexpr double kDegree = 180.0 / std::numbers::pi;
constexpr double kPlantAbsoluteTolerance = 1e-9;
constexpr double kPlantRelativeTolerance = 1e-7;
constexpr double kPlantFloorStep = 5e-5;
constexpr double kSixDofRate = 1000.0;  ///< [Hz] the controller's rate unless given

/// What the six-DOF replay does not do (yet), refused by the option's name when set.
void refusePlanarOnly(const ShakeOptions& o, std::size_t records) {
    const ShakeOptions d;
    const char* planar = ": planar tables only for now (a six-DOF table replays in computed torque)";
    const auto refuse = [planar](bool set, const char* field, const char* what) {
        if (set) throw OptionError(field, std::string(what) + planar);
    };
    refuse(o.plant == PlantKind::simbody, "plant", "the Simbody plant");
    refuse(!o.record_y.empty(), "record_y", "a record on y alone");
    refuse(!o.record_theta.empty(), "record_theta", "a record on theta");
    refuse(o.axis != d.axis, "axis", "a record on one axis");
    if (records == 1 && o.threads != d.threads)
        throw OptionError("threads", "does not apply to one record: it goes with a suite (a folder of records)");
}

/// The drive-signal iteration of a six-DOF table corrects by the identity: the drive models
/// invert the planar table controller's closed loop.
void refuseDriveModel(const ShakeOptions& o) {
    if (o.drive_model != DriveModel::identity) {
        throw OptionError("drive_model", std::string(name(o.drive_model)) +
                                             ": planar tables only for now (it inverts the planar table "
                                             "controller's closed loop); a six-DOF table iterates with identity");
    }
}

/// The options of the drive-signal iteration (spatial::iterateReplay): the gain, the tolerance,
/// and the fit's options, whose margin the drive keeps half of.
spatial::DriveIterationOptions iterationOptions(const ShakeOptions& options) {
    spatial::DriveIterationOptions out;
    static_cast<DriveIterationSettings&>(out) = options;
    static_cast<FitSettings&>(out.fit) = options;
    return out;
}

/// shake.json's keys of the iteration, as a planar table's: the RMS error of each pass (its
/// worst axis's) and the pass kept, with each axis's errors and why it stopped.
void addIterationJson(const spatial::DriveIterationPasses& passes, nlohmann::json& json) {
    std::vector<double> worst;
    worst.reserve(passes.worst.size());
    nlohmann::json axes = nlohmann::json::object();
    for (double e : passes.worst) worst.push_back(100.0 * e);
    for (std::size_t axis = 0; axis < 3; ++axis) {
        std::vector<double> rms;
        rms.reserve(passes.rms.size());
        for (const std::array<double, 3>& p : passes.rms) rms.push_back(100.0 * p[axis]);
        axes[spatial::kShakeAxes[axis]] = rms;
    }
    json["pass_rms_error_percent"] = worst;
    json["pass_kept"] = passes.best_pass;
    if (passes.stop.empty()) return;
    json["pass_rms_error_percent_axes"] = axes;
    json["iteration_stop"] = passes.stop;
}

/// The summary's line of the iteration: each pass's RMS error per axis and its worst, why it
/// stopped, the pass kept (empty without iteration).
std::string iterationText(const spatial::DriveIterationPasses& passes) {
    if (passes.stop.empty()) return {};
    std::string text = "drive iteration (identity drive model; a pass's error is its worst axis's): RMS error per pass";
    for (std::size_t k = 0; k < passes.rms.size(); ++k) {
        const std::array<double, 3>& p = passes.rms[k];
        text += k > 0 ? "," : "";
        text += text::format(" %zu: %.2f %% (ax %.2f %%, ay %.2f %%, az %.2f %%)", k, 100.0 * passes.worst[k],
                             100.0 * p[0], 100.0 * p[1], 100.0 * p[2]);
    }
    text += "; stopped: ";
    text += passes.stop;
    text += "; pass ";
    text += std::to_string(passes.best_pass);
    text += " kept\n";
    return text;
}

/// The record's components on the table's x, y, z (in g, read as m/s^2), its first `window` seconds.
spatial::GroundRecord3 readRecord3(const RecordFiles& files, const ShakeOptions& options, Observer& observer,
                                   io::TableMotion& motion) {
    if (files.files.size() < 2) {
        throw OptionError("record", io::terminalText(files.label) +
                                        ": a six-DOF table replays a record given as its components (two "
                                        "horizontals and a vertical, each header's azimuth or UP): give each "
                                        "component's file with --record");
    }
    std::vector<io::GroundMotionRecord> components;
    components.reserve(files.files.size());
    for (const std::string& f : files.files) components.push_back(io::readAt2File(f));
    motion = io::combineComponents(components, options.x_azimuth);
    for (const std::string& note : motion.notes) observer.warning(files.label + ": " + note);
    spatial::GroundRecord3 record;
    record.dt = motion.dt;
    record.a = {motion.ax, motion.ay, motion.az};
    for (std::vector<double>& a : record.a) {
        for (double& v : a) v *= options.amplitude;
        if (options.window > 0.0)
            a.resize(std::min(a.size(), static_cast<std::size_t>(options.window / record.dt) + 1));
    }
    if (std::all_of(record.a.begin(), record.a.end(), [](const std::vector<double>& a) {
            return std::all_of(a.begin(), a.end(), [](double v) { return v == 0.0; });
        })) {
        throw Error(files.label + ": every acceleration" + (options.window > 0.0 ? " of the window" : "") +
                    " is zero: no ground motion to replay");
    }
    return record;
}

io::Table replayTable(const spatial::ShakeReplay3& r, const spatial::Model& model) {
    io::Table table;
    table.columns = {"t", "x_d", "y_d", "z_d", "ax", "ay", "az", "ax_achieved", "ay_achieved", "az_achieved"};
    for (const char* c : spatial::kCoordinateNames) table.columns.emplace_back(c);
    for (const char* prefix : {"u", "tau"}) {
        for (int a = 1; a <= model.actuators; ++a) table.columns.push_back(prefix + std::to_string(a));
    }
    const std::vector<double>& ticks = r.loop.t;
    const std::size_t n = std::min(r.fit.t.size(), static_cast<std::size_t>(ticks.back() / r.fit.dt) + 1);
    spatial::TaskVector p, dp, ddp;
    table.rows.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double t = r.fit.t[i];
        r.fit.trajectory.evaluate(t, p, dp, ddp);
        // the tick nearest t
        auto k = static_cast<std::size_t>(std::lower_bound(ticks.begin(), ticks.end(), t) - ticks.begin());
        if (k == ticks.size() || (k > 0 && t - ticks[k - 1] < ticks[k] - t)) --k;
        std::vector<double> row{t, p(0), p(1), p(2)};
        for (std::size_t axis = 0; axis < 3; ++axis) row.push_back(r.fit.a[axis][i]);
        for (std::size_t axis = 0; axis < 3; ++axis) row.push_back(r.achieved[axis][i]);
        for (int c = 0; c < 6; ++c) row.push_back(r.loop.p[k](c));
        for (int a = 0; a < model.actuators; ++a) row.push_back(r.loop.u[k](a));
        for (int a = 0; a < model.actuators; ++a) row.push_back(r.loop.tau[k](a));
        table.rows.push_back(std::move(row));
    }
    return table;
}

nlohmann::json useJson(const LimitUse& u) { return {{"ratio", u.ratio}, {"what", u.what}, {"t", u.t}}; }

std::string replayJson(const spatial::ShakeReplay3& r, const spatial::DriveIterationPasses& passes,
                       const io::TableMotion& motion, const ShakeOptions& options, const std::string& controller) {
    nlohmann::json json;
    json["time_scale"] = r.fit.time_scale;
    json["amplitude_scale"] = r.fit.amplitude;  // [x, y, z]
    json["per_axis_scale"] = r.fit.per_axis;
    json["x_azimuth"] = motion.x_azimuth;
    json["sources"] = motion.sources;
    json["margin"] = options.margin;
    json["specimen_mass"] = options.payload_mass;
    json["fitted_limit_use"] = useJson(r.fit.use);
    json["achieved_limit_use"] = useJson(r.achieved_use);
    json["passband_periods"] = {r.period_min, r.period_max};
    json["saturated_ticks"] = r.loop.saturated_ticks;
    json["duration"] = r.loop.t.back();
    json["amplitude_requested"] = options.amplitude;
    json["controller"] = controller;
    json["controller_rate"] = options.rate.value_or(six_dof_shake::kSixDofRate);  // [Hz]
    json["parasitic_rotation_deg"] = {
        {"roll", kDegree * r.parasitic[0]}, {"pitch", kDegree * r.parasitic[1]}, {"yaw", kDegree * r.parasitic[2]}};
    nlohmann::json metrics = nlohmann::json::object();
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const ShakeScore& s = r.score[axis];
        if (s.periods.empty()) continue;  // an axis that does not move
        metrics[spatial::kShakeAxes[axis]] = {{"rms_error_percent", 100.0 * s.rms_error},
                                              {"peak_error_percent", 100.0 * s.peak_error},
                                              {"spectrum_outside_band_percent", 100.0 * s.share_outside},
                                              {"spectrum_periods_counted", s.counted},
                                              {"displacement_error_percent", 100.0 * s.displacement_error},
                                              {"periods", s.periods},
                                              {"target_sa", s.target_sa},
                                              {"achieved_sa", s.achieved_sa}};
    }
    json["metrics"] = metrics;
    addIterationJson(passes, json);
    return json.dump(2) + "\n";
}

void figureFiles(const spatial::ShakeReplay3& r, const io::Table& table, const std::string& folder,
                 const std::string& title, FileSink& files) {
    render::Figure accel{render::literalText(title) + ": target and achieved acceleration", {}};
    render::Figure spectra{render::literalText(title) + ": 5 %-damped pseudo-acceleration spectra", {}};
    const std::size_t n = table.rows.size();
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (r.score[axis].periods.empty()) continue;
        accel.panels.push_back(accelerationPanel(spatial::kShakeAxes[axis], "m/s^2", std::span(r.fit.t).first(n),
                                                 std::span(r.fit.a[axis]).first(n),
                                                 std::span(r.achieved[axis]).first(n), "nocdyn"));
        spectra.panels.push_back(spectrumPanel(spatial::kShakeAxes[axis], "m/s^2", r.score[axis]));
    }
    files.figure(inFolder(folder, "shake_acceleration"), accel);
    files.figure(inFolder(folder, "shake_spectrum"), spectra);
}

/// The achieved motion on the 3-D page (render/animation3d.hpp): shake.csv's rows, the loop's
/// pose, u and tau at the tick nearest each record instant; the page keeps at most
/// render::kMaxAnimationFrames of them as frames (evenly spread) and every row's extremes in its plots.
std::string animationPage(const spatial::Model& model, const io::Table& table, const std::string& source) {
    render::SpatialMotionSamples motion;
    motion.source = source;
    motion.actuators = model.actuators;
    const std::size_t pose = table.column(spatial::kCoordinateNames[0]);
    const std::size_t u = table.column("u1"), tau = table.column("tau1");
    const auto n = static_cast<std::size_t>(model.actuators);
    for (const std::vector<double>& row : table.rows) {
        motion.t.push_back(row[0]);
        spatial::TaskVector p(6);
        for (std::size_t c = 0; c < 6; ++c) p(static_cast<Eigen::Index>(c)) = row[pose + c];
        motion.p.push_back(p);
        for (std::size_t a = 0; a < n; ++a) {
            motion.u.push_back(row[u + a]);
            motion.tau.push_back(row[tau + a]);
        }
    }
    return render::spatialAnimationPage(model, motion, {});
}

std::string summary(const spatial::ShakeReplay3& r, const spatial::DriveIterationPasses& passes,
                    const io::TableMotion& motion, const ShakeOptions& options, const std::string& controller,
                    ShakeResult& out) {
    const spatial::FittedRecord3& fit = r.fit;
    std::string text = text::format(
        "components: x at azimuth %g deg, y at %g deg, z up; time scale L = %.4g, amplitude scale A = %.4g, %.4g, "
        "%.4g (x, y, z; %s)\n",
        motion.x_azimuth, std::fmod(motion.x_azimuth + 630.0, 360.0), fit.time_scale, fit.amplitude[0],
        fit.amplitude[1], fit.amplitude[2], fit.per_axis ? "per axis" : "one for all three");
    text += text::format(
        "fitted motion (specimen %g kg on the platform): worst limit use %.1f %% of the allowed (%s at "
        "t = %.4g s)\n",
        options.payload_mass, 100.0 * fit.use.ratio, fit.use.what.c_str(), fit.use.t);
    text += "controller: " + controller + "\n";
    text += text::format(
        "closed loop: %.4g s of motion in %.3g s, %zu saturated ticks; worst use of a limit %.1f %% (%s)\n",
        r.loop.t.back(), r.seconds, r.loop.saturated_ticks, 100.0 * r.achieved_use.ratio, r.achieved_use.what.c_str());
    text += text::format("rotations (held at zero): peak |roll| %.3g deg, |pitch| %.3g deg, |yaw| %.3g deg\n",
                         kDegree * r.parasitic[0], kDegree * r.parasitic[1], kDegree * r.parasitic[2]);
    text += iterationText(passes);
    out.passed = 1;
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const ShakeScore& s = r.score[axis];
        if (s.periods.empty()) continue;
        ShakeSuiteRow row;
        row.record = motion.name + " " + spatial::kShakeAxes[axis];
        row.time_scale = fit.time_scale;
        row.amplitude = fit.amplitude[axis] * options.amplitude;
        row.amplitude_asked = options.amplitude != 1.0;
        row.rms_error_percent = 100.0 * s.rms_error;
        row.peak_error_percent = 100.0 * s.peak_error;
        row.within_percent = 100.0 * (1.0 - s.share_outside);
        row.limit_use_percent = 100.0 * r.achieved_use.ratio;
        row.binding = r.achieved_use.what;
        row.pass = row.rms_error_percent <= options.max_rms_percent &&
                   std::abs(row.peak_error_percent) <= options.max_peak_percent &&
                   row.within_percent >= options.min_spectrum_percent && r.achieved_use.ratio <= 1.0;
        text += text::format(
            "%s: RMS error %.2f %% of the target RMS, peak error %+.2f %%, spectrum: %.0f %% of the %d periods "
            "%.3g-%.3g s within +-10 %%; displacement error %.2f %%; %s\n",
            spatial::kShakeAxes[axis], row.rms_error_percent, row.peak_error_percent, row.within_percent, s.counted,
            r.period_min, r.period_max, 100.0 * s.displacement_error, row.pass ? "pass" : "FAIL");
        out.passed = out.passed != 0 && row.pass ? 1 : 0;
        out.rows.push_back(std::move(row));
    }
    text += text::format(
        "verdict (every axis against the goals: RMS <= %.3g %%, |peak| <= %.3g %%, spectrum within +-10 %% at >= "
        "%.3g %% of the counted periods, every limit <= 100 %%): %s\n",
        options.max_rms_percent, options.max_peak_percent, options.min_spectrum_percent, out.passed ? "pass" : "FAIL");
    return text;
}

/// The closed loop's settings from the options, and the controller's description.
spatial::LoopOptions loopOptions(const ShakeOptions& options, std::string& controller) {
    spatial::LoopOptions loop;
    // a six-DOF table's plant costs some 20 times a planar one's per tick: 1 kHz unless given (the
    // forces of the hold's middle state keep the error O(dt^2): El Centro's z within 2 % at 1 kHz)
    loop.rate = options.rate.value_or(kSixDofRate);
    loop.controller = ControlLaw::computed_torque;
    loop.mid_hold = true;
    loop.natural_frequency = options.natural_frequency.value_or(kPoseNaturalFrequency);
    // the plant integrated to 1e-9 m (rad) and 1e-7 relative, a step the error test rejects
    // taken anyway at 50 us: where a leg's rate changes sign its Coulomb friction jumps, and the
    // error control would shrink the step to the 1 us floor at each jump (taking most of the
    // time); such a step errs by about the jump in acceleration times h^2 / 2 (~1e-9 m)
    loop.simulator.atol = kPlantAbsoluteTolerance;
    loop.simulator.rtol = kPlantRelativeTolerance;
    loop.simulator.floor_step = kPlantFloorStep;
    const bool noisy = options.controller == ShakeController::pose;
    if (noisy) {
        static_cast<PoseSensorNoise&>(loop) = poseSensorNoise(options.noise_pose, options.noise_rate, options.seed);
    }
    controller = text::format(
        "computed torque on the %s pose and rate (f_n = %g Hz, %g Hz), the rotations' targets zero; the model "
        "carries the specimen",
        noisy ? "noisy" : "exact", loop.natural_frequency, loop.rate);
    return loop;
}

/// The record fitted to the table's limits (nocdyn/sim/spatial_shake.hpp, fitRecord).
spatial::FittedRecord3 fitOf(const spatial::Model& model, const spatial::GroundRecord3& record,
                             const ShakeOptions& options, const spatial::LoopOptions& loop) {
    FitOptions fit_options;
    static_cast<FitSettings&>(fit_options) = options;
    spatial::FittedRecord3 fit = spatial::fitRecord(model, record, fit_options, options.per_axis_scale);
    if (!(fit.t.back() * loop.rate <= 1e7)) {
        throw OptionError("rate", text::format("%g s of replay at %g Hz: at most 1e7 ticks (give --window)",
                                               fit.t.back(), loop.rate));
    }
    return fit;
}

/// One record's files, handed to `files` in `folder` ("": the output folder itself): shake.csv,
/// shake.json, the figures and the 3-D page (built before any file is handed over: a pose out of
/// reach leaves no partial output).
void recordFiles(const spatial::ShakeReplay3& r, const spatial::Model& model, const ShakeResult& out,
                 const std::string& folder, const std::string& label, FileSink& files) {
    const std::string title = model.name + ": " + label;
    const std::string page = animationPage(model, out.table, title);
    files.folder(folder);
    files.table(inFolder(folder, "shake.csv"), out.table);
    files.text(inFolder(folder, "shake.json"), out.metrics_json);
    figureFiles(r, out.table, folder, title, files);
    files.text(inFolder(folder, "shake_animation.html"), page);
}

/// A record of a suite, read: its files and its components on the table's x, y, z.
struct SuiteRecord {
    io::TableMotion motion;
    spatial::GroundRecord3 record;
};

/// A suite's record must be three components, two horizontals and a vertical; anything else is
/// refused naming its file (a lone component) or its files.
SuiteRecord readSuiteRecord(const RecordFiles& files, const ShakeOptions& options, Observer& observer) {
    const char* want =
        "a six-DOF table's suite groups the files by their shared name prefix into records of three "
        "components (two horizontals and a vertical, each header's azimuth or UP)";
    if (files.files.size() == 1) {
        throw OptionError("record", io::terminalText(files.label) +
                                        ": cannot be grouped with other components (no two other files of the suite "
                                        "share its name prefix '" +
                                        io::terminalText(io::componentGroup(files.label)) +
                                        "', or a header lacks "
                                        "its orientation): " +
                                        want);
    }
    SuiteRecord out;
    out.record = readRecord3(files, options, observer, out.motion);
    if (files.files.size() != 3 || !out.motion.has_vertical) {
        std::string names;
        for (const std::string& f : files.files)
            names += (names.empty() ? "" : ", ") + io::terminalText(std::filesystem::path(f).filename().string());
        throw OptionError("record", io::terminalText(files.label) + " (" + names + "): no vertical component: " + want);
    }
    return out;
}

/// The suite's summary.md: one row per record and axis, then the grouping of the files.
std::string suiteTable(const ShakeResult& r, std::size_t records, const std::vector<SuiteRecord>& read,
                       const std::vector<std::string>& folders, const ShakeOptions& options,
                       const std::string& controller, std::size_t workers) {
    std::string text = text::format(
        "%zu records (three components each) on a six-DOF table, %s, %zu at a time; pass: RMS <= %.3g %%, "
        "|peak| <= %.3g %%, spectrum within +-10 %% at >= %.3g %% of the counted periods, every limit <= 100 %%, "
        "on every axis\n\n",
        records, controller.c_str(), workers, options.max_rms_percent, options.max_peak_percent,
        options.min_spectrum_percent);
    text +=
        "| record | folder | axis | L | A | RMS error | peak error | spectrum within +-10 % | worst limit use "
        "(binding) | result |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const ShakeSuiteRow& row : r.rows) {
        // the record's name and the axis (rows are "NAME ax")
        const std::size_t space = row.record.rfind(' ');
        text += "| " + io::markdownText(row.record.substr(0, space)) + " | " + io::markdownText(row.folder) + " | " +
                row.record.substr(space + 1) + " |";
        text += text::format(" %.4g | %.4g%s | %.2f %% | %+.2f %% | %.0f %% | %.0f %% (%s) | %s |\n", row.time_scale,
                             row.amplitude, row.amplitude_asked ? " (asked)" : "", row.rms_error_percent,
                             row.peak_error_percent, row.within_percent, row.limit_use_percent, row.binding.c_str(),
                             row.pass ? "pass" : "FAIL");
    }
    text += "\n" + std::to_string(r.passed) + " of " + std::to_string(records) + " records pass (every axis)\n";
    text +=
        "\nComponents grouped into records by their shared name prefix (x, y: the horizontals rotated onto the "
        "table; z: the vertical):\n";
    for (std::size_t i = 0; i < read.size(); ++i) {
        const io::TableMotion& m = read[i].motion;
        text += "- " + io::markdownText(m.name) + " (folder " + io::markdownText(folders[i]) + "):";
        for (std::size_t c = 0; c < m.sources.size(); ++c) {
            text += (c ? ", " : " ") + io::markdownText(std::filesystem::path(m.sources[c]).filename().string());
        }
        text += "\n";
    }
    return text;
}

/// A suite: every record read (and refused) before any replay, then replayed on `threads` workers
/// from a queue; one folder per record and summary.md under out_dir.
ShakeResult runSuite(const std::vector<RecordFiles>& records, const ShakeOptions& options, const spatial::Model& model,
                     Observer& observer, FileSink& files) {
    if (options.out_dir.empty()) throw OptionError("out_dir", "a suite of records needs an output folder");
    std::vector<SuiteRecord> read;
    read.reserve(records.size());
    for (const RecordFiles& r : records) read.push_back(readSuiteRecord(r, options, observer));
    const std::vector<std::string> folders = recordFolders(records);
    std::string controller;
    const spatial::LoopOptions loop = loopOptions(options, controller);
    const std::size_t workers =
        std::min<std::size_t>(options.threads > 0 ? options.threads : hardwareThreads(), records.size());
    std::vector<ShakeResult> results(records.size());  // each record's rows and verdict
    std::vector<std::string> errors(records.size());
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    std::mutex mutex;  // the outputs (figures) one at a time, and the count of records done
    std::condition_variable finished;
    std::size_t done = 0;
    // workers never call the observer: a stop reaches each replay at its next tick
    spatial::LoopOptions stoppable = loop;
    stoppable.progress = [&stop](double /*t*/) {
        if (stop.load(std::memory_order_relaxed)) throw Cancelled();
    };
    const auto work = [&] {
        for (std::size_t i = next++; i < records.size() && !stop; i = next++) {
            try {
                spatial::DriveIterationPasses passes;
                const spatial::ShakeReplay3 r =
                    spatial::iterateReplay(model, fitOf(model, read[i].record, options, loop), stoppable,
                                           options.highpass, iterationOptions(options), passes);
                ShakeResult& one = results[i];
                one.table = replayTable(r, model);
                one.metrics_json = replayJson(r, passes, read[i].motion, options, controller);
                (void)summary(r, passes, read[i].motion, options, controller, one);
                const std::lock_guard lock(mutex);
                recordFiles(r, model, one, folders[i], records[i].label, files);
                one.table = {};  // written; keep the scores
            } catch (const std::exception& e) {
                errors[i] = e.what();
            }
            const std::lock_guard lock(mutex);
            ++done;
            finished.notify_all();
        }
    };
    // the calling thread watches (worker 0): the progress, and a stop asked by the observer
    const auto watch = [&] {
        try {
            std::unique_lock lock(mutex);
            while (done < records.size()) {
                finished.wait_for(lock, std::chrono::milliseconds(200));
                const auto count = static_cast<double>(done);
                lock.unlock();
                observer.progress(count, static_cast<double>(records.size()), "records");
                stopIfRequested(observer);
                lock.lock();
            }
        } catch (...) {
            stop = true;
            throw;
        }
    };
    runWorkers("shake", static_cast<unsigned>(workers) + 1, [&](unsigned w) {
        if (w == 0) {
            watch();
        } else {
            work();
        }
    });
    ShakeResult out;
    out.suite = true;
    for (std::size_t i = 0; i < records.size(); ++i) {
        if (!errors[i].empty()) throw Error(records[i].label + ": " + errors[i]);
        ShakeResult& one = results[i];
        out.passed += one.passed;
        for (ShakeSuiteRow& row : one.rows) {
            row.folder = folders[i];
            out.rows.push_back(std::move(row));
        }
    }
    out.text = suiteTable(out, records.size(), read, folders, options, controller, workers);
    files.text("summary.md", out.text);
    return out;
}

}  // namespace six_dof_shake

ShakeResult runSpatialShake(const ShakeOptions& options, Observer& observer, FileSink& files) {
    if (options.x_azimuth) requireIn(*options.x_azimuth, kAzimuthRange, "x_azimuth");
    const std::vector<RecordFiles> records = groupRecordFiles(options.record);
    six_dof_shake::refusePlanarOnly(options, records.size());
    six_dof_shake::refuseDriveModel(options);
    const SpatialRobotDescription description = io::loadSpatialRobotDescription(options.robot.path, options.robot.set);
    // the specimen on the platform, in the fit's inverse dynamics and in the plant (the
    // controller's model carries it too)
    const spatial::Model model(spatial::withSpecimen(description, options.payload_mass));
    if (records.size() > 1 && options.identify_payload)
        throw OptionError("identify_payload", "a six-DOF table identifies the specimen before one record, not a suite");
    if (records.size() > 1) return six_dof_shake::runSuite(records, options, model, observer, files);
    io::TableMotion motion;
    const spatial::GroundRecord3 record = six_dof_shake::readRecord3(records.front(), options, observer, motion);
    std::string controller;
    spatial::LoopOptions loop = six_dof_shake::loopOptions(options, controller);
    // the specimen identified first: the controller's model the robot carrying it as identified
    std::optional<SpatialSpecimen> specimen;
    std::optional<spatial::Model> identified;
    if (options.identify_payload) {
        specimen = identifySpatialSpecimen(description, model, options, loop);
        identified.emplace(spatial::withPayload(description, specimen->estimate.payload));
        loop.controller_model = &*identified;
        controller += " as identified first";
    }
    spatial::FittedRecord3 fit = six_dof_shake::fitOf(model, record, options, loop);
    // every pass's seconds of motion (the first, and at most `iterations` more)
    const double total = fit.t.back() * (1.0 + options.iterations);
    Meter meter(observer, total, "s");
    spatial::LoopOptions metered = loop;
    metered.progress = [&meter](double t) { meter(t); };
    spatial::DriveIterationPasses passes;
    const spatial::ShakeReplay3 r = spatial::iterateReplay(model, std::move(fit), metered, options.highpass,
                                                           six_dof_shake::iterationOptions(options), passes);
    meter.report(total);
    ShakeResult out;
    out.table = six_dof_shake::replayTable(r, model);
    out.metrics_json = six_dof_shake::replayJson(r, passes, motion, options, controller);
    out.text = six_dof_shake::summary(r, passes, motion, options, controller, out);
    if (specimen) {
        out.metrics_json = withPayloadJson(out.metrics_json, *specimen);
        out.text = payloadSummary(*specimen) + out.text;
    }
    if (!options.out_dir.empty()) {
        six_dof_shake::recordFiles(r, model, out, "", records.front().label, files);
        out.animation = true;
    }
    return out;
}

}  // namespace nocdyn::app
