// `identify`: a payload's mass, c.o.m. and inertia (or the robot's base parameters) from a log
// of actuator positions and forces (sim/identification.hpp), with the report printed as YAML and
// the file written: the robot with the payload merged, or the calibration.
#pragma once

#include <optional>
#include <string>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/sim/identification.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

inline constexpr Range kCutoffRange{1e-3, 1e6, "Hz"};
inline constexpr Range kHoldoutRange{0.0, 0.9, ""};

/// The fit's settings (cutoff, holdout, friction, held_forces) are the library's.
struct IdentifyOptions : IdentificationSettings {
    RobotSource robot;
    /// The log: CSV t,u1..un with tau1..taun (forces at each sample) or tau1_held..taun_held
    /// (and du1..dun, ddu1..ddun when known). With data_table: the log's name in messages.
    std::string data;
    /// The same log given in code (Python): used instead of the file when set.
    std::optional<io::Table> data_table;
    bool payload = false;     ///< identify a payload (the default when base is not given)
    bool base = false;        ///< identify the robot's base parameters instead
    std::string calibration;  ///< payload: a calibration file (identify base's output)
    std::string prior;        ///< payload: bounds on its parameters (YAML)
    /// The same bounds given in code (Python): used instead of the file when set.
    std::optional<PayloadPrior> prior_bounds;
};

/// Throws OptionError naming the field of a value out of range or options that do not go together.
void validate(const IdentifyOptions& options);

struct IdentifyResult {
    /// The report printed (YAML with # comments): fit, payload or base parameters.
    std::string text;
    /// The file: the robot with the payload merged into the platform, or the calibration.
    std::string yaml;
    std::optional<PayloadResult> payload;
    std::optional<BaseResult> base;
    /// Measured against predicted forces on the held-out samples, one panel per actuator.
    render::Figure figure;
};

/// The measurements of a log (named columns, time increasing; errors name file, line, column).
[[nodiscard]] Measurements readMeasurements(const std::string& path, int actuators);

/// The measurements of a log's table, read from `source` (errors name it, and the line of a
/// row read from a file, else the row's number from 1); every value must be finite.
[[nodiscard]] Measurements measurementsOf(const io::Table& table, const std::string& source, int actuators);

/// Reads, reconstructs the motion, solves (three steps through the observer). Writes no file:
/// the front ends write `yaml` and render `figure` where their caller asks.
IdentifyResult runIdentify(const IdentifyOptions& options, Observer& observer);

}  // namespace nocdyn::app
