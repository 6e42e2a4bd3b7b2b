#include "app/shake.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <string_view>
#include <utility>

#include "app/outputs.hpp"
#include "app/plants.hpp"
#include "app/shake_outputs.hpp"
#include "app/shake_records.hpp"
#include "app/shake_spatial.hpp"
#include "app/pose_spatial.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/parallel.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

/// Why `axis` and `record_y` do not go with a record given as its components.
constexpr const char* kComponentsDriveBoth =
    "a record given as its components drives x and y itself (its horizontals rotated onto them)";

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

/// The replay's options: the command's time scale ("auto" or a decimal L) in time_scale.
ShakeReplayOptions replayOptions(const ShakeOptions& o) {
    ShakeReplayOptions replay = o;
    if (o.time_scale_text == "auto") return replay;
    // a decimal number only (std::stod would read 0x10 as 16, and nan or inf)
    double value = 0.0;
    const std::string& text = o.time_scale_text;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc{} || end != text.data() + text.size() || !(value >= 1e-3 && value <= 1e4)) {
        throw OptionError("time_scale", "expected auto or a decimal number from 0.001 to 10000, got '" +
                                            io::terminalText(text) + "'");
    }
    replay.time_scale = value;
    return replay;
}

/// The plant the options name, for the robot it carries.
PlantFactory plantFactory(const ShakeOptions& o) {
    return [kind = o.plant, accuracy = o.accuracy](const RobotDescription& robot) {
        return makePlant(kind, robot, accuracy);
    };
}

/// The pose coordinate `record` drives, in the replay's order [theta, x, y]: 1 (x) or 2 (y).
std::size_t recordAxis(const ShakeOptions& options) { return options.axis == ShakeAxis::y ? 2 : 1; }

/// The acceleration series of the axis `record` drives.
std::vector<double>& recordTarget(GroundRecord& record, const ShakeOptions& options) {
    return recordAxis(options) == 2 ? record.ay : record.ax;
}

/// A suite's row from its replay: the scores of the record's axis, and whether every threshold holds.
ShakeSuiteRow scoreRow(const ShakeOutcome& o, const ShakeOptions& options) {
    const ShakeScore& s = o.score[recordAxis(options)];
    ShakeSuiteRow row;
    row.time_scale = o.fit.time_scale;
    row.amplitude = o.fit.amplitude_scale * o.amplitude;
    row.amplitude_asked = o.amplitude != 1.0;
    row.rms_error_percent = 100.0 * s.rms_error;
    row.peak_error_percent = 100.0 * s.peak_error;
    row.within_percent = 100.0 * (1.0 - s.share_outside);
    row.limit_use_percent = 100.0 * o.achieved_use.ratio;
    row.binding = o.achieved_use.what;
    row.pass = row.rms_error_percent <= options.max_rms_percent &&
               std::abs(row.peak_error_percent) <= options.max_peak_percent &&
               row.within_percent >= options.min_spectrum_percent && o.achieved_use.ratio <= 1.0;
    return row;
}

/// A single replay's verdict: pass, or FAIL naming each goal missed, with the goals.
std::string verdictLine(const ShakeSuiteRow& row, const ShakeOptions& options) {
    std::vector<std::string> missed;
    if (!(row.rms_error_percent <= options.max_rms_percent))
        missed.push_back(text::format("RMS error %.3g %% > %.3g %%", row.rms_error_percent, options.max_rms_percent));
    if (!(std::abs(row.peak_error_percent) <= options.max_peak_percent))
        missed.push_back(
            text::format("|peak error| %.3g %% > %.3g %%", std::abs(row.peak_error_percent), options.max_peak_percent));
    if (!(row.within_percent >= options.min_spectrum_percent))
        missed.push_back(text::format("spectrum within +-10 %% at %.3g %% < %.3g %% of the counted periods",
                                      row.within_percent, options.min_spectrum_percent));
    if (!(row.limit_use_percent <= 100.0))
        missed.push_back(text::format("%s at %.3g %% of its limit", row.binding.c_str(), row.limit_use_percent));
    std::string line = text::format(
        "verdict (%s, against the goals: RMS <= %.3g %%, |peak| <= %.3g %%, spectrum within +-10 %% at >= %.3g "
        "%% of the counted periods, every limit <= 100 %%): ",
        std::string(nameOf(options.axis)).c_str(), options.max_rms_percent, options.max_peak_percent,
        options.min_spectrum_percent);
    if (row.pass) return line + "pass\n";
    line += "FAIL (";
    for (std::size_t i = 0; i < missed.size(); ++i) line += (i ? "; " : "") + missed[i];
    return line + ")\n";
}

/// summary.md of a suite.
std::string suiteTable(const ShakeResult& r, const ShakeOptions& options, std::size_t workers,
                       const std::string& sensing) {
    std::ostringstream out;
    std::string line;
    line = text::format(
        "%zu records on %s%s, controller %s, %zu at a time; pass: RMS <= %.3g %%, |peak| <= %.3g %%, "
        "spectrum within +-10 %% at >= %.3g %% of the counted periods, every limit <= 100 %%\n\n",
        r.rows.size(), std::string(nameOf(options.plant)).c_str(),
        options.axis == ShakeAxis::y ? ", each driving and scored on y" : "",
        std::string(nameOf(options.controller)).c_str(), workers, options.max_rms_percent, options.max_peak_percent,
        options.min_spectrum_percent);
    out << line << "sensors: " << sensing << "\n\n"
        << "| record | folder | L | A | RMS error | peak error | spectrum within +-10 % | worst limit use (binding) | "
           "result |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const ShakeSuiteRow& row : r.rows) {
        line = text::format(" %.4g | %.4g%s | %.2f %% | %+.2f %% | %.0f %% | %.0f %% (%s) | %s |", row.time_scale,
                            row.amplitude, row.amplitude_asked ? " (asked)" : "", row.rms_error_percent,
                            row.peak_error_percent, row.within_percent, row.limit_use_percent, row.binding.c_str(),
                            row.pass ? "pass" : "FAIL");
        // the names through the Markdown escaper: a file name cannot forge a row or carry HTML
        out << "| " << io::markdownText(std::filesystem::path(row.record).filename().string()) << " | "
            << io::markdownText(row.folder) << " |" << line << "\n";
    }
    out << "\n" << r.passed << " of " << r.rows.size() << " records pass\n";
    return out.str();
}

ShakeResult runSuite(const std::vector<RecordFiles>& records, const ShakeOptions& options,
                     const ShakeReplayOptions& replay, const RobotDescription& robot, Observer& observer,
                     FileSink& files) {
    if (options.out_dir.empty()) throw OptionError("out_dir", "a suite of records needs an output folder");
    const std::vector<std::string> folders = recordFolders(records);
    std::vector<GroundRecord> inputs(records.size());
    // every record read (and refused) before any replay
    std::vector<std::string> notes;
    for (std::size_t i = 0; i < records.size(); ++i) {
        if (records[i].files.size() > 1) {
            if (options.axis == ShakeAxis::y) throw OptionError("axis", records[i].label + ": " + kComponentsDriveBoth);
            inputs[i] = readComponents(records[i], options.window, notes, options.x_azimuth);
        } else {
            recordTarget(inputs[i], options) = readAxis(records[i].label, options.window, inputs[i].dt, false);
        }
    }
    for (const std::string& note : notes) observer.warning(note);
    const std::size_t workers =
        std::min<std::size_t>(options.threads > 0 ? options.threads : hardwareThreads(), records.size());
    std::vector<ShakeOutcome> outcomes(records.size());
    std::vector<std::string> errors(records.size());
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stop{false};
    std::mutex mutex;  // the outputs (figures) one at a time, and the count of records done
    std::condition_variable finished;
    std::size_t done = 0;
    const PlantFactory make_plant = plantFactory(options);
    // workers never call the observer: a stop reaches each replay at its next tick
    const std::function<void(double)> stopper = [&stop](double /*t*/) {
        if (stop.load(std::memory_order_relaxed)) throw Cancelled();
    };
    const auto work = [&] {
        for (std::size_t i = next++; i < records.size() && !stop; i = next++) {
            try {
                outcomes[i] = runShakeReplay(robot, inputs[i], replay, make_plant, stopper);
                const std::lock_guard lock(mutex);
                shakeFiles(outcomes[i], Model(robot), folders[i], robot.name + ": " + records[i].label, files);
                outcomes[i].loop = {};  // the ticks are written; keep the scores
                outcomes[i].achieved = {};
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
        ShakeSuiteRow row = scoreRow(outcomes[i], options);
        row.record = records[i].label;
        row.folder = folders[i];
        out.passed += row.pass ? 1 : 0;
        out.rows.push_back(std::move(row));
    }
    out.text = suiteTable(out, options, workers, outcomes.front().sensing);
    // the records made of components, their names through the Markdown escaper as in the table
    std::string grouped;
    for (const RecordFiles& r : records) {
        if (r.files.size() == 1) continue;
        const std::string files = " (" + std::to_string(r.files.size()) + " files)";
        grouped += (grouped.empty() ? "" : ", ") + io::markdownText(r.label) + files;
    }
    if (!grouped.empty()) {
        out.text +=
            "\nComponents grouped into records by their shared name prefix, the horizontals on x and y: " + grouped +
            "\n";
    }
    files.text("summary.md", out.text);
    return out;
}

void requireCount(long long value, long long hi, const char* field) {
    if (value < 0 || value > hi) {
        throw OptionError(field, std::to_string(value) + " is outside [0, " + std::to_string(hi) + "]");
    }
}

/// An option set away from its default where it has no effect is refused, naming the option it
/// goes with (a value left at its default changes nothing either way).
void refuseWhatDoesNotApply(const ShakeOptions& o) {
    const ShakeOptions d;
    const bool table = o.controller == ShakeController::table;
    const auto refuse = [](bool set, const char* field, const std::string& needs) {
        if (set) throw OptionError(field, "does not apply here: it goes with " + needs);
    };
    // the drive iteration's settings: only with passes to iterate
    refuse(o.drive_model != d.drive_model && o.iterations == 0, "drive_model",
           "`iterations` 1 or more (the passes whose drive it corrects)");
    refuse(o.iteration_gain != d.iteration_gain && o.iterations == 0, "iteration_gain", "`iterations` 1 or more");
    refuse(o.iteration_tolerance != d.iteration_tolerance && o.iterations == 0, "iteration_tolerance",
           "`iterations` 1 or more");
    refuse(o.excitation_duration != d.excitation_duration && !o.identify_payload, "excitation_duration",
           "`identify_payload`");
    // the table controller's sensing, and the pose controller's noisy sensor
    const std::pair<bool, const char*> table_only[] = {
        {o.acceleration_gain != d.acceleration_gain, "acceleration_gain"},
        {o.noise_u != d.noise_u, "noise_u"},
        {o.accel_noise_density != d.accel_noise_density, "accel_noise_density"},
        {o.accel_bandwidth != d.accel_bandwidth, "accel_bandwidth"},
        {o.accel_baseline != d.accel_baseline, "accel_baseline"},
        {o.no_accelerometer, "no_accelerometer"}};
    for (const auto& [set, field] : table_only) refuse(set && !table, field, "`controller` table");
    for (const auto& [set, field] : table_only) {
        if (std::string_view(field).starts_with("accel") || std::string_view(field) == "acceleration_gain")
            refuse(set && o.no_accelerometer, field, "the accelerometers (not `no_accelerometer`)");
    }
    refuse(o.noise_pose != d.noise_pose && table, "noise_pose", "`controller` pose");
    refuse(o.noise_rate != d.noise_rate && table, "noise_rate", "`controller` pose");
    refuse(o.accuracy != d.accuracy && o.plant != PlantKind::simbody, "accuracy", "`plant` simbody");
}

/// A suite's settings on a single record are refused, naming what they go with. The goals
/// (max_rms_percent and the like) apply to one record too: its verdict is judged against them.
void refuseSuiteOptions(const ShakeOptions& o) {
    const ShakeOptions d;
    const std::pair<bool, const char*> suite_only[] = {{o.threads != d.threads, "threads"}};
    for (const auto& [set, field] : suite_only) {
        if (set)
            throw OptionError(field,
                              "does not apply to one record: it goes with a suite (`record` repeated, or "
                              "a folder of records)");
    }
}

}  // namespace

void validate(const ShakeOptions& o) {
    if (o.record.empty()) throw OptionError("record", "at least one AT2 record is required");
    if (o.axis == ShakeAxis::y && !o.record_y.empty())
        throw OptionError("record_y", "the record already drives y (`axis` y): give the x record as `record`");
    requireIn(o.highpass, kHighpassRange, "highpass");
    requireIn(o.margin, kShareRange, "margin");
    requireIn(o.window, kWindowRange, "window");
    if (o.rate) requireIn(*o.rate, kShakeRateRange, "rate");
    if (o.natural_frequency) requireIn(*o.natural_frequency, kShakeNaturalFrequencyRange, "natural_frequency");
    requireIn(o.acceleration_gain, kShareRange, "acceleration_gain");
    requireIn(o.noise_u, kEncoderNoiseRange, "noise_u");
    requireIn(o.accel_noise_density, kAccelNoiseDensityRange, "accel_noise_density");
    requireIn(o.accel_bandwidth, kAccelBandwidthRange, "accel_bandwidth");
    requireIn(o.accel_baseline, kAccelBaselineRange, "accel_baseline");
    requireIn(o.amplitude, kAmplitudeRange, "amplitude");
    requireCount(o.iterations, kMaxIterations, "iterations");
    requireIn(o.iteration_gain, kIterationGainRange, "iteration_gain");
    requireIn(o.iteration_tolerance, kIterationToleranceRange, "iteration_tolerance");
    if (o.drive_model != DriveModel::identity && o.controller != ShakeController::table)
        throw OptionError("drive_model", std::string(name(o.drive_model)) +
                                             " inverts the table controller's closed loop: needs controller table");
    if (o.drive_specimen && o.drive_model == DriveModel::identity)
        throw OptionError("drive_specimen", "goes with `drive_model` exact or difference");
    requireIn(o.excitation_duration, kExcitationDurationRange, "excitation_duration");
    requireCount(o.threads, kMaxThreads, "threads");
    requireIn(o.max_rms_percent, kErrorPercentRange, "max_rms_percent");
    requireIn(o.max_peak_percent, kErrorPercentRange, "max_peak_percent");
    requireIn(o.min_spectrum_percent, kPercentRange, "min_spectrum_percent");
    requireIn(o.payload_mass, kPayloadMassRange, "payload_mass");
    requireIn(o.noise_pose, kNoisePoseRange, "noise_pose");
    requireIn(o.noise_rate, kNoiseRateRange, "noise_rate");
    requireIn(o.accuracy, kAccuracyRange, "accuracy");
    if (o.x_azimuth) requireIn(*o.x_azimuth, kAzimuthRange, "x_azimuth");
    if (o.identify_payload && o.controller != ShakeController::table)
        throw OptionError("identify_payload", "needs `controller` table");
    refuseWhatDoesNotApply(o);
}

ShakeResult runShake(const ShakeOptions& options, Observer& observer, FileSink& files) {
    validate(options);
    requireOutputFolder(options.out_dir, "out_dir");
    if (isSpatialRobot(options.robot)) {
        ShakeOptions six = options;
        six.record = expandRecords(options.record);          // a folder's *.AT2 files
        six.time_scale = replayOptions(options).time_scale;  // "auto" or L, read as for a planar table
        return runSpatialShake(six, observer, files);
    }
    if (options.per_axis_scale)
        throw OptionError("per_axis_scale", "goes with a six-DOF table (a spatial robot with motion: full)");
    const RobotDescription robot = loadRobot(options.robot);
    if (robot.motion == PlatformMotion::translation) {
        // a two-DOF table moves its tool point in x, y: no rotation to drive or to sense
        if (!options.record_theta.empty())
            throw OptionError("record_theta",
                              "a two-DOF robot (motion: translation, pose [x, y]) has no theta to drive");
        if (options.accel_baseline != ShakeOptions{}.accel_baseline) {
            throw OptionError("accel_baseline",
                              "a two-DOF robot (motion: translation, pose [x, y]) has no angular acceleration to "
                              "sense: there is no accelerometer pair");
        }
        if (options.identify_payload) {
            throw OptionError("identify_payload",
                              "not for a two-DOF robot (motion: translation, pose [x, y]) yet: the payload "
                              "identification estimates a platform's mass, c.o.m. and inertia from motions in x, y "
                              "and theta");
        }
        if (options.drive_model != DriveModel::identity) {
            throw OptionError("drive_model", std::string(name(options.drive_model)) +
                                                 ": not for a two-DOF robot (motion: translation, pose [x, y]) yet: "
                                                 "the table's closed loop is linearised over theta, x and y; "
                                                 "iterate with drive_model identity");
        }
    }
    if (const std::string rigid = rigidPlantWarning(robot, "shake"); !rigid.empty()) observer.warning(rigid);
    const ShakeReplayOptions replay = replayOptions(options);
    const std::vector<RecordFiles> records = groupRecordFiles(expandRecords(options.record));
    if (records.size() > 1) {
        if (!options.record_y.empty() || !options.record_theta.empty())
            throw OptionError("record_y", "record_y and record_theta go with a single record");
        return runSuite(records, options, replay, robot, observer, files);
    }
    refuseSuiteOptions(options);
    GroundRecord record;
    if (records.front().files.size() > 1) {
        // the components of one record: its horizontals drive x and y
        if (!options.record_y.empty())
            throw OptionError("record_y", records.front().label + ": " + kComponentsDriveBoth);
        if (options.axis == ShakeAxis::y)
            throw OptionError("axis", records.front().label + ": " + kComponentsDriveBoth);
        std::vector<std::string> notes;
        record = readComponents(records.front(), options.window, notes, options.x_azimuth);
        for (const std::string& note : notes) observer.warning(note);
    } else {
        recordTarget(record, options) = readAxis(records.front().label, options.window, record.dt, false);
    }
    if (!options.record_y.empty()) record.ay = readAxis(options.record_y, options.window, record.dt, false);
    if (!options.record_theta.empty()) record.alpha = readAxis(options.record_theta, options.window, record.dt, true);
    // the shortest driven axis (records of one event may differ by a few samples)
    std::size_t n = recordTarget(record, options).size();
    for (const auto* a : {&record.ax, &record.ay, &record.alpha}) {
        if (!a->empty()) n = std::min(n, a->size());
    }
    for (auto* a : {&record.ax, &record.ay, &record.alpha}) {
        if (!a->empty()) a->resize(n);
    }
    // the length of the replay is known only once fitted: progress in seconds of motion
    Meter meter(observer, 0.0, "s");
    const ShakeOutcome outcome =
        runShakeReplay(robot, record, replay, plantFactory(options), [&meter](double t) { meter(t); });
    const Model model(robot);
    ShakeResult out;
    out.table = shakeTable(outcome, model);
    out.metrics_json = shakeJson(outcome);
    std::ostringstream text;
    printShakeSummary(outcome, text);
    // the verdict against the suite's goals, as a suite's row would give it
    ShakeSuiteRow row = scoreRow(outcome, options);
    row.record = records.front().label;
    text << verdictLine(row, options);
    out.passed = row.pass ? 1 : 0;
    out.rows.push_back(std::move(row));
    out.text = text.str();
    if (!options.out_dir.empty()) shakeFiles(outcome, model, "", robot.name + ": " + records.front().label, files);
    return out;
}

}  // namespace nocdyn::app
