// `shake`: a ground-motion record (PEER AT2) fitted to a robot by similitude and played on a
// plant with an unknown payload (nocdyn/sim/shake_replay.hpp); one record, or a suite of records
// played in parallel and scored against pass thresholds. Every error is in percent, with
// "_percent" in its name (options, shake.json, the text and the suite's table alike).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "app/outputs.hpp"
#include "nocdyn/choice.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/sim/shake_replay.hpp"

namespace nocdyn::app {

inline constexpr Range kHighpassRange{0.0, 1e3, "Hz"};
inline constexpr Range kShareRange{0.0, 0.9, ""};  // margin, acceleration gain
inline constexpr Range kWindowRange{0.0, 1e5, "s"};
inline constexpr Range kEncoderNoiseRange{1e-12, 1.0, "m or rad"};
inline constexpr Range kAccelNoiseDensityRange{0.0, 1e6, "ug/sqrt(Hz)"};
inline constexpr Range kAccelBandwidthRange{1.0, 1e5, "Hz"};
inline constexpr Range kAccelBaselineRange{1e-3, 10.0, "m"};
inline constexpr Range kAmplitudeRange{1e-3, 1e3, ""};
inline constexpr Range kAzimuthRange{-360.0, 360.0, "deg"};
inline constexpr Range kIterationGainRange{0.01, 1.0, ""};
inline constexpr Range kIterationToleranceRange{0.0, 0.9, ""};
inline constexpr Range kExcitationDurationRange{0.2, 600.0, "s"};
inline constexpr Range kErrorPercentRange{0.0, 1000.0, "%"};
inline constexpr Range kPercentRange{0.0, 100.0, "%"};
inline constexpr Range kNoisePoseRange{0.0, 1.0, "m, rad"};
inline constexpr Range kNoiseRateRange{0.0, 1e3, "m/s, rad/s"};
inline constexpr Range kAccuracyRange{1e-14, 1e-3, ""};
inline constexpr int kMaxIterations = 20;
inline constexpr unsigned kMaxThreads = 256;

/// The pose axis a single record drives (and is scored on).
enum class ShakeAxis { x, y };

inline constexpr std::array<Choice<ShakeAxis>, 2> kShakeAxes{{{ShakeAxis::x, "x"}, {ShakeAxis::y, "y"}}};
[[nodiscard]] constexpr std::span<const Choice<ShakeAxis>> choices(ShakeAxis) { return kShakeAxes; }

/// The replay's choices (ShakeReplayOptions: fit, plant, controller, sensors, payload, drive
/// iteration, with their defaults) and the command's own: the records, the window, the suite's
/// workers and goals, the output folder.
struct ShakeOptions : ShakeReplayOptions {
    RobotSource robot;
    /// AT2 records driving `axis` (values in g); several, or a folder (its *.AT2 files): a suite.
    std::vector<std::string> record;
    /// The pose axis `record` drives: x (the default) or y (then `record_y` is not given).
    ShakeAxis axis = ShakeAxis::x;
    std::string record_y;      ///< AT2 record driving y (values in g), same time step
    std::string record_theta;  ///< AT2-format file driving theta, values in rad/s^2
    /// The time scale as a user writes it (the command line's and Python's `time_scale`): "auto"
    /// (time_scale as set, by default the least compression L >= 1 that fits) or a decimal L in
    /// [0.001, 10000], which runShake puts in time_scale.
    std::string time_scale_text = "auto";
    double window = 0.0;  ///< [s] of the record played; 0: all
    /// A record given as its components: the table's x azimuth [deg, clockwise from north];
    /// none: the first horizontal's (io::combineComponents).
    std::optional<double> x_azimuth;
    /// A six-DOF table: each axis scaled to its own limit (then the three by one factor), not
    /// one amplitude scale for all three.
    bool per_axis_scale = false;
    unsigned threads = 0;           ///< suite: records at once (0: one per core)
    double max_rms_percent = 5.0;   ///< suite: pass at an RMS error of at most this [%]
    double max_peak_percent = 5.0;  ///< suite: pass at |peak error| of at most this [%]
    /// suite: pass when at least this percentage of the counted periods is within +-10 %
    double min_spectrum_percent = 95.0;
    /// Where the files go (shake.csv, shake.json, figures; a suite: summary.md and one folder per
    /// record); empty: nothing written (a suite needs one).
    std::string out_dir;
};

/// Throws OptionError naming the field of the first value out of its range.
void validate(const ShakeOptions& options);

/// One record of a suite.
struct ShakeSuiteRow {
    std::string record, folder;
    double time_scale = 1.0, amplitude = 1.0;  ///< L, and A times the asked amplitude
    bool amplitude_asked = false;
    double rms_error_percent = 0.0, peak_error_percent = 0.0, within_percent = 0.0;
    double limit_use_percent = 0.0;
    std::string binding;  ///< the limit used most
    bool pass = false;
};

struct ShakeResult {
    bool suite = false;
    /// One record: shake.csv's table, shake.json's text and the summary printed.
    io::Table table;
    std::string metrics_json;
    std::string text;
    bool animation = false;  ///< shake_animation.html written too (a six-DOF table's replay in 3-D)
    /// A suite: every record's row, summary.md's text, the number of workers. One record: its
    /// row (the verdict against the same goals, also the text's last line). Every row is scored
    /// on `axis`.
    std::vector<ShakeSuiteRow> rows;
    int passed = 0;
};

/// Reads the records (every one before any replay), plays them, scores them; when options.out_dir
/// is given, hands each record's files to `files` as the record finishes (a suite: one folder
/// per record, then summary.md), so that a long suite's finished records survive a stop; the
/// front ends pass an OutputFolder of out_dir (app/outputs.hpp). A suite plays its records on
/// `threads` threads; progress (records done) and a stop are handled on the calling thread, a
/// stop ending every replay at its next tick.
ShakeResult runShake(const ShakeOptions& options, Observer& observer, FileSink& files);

}  // namespace nocdyn::app
