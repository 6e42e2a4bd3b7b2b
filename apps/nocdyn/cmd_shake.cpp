// nocdyn shake: play a ground-motion record (PEER AT2) on a robot within its limits and score
// the reproduction (shake_replay.hpp).
#include <algorithm>
#include <atomic>
#include <charconv>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/layouts.hpp"
#include "plants.hpp"
#include "progress.hpp"
#include "shake_replay.hpp"

namespace nocdyn::cli {

namespace {

struct ShakeOptions {
    std::string robot, record_y, record_theta, time_scale = "auto", out = "shake";
    std::vector<std::string> records;
    double window = 0.0;
    std::optional<double> natural_frequency;
    double accel_density_ug = 22.5;  ///< [ug/sqrt(Hz)]
    bool no_accelerometer = false;
    unsigned jobs = 0;
    double max_rms = 0.05, max_peak = 0.05, min_spectrum = 0.95;
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

/// The records named: files, and the *.AT2 files of folders (sorted by name).
std::vector<std::string> expandRecords(const std::vector<std::string>& names) {
    std::vector<std::string> out;
    for (const std::string& name : names) {
        std::error_code error;
        if (!std::filesystem::is_directory(name, error)) {
            out.push_back(name);
            continue;
        }
        std::vector<std::string> found;
        for (const auto& entry : std::filesystem::directory_iterator(name, error)) {
            std::string ext = entry.path().extension().string();
            for (char& c : ext) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
            if (entry.is_regular_file() && ext == ".AT2") found.push_back(entry.path().string());
        }
        if (error) throw Error("--record " + name + ": cannot list the folder: " + error.message());
        if (found.empty()) throw Error("--record " + name + ": the folder holds no .AT2 file");
        std::sort(found.begin(), found.end());
        out.insert(out.end(), found.begin(), found.end());
    }
    return out;
}

/// One folder name per record, safe and unique: the record's stem with every character but
/// letters, digits, '-' and '_' replaced by '_' (no separator, no "." or ".." and no hidden
/// folder), "record" when nothing is left, and "-2", "-3", ... after a name already taken
/// ignoring case (quake.AT2 and quake.at2 must not share a folder on any file system).
std::vector<std::string> recordFolders(const std::vector<std::string>& records) {
    std::vector<std::string> out, taken;
    for (const std::string& record : records) {
        std::string name = std::filesystem::path(record).stem().string();
        bool any = false;
        for (char& c : name) {
            const bool plain = std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_';
            if (!plain) c = '_';
            any = any || std::isalnum(static_cast<unsigned char>(c)) != 0;
        }
        if (!any) name = "record";
        if (name.size() > 100) name.resize(100);
        const auto lower = [](std::string text) {
            for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            return text;
        };
        std::string chosen = name;
        for (int k = 2; std::find(taken.begin(), taken.end(), lower(chosen)) != taken.end(); ++k)
            chosen = name + "-" + std::to_string(k);
        taken.push_back(lower(chosen));
        out.push_back(chosen);
    }
    return out;
}

struct SuiteRow {
    std::string record, folder;
    ShakeOutcome outcome;
    std::string error;
};

/// One row of the suite's table, and whether it passes.
bool suiteLine(const SuiteRow& row, const ShakeOptions& options, std::string& line) {
    const ShakeOutcome& o = row.outcome;
    const ShakeScore& s = o.score[1];
    const double within = 1.0 - s.share_outside;
    const bool pass = s.rms_error <= options.max_rms && std::abs(s.peak_error) <= options.max_peak &&
                      within >= options.min_spectrum && o.achieved_use.ratio <= 1.0;
    char numbers[512];
    std::snprintf(numbers, sizeof numbers, " %.4g | %.4g%s | %.2f %% | %+.2f %% | %.0f %% | %.0f %% (%s) | %s |",
                  o.fit.time_scale, o.fit.amplitude_scale * o.amplitude, o.amplitude != 1.0 ? " (asked)" : "",
                  100.0 * s.rms_error, 100.0 * s.peak_error, 100.0 * within, 100.0 * o.achieved_use.ratio,
                  o.achieved_use.what.c_str(), pass ? "pass" : "FAIL");
    // the names through the Markdown escaper: a file name cannot forge a row or carry HTML
    line = "| " + io::markdownText(std::filesystem::path(row.record).filename().string()) + " | " +
           io::markdownText(row.folder) + " |" + numbers;
    return pass;
}

void runSuite(const std::vector<std::string>& records, const ShakeOptions& options, const RobotDescription& robot) {
    std::vector<SuiteRow> rows(records.size());
    std::vector<GroundRecord> inputs(records.size());
    const std::vector<std::string> folders = recordFolders(records);
    // every record read (and refused) before any replay
    for (std::size_t i = 0; i < records.size(); ++i) {
        rows[i].record = records[i];
        rows[i].folder = folders[i];
        inputs[i].ax = readAxis(records[i], options.window, inputs[i].dt, false);
    }
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const auto workers =
        static_cast<std::size_t>(std::min<std::size_t>(options.jobs > 0 ? options.jobs : cores, records.size()));
    std::atomic<std::size_t> next{0};
    std::mutex output;
    const auto work = [&] {
        for (std::size_t i = next++; i < records.size(); i = next++) {
            try {
                rows[i].outcome = runShake(robot, inputs[i], options.settings);
                const std::lock_guard lock(output);
                writeShakeOutputs(rows[i].outcome, Model(robot),
                                  (std::filesystem::path(options.out) / folders[i]).string(),
                                  robot.name + ": " + records[i]);
                rows[i].outcome.loop = {};  // the ticks are written; keep the scores
                rows[i].outcome.achieved = {};
            } catch (const std::exception& e) {
                rows[i].error = e.what();
            }
        }
    };
    std::vector<std::thread> pool;
    for (std::size_t w = 0; w + 1 < workers; ++w) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    for (const SuiteRow& row : rows) {
        if (!row.error.empty()) throw Error(row.record + ": " + row.error);
    }
    std::ostringstream table;
    char head[512];
    std::snprintf(head, sizeof head,
                  "%zu records on %s, controller %s, %zu at a time; pass: RMS <= %.3g %%, |peak| <= %.3g %%, "
                  "spectrum within +-10 %% at >= %.3g %% of the counted periods, every limit <= 100 %%\n\n",
                  records.size(), options.settings.plant.c_str(), options.settings.controller.c_str(), workers,
                  100.0 * options.max_rms, 100.0 * options.max_peak, 100.0 * options.min_spectrum);
    table
        << head << "sensors: " << rows.front().outcome.sensing << "\n\n"
        << "| record | folder | L | A | RMS error | peak error | spectrum within +-10 % | worst limit use (binding) | "
           "result |\n|---|---|---|---|---|---|---|---|---|\n";
    int passed = 0;
    for (const SuiteRow& row : rows) {
        std::string line;
        passed += suiteLine(row, options, line) ? 1 : 0;
        table << line << "\n";
    }
    table << "\n" << passed << " of " << rows.size() << " records pass\n";
    io::writeTextFile((std::filesystem::path(options.out) / "summary.md").string(), table.str());
    std::cout << table.str() << "wrote " << io::terminalText(options.out) << "/summary.md and one folder per record\n";
}

void run(ShakeOptions options) {
    const RobotDescription robot = loadRobotDescriptionOrDefault(options.robot);
    if (options.time_scale != "auto") {
        // a decimal number only (std::stod would read 0x10 as 16, and nan or inf)
        double value = 0.0;
        const std::string& text = options.time_scale;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || error != std::errc{} || end != text.data() + text.size() ||
            !(value >= 1e-3 && value <= 1e4)) {
            throw Error("--time-scale: expected auto or a decimal number from 0.001 to 10000, got '" +
                        io::terminalText(text) + "'");
        }
        options.settings.fit.time_scale = value;
    }
    ShakeSettings& settings = options.settings;
    const bool table = settings.controller == "table";
    if (options.natural_frequency) {
        (table ? settings.table.natural_frequency : settings.natural_frequency) = *options.natural_frequency;
    } else if (table && settings.identify_payload) {
        settings.table.natural_frequency = 2.0;  // the model carries the payload: the feedback holds the drift only
    }
    settings.table.sensors.accel_noise_density = options.accel_density_ug * 1e-6 * kGravity;
    settings.table.sensors.accelerometer = !options.no_accelerometer;
    settings.table.seed = settings.seed;
    if (settings.identify_payload && !table) throw Error("--identify-payload needs --controller table");
    const std::vector<std::string> records = expandRecords(options.records);
    if (records.size() > 1) {
        if (!options.record_y.empty() || !options.record_theta.empty()) {
            throw Error("--record-y and --record-theta go with a single --record");
        }
        runSuite(records, options, robot);
        return;
    }
    GroundRecord record;
    record.ax = readAxis(records.front(), options.window, record.dt, false);
    if (!options.record_y.empty()) record.ay = readAxis(options.record_y, options.window, record.dt, false);
    if (!options.record_theta.empty()) record.alpha = readAxis(options.record_theta, options.window, record.dt, true);
    const std::size_t n = std::min({record.ax.size(), record.ay.empty() ? record.ax.size() : record.ay.size(),
                                    record.alpha.empty() ? record.ax.size() : record.alpha.size()});
    for (auto* a : {&record.ax, &record.ay, &record.alpha}) {
        if (!a->empty()) a->resize(n);  // records of one event may differ by a few samples
    }
    // one progress line every few seconds on standard error (the Simbody plant takes minutes)
    Heartbeat heartbeat("nocdyn shake");
    settings.table.progress = [&heartbeat](double t) { heartbeat.at(t); };
    const ShakeOutcome outcome = runShake(robot, record, settings);
    heartbeat.finish();
    writeShakeOutputs(outcome, Model(robot), options.out, robot.name + ": " + records.front());
    printShakeSummary(outcome, std::cout);
    std::cout << "wrote " << io::terminalText(options.out) << "/shake.csv, shake.json, shake_acceleration.{png,svg}, "
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
        "(inverse dynamics of the fitted motion), else the amplitude is scaled down. The motion is then played on\n"
        "the plant carrying a payload the controller does not know, measured as a shake table measures it:\n"
        "encoders and platform accelerometers fused by a Kalman estimator, model feed-forward with low-gain pose\n"
        "feedback (--controller table; docs/earthquake-replay.md); optionally the payload identified first and the\n"
        "drive iterated.\n"
        "Writes DIR/shake.csv (" +
            io::columnList(io::TableId::shake) +
            "),\n"
            "DIR/shake.json (time_scale, amplitude_scale, metrics: RMS and peak acceleration errors, 5 %-damped\n"
            "pseudo-acceleration spectra) and figures DIR/shake_acceleration.{png,svg}, DIR/shake_spectrum.{png,svg}\n"
            "(DIR: --out-dir). The default plant is nocdyn-rk4 (a 40 s record in seconds); --plant simbody replays\n"
            "on the independent Simbody model, about 70 times slower, as a check.");
    addRobotOption(*command, options->robot);
    command
        ->add_option("--record", options->records,
                     "AT2 record driving x (values in g); repeat it, or name a folder (its *.AT2 files), for a suite: "
                     "one folder of outputs per record under --out-dir, the records in parallel, one summary table "
                     "(DIR/summary.md)")
        ->required()
        ->check(CLI::ExistingPath);
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
    command
        ->add_option("--controller", options->settings.controller,
                     "table (encoders and platform accelerometers fused by a Kalman filter, model feed-forward, "
                     "low-gain pose feedback, acceleration correction) or pose (computed torque on a noisy pose and "
                     "rate sensor, --noise-pose, --noise-rate)")
        ->check(CLI::IsMember({"table", "pose"}))
        ->capture_default_str();
    command
        ->add_option("--natural-frequency", options->natural_frequency,
                     "f_n of the pose feedback [Hz] (default: table 6, or 2 with --identify-payload; pose 30)")
        ->check(CLI::Range(0.1, 1e4));
    command
        ->add_option("--acceleration-gain", options->settings.table.acceleration_gain,
                     "table: gain g per tick of the acceleration correction (bandwidth about g rate / 2 pi)")
        ->check(CLI::Range(0.0, 0.9))
        ->capture_default_str();
    command
        ->add_option("--encoder-noise", options->settings.table.sensors.encoder_noise,
                     "table: std. dev. of each actuator encoder [m or rad]")
        ->check(CLI::Range(1e-12, 1.0))
        ->capture_default_str();
    command
        ->add_option("--accel-noise-density", options->accel_density_ug,
                     "table: accelerometer noise density [ug/sqrt(Hz)] (ADXL355: 22.5)")
        ->check(CLI::Range(0.0, 1e6))
        ->capture_default_str();
    command
        ->add_option("--accel-bandwidth", options->settings.table.sensors.accel_bandwidth,
                     "table: accelerometer bandwidth, a first-order low-pass [Hz] (ADXL355 at 4 kHz ODR: 1000)")
        ->check(CLI::Range(1.0, 1e5))
        ->capture_default_str();
    command
        ->add_option("--accel-baseline", options->settings.table.sensors.accel_baseline,
                     "table: distance of the two accelerometers that give the angular acceleration [m]")
        ->check(CLI::Range(1e-3, 10.0))
        ->capture_default_str();
    command->add_flag("--no-accelerometer", options->no_accelerometer,
                      "table: encoders only (no acceleration correction)");
    command
        ->add_option("--amplitude", options->settings.amplitude,
                     "Multiply the record's accelerations by this before the fit (a weak record raised above the "
                     "sensor noise; the output says so)")
        ->check(CLI::Range(1e-3, 1e3))
        ->capture_default_str();
    command->add_flag("--identify-payload", options->settings.identify_payload,
                      "table: identify the payload first (an excitation designed for it, played within the limits, "
                      "then least squares) and replay with it in the controller's model");
    command
        ->add_option("--iterations", options->settings.iterations,
                     "Drive-signal iteration: at most N passes after the first, each correcting the drive by "
                     "--iteration-gain times the last pass's acceleration error; stops when a pass improves the RMS "
                     "error by less than 2 % or its drive would leave the limits; the best pass is kept")
        ->check(CLI::Range(0, 20))
        ->capture_default_str();
    command->add_option("--iteration-gain", options->settings.iteration_gain, "Drive-signal iteration gain")
        ->check(CLI::Range(0.01, 1.0))
        ->capture_default_str();
    command
        ->add_option("--excitation-duration", options->settings.excitation_duration,
                     "--identify-payload: length of the excitation [s] (whole periods of its 5 Hz base)")
        ->check(CLI::Range(0.2, 600.0))
        ->capture_default_str();
    command->add_option("--jobs", options->jobs, "Suite: records played at once (0: one per core)")
        ->check(CLI::Range(0u, 256u))
        ->capture_default_str();
    command->add_option("--max-rms", options->max_rms, "Suite: pass when the RMS error is at most this (share)")
        ->check(CLI::Range(0.0, 10.0))
        ->capture_default_str();
    command->add_option("--max-peak", options->max_peak, "Suite: pass when |peak error| is at most this (share)")
        ->check(CLI::Range(0.0, 10.0))
        ->capture_default_str();
    command
        ->add_option("--min-spectrum", options->min_spectrum,
                     "Suite: pass when at least this share of the counted periods is within +-10 %")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    command->add_option("--payload-mass", options->settings.payload.mass, "Mass on the plant's platform only [kg]")
        ->check(CLI::Range(0.0, 1e4))
        ->capture_default_str();
    command->add_option("--noise-pose", options->settings.noise_pose, "pose: std. dev. of the pose noise [m, rad]")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    command->add_option("--noise-rate", options->settings.noise_rate, "pose: std. dev. of the rate noise [m/s, rad/s]")
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
