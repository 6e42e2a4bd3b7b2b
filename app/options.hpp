// What the options of several commands share, for the command line and Python alike: the robot
// (a file, its parameter overrides, or a robot built in code), the sampling of a trajectory, the
// accepted range of a number, and the error naming the option a value breaks.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "nocdyn/description.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn {
class Model;
}

namespace nocdyn::app {

/// A value outside what an option accepts. field() is the option's name in the options struct
/// ("rate", "allow_limits"): the command line shows it as --rate, Python as rate. Another option
/// named in the message is written between backquotes (`iterations`): the command line shows it
/// as --iterations, what() (Python) as iterations.
class OptionError : public Error {
public:
    OptionError(std::string field, const std::string& message)
        : Error(field + ": " + withoutQuotes(message)), field_(std::move(field)), message_(message) {}
    [[nodiscard]] const std::string& field() const { return field_; }
    /// The message without the option's name.
    [[nodiscard]] const std::string& message() const { return message_; }

private:
    static std::string withoutQuotes(std::string text) {
        std::erase(text, '`');
        return text;
    }
    std::string field_, message_;
};

/// The closed interval a number option accepts, with its unit; nan and inf are never accepted.
struct Range {
    double lo, hi;
    const char* unit;
};

/// Throws OptionError(field, ...) unless `value` is finite and in `range`.
void requireIn(double value, const Range& range, const std::string& field);

/// Sampling ranges shared by the trajectory-driven commands.
inline constexpr Range kRateRange{1.0, 1e8, "Hz"};
inline constexpr Range kDurationRange{1e-6, 1e6, "s"};
/// Positions a user gives (pose, forward kinematics): far beyond any planar robot's size.
inline constexpr Range kAngleRange{-1e6, 1e6, "rad"};
inline constexpr Range kLengthRange{-1e3, 1e3, "m"};
/// The shake-table loop (shake, frequency-response's closed loop): its controller's tick rate
/// and its pose feedback's natural frequency.
inline constexpr Range kShakeRateRange{100.0, 1e6, "Hz"};
inline constexpr Range kShakeNaturalFrequencyRange{0.1, 1e4, "Hz"};
/// A payload added to a robot (shake, control, frequency-response, excite's guess): its mass, and
/// its inertia about its centre of mass.
inline constexpr Range kPayloadMassRange{0.0, 1e4, "kg"};
inline constexpr Range kPayloadInertiaRange{0.0, 1e6, "kg m^2"};

/// The robot a command works on.
struct RobotSource {
    /// A robot file (YAML, either form); empty: the paper's prototype (robots/paper-3prr.yaml).
    std::string path;
    /// NAME=VALUE overrides of parameters the file declares (a later one for a name wins).
    io::ParameterSet set;
    /// A robot built in code (Python's nocdyn.Robot): used instead of `path` when given.
    std::optional<RobotDescription> description;
};

/// The robot a source names, with its overrides: a three-DOF robot or a two-DOF one (motion:
/// translation), which every command takes. Throws nocdyn::Error for a bad file, and
/// OptionError("set") for overrides of the built-in prototype or of a robot built in code.
[[nodiscard]] RobotDescription loadRobot(const RobotSource& source);

/// The warning of a command whose plant is the rigid robot (simulate, control, shake) when the
/// robot file declares compliance that the plant leaves out; empty when it declares none.
[[nodiscard]] std::string rigidPlantWarning(const RobotDescription& robot, const std::string& command);

/// Adds NAME=VALUE to a parameter set (a later one for the same name replaces the earlier).
void addOverride(io::ParameterSet& set, const io::Parameter& parameter);

/// How a trajectory-driven command samples its trajectory.
struct SamplingOptions {
    /// paper1, paper2 (eqs. 33-34), a trajectory file (YAML, harmonics) or samples (.csv).
    std::string trajectory;
    /// A trajectory built in code (Python's nocdyn.Trajectory): used instead of `trajectory` when given.
    std::optional<PoseTrajectory> given_trajectory;
    /// Seconds to sample; empty: the trajectory's own duration, else 0.2 s.
    std::optional<double> duration;
    /// Samples per second.
    double rate = 10000.0;
};

/// Checks duration and rate against their ranges (OptionError naming the field).
void validate(const SamplingOptions& options);

/// The trajectory to sample: the one given in code, else the one `trajectory` names.
[[nodiscard]] PoseTrajectory trajectoryOf(const SamplingOptions& options);

/// `trajectory` as `model` moves along it: unchanged for a three-DOF robot; for a two-DOF robot
/// (motion: translation, pose [x, y]) a trajectory keyed x, y, its theta held at home(0) = 0.
/// Throws nocdyn::Error "trajectory 'SOURCE': theta: ..." for a theta axis that is not 0 throughout
/// (a YAML key theta, a CSV column theta or alpha): such a robot has no platform rotation. SOURCE
/// is `source` (the file or name given), else the trajectory's name.
[[nodiscard]] PoseTrajectory trajectoryFor(const Model& model, PoseTrajectory trajectory,
                                           const std::string& source = "");

/// The duration asked for, else the trajectory's own, else 0.2 s.
[[nodiscard]] double chooseDuration(const std::optional<double>& requested, const PoseTrajectory& trajectory);

}  // namespace nocdyn::app
