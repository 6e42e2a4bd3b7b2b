// What several sub-commands share: loading the robot and trajectory named on the command
// line, choosing the sampling, writing a table to a file or stdout.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>

#include "app/options.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/description.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::report {}  // namespace nocdyn::report

namespace nocdyn::cli {

/// The commands draw figures, pages and replays with the report module's functions.
using namespace nocdyn::report;

/// Accepted ranges of the sampling options (README, "Command line").
inline constexpr double kMinRate = 1.0, kMaxRate = 1e8;           // --rate [Hz]
inline constexpr double kMinDuration = 1e-6, kMaxDuration = 1e6;  // --duration [s]
/// simulate and control integrate over time and hold every output sample in memory.
inline constexpr double kMaxSimulatedDuration = 1e3;  // [s]
inline constexpr double kMaxSimulatedSamples = 1e7;

/// Options every trajectory-driven command takes.
struct TrajectoryOptions {
    std::string trajectory;
    std::string robot;
    std::optional<double> duration;
    double rate = 10000.0;
    std::string output;
};

/// A CLI11 check: the argument is a finite decimal number in [lo, hi] (unit named in the
/// message, e.g. "Hz"); nan, inf and hex are refused. Any failure exits with status 2.
[[nodiscard]] CLI::Validator finiteIn(double lo, double hi, const std::string& unit);

/// finiteIn over an option's range as the application layer states it.
[[nodiscard]] inline CLI::Validator within(const app::Range& range) { return finiteIn(range.lo, range.hi, range.unit); }

/// A CLI11 check: the argument is a finite decimal number; nan, inf and hex are refused.
[[nodiscard]] CLI::Validator finiteNumber();

/// The one rule for floating options: every FLOAT option of every command of `app` refuses
/// nan, inf and hexadecimal (no option gives them a meaning).
void requireFiniteFloats(CLI::App& app);

/// Refuses (nocdyn::Error) a command whose output would replace one of its inputs: an output
/// file (-o, --log, --png, --svg, --figure's STEM.png and STEM.svg) that is an input file
/// (--robot, --trajectory, --record, ... the same file by inode, through any path or link), or
/// an input file of a kind the command writes (.csv .json .md .png .svg .html) inside its output
/// folder (--out-dir), or an input folder that is the output folder. Called for every command
/// once parsed.
void refuseOutputOverInput(const CLI::App& command);

/// A CLI11 check for a file name given on the command line: an empty one is refused (it would
/// otherwise mean standard output, the default when the option is absent).
[[nodiscard]] CLI::Validator nonEmptyPath();

/// Receives the progress of every long job (done, total) instead of the terminal line, when set
/// (the Python package's progress callback; it may throw to stop the job). Empty: none.
void setProgressObserver(std::function<void(double, double)> observer);
/// The observer set by setProgressObserver (empty: none).
[[nodiscard]] const std::function<void(double, double)>& progressObserver();

/// Progress of a long job: "t = 1.2 of 10 s (12 %), about 40 s left" on standard error. On a
/// terminal one line rewritten at most once a second and cleared by finish() or when dropped;
/// otherwise (a log, a pipe) one line of its own every kProgressLogSeconds, the first only
/// after that long (a short run writes nothing). Nothing with --quiet (setQuiet).
class Progress {
public:
    explicit Progress(double total);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    /// Reports reaching `done` of the total (cheap: the clock is read every 1024 calls).
    void update(double done);
    void finish();

private:
    double total_;
    bool terminal_;
    bool shown_ = false;
    unsigned calls_ = 0;
    double start_ = 0.0, last_ = 0.0;
};

/// Adds --robot to a command (empty = the paper's prototype), and --set NAME=VALUE (any
/// number of times) overriding a parameter the robot file declares.
void addRobotOption(CLI::App& command, std::string& robot_path);

/// Adds --robot and --set NAME=VALUE (any number of times) to a command, into its options'
/// RobotSource (path and overrides: nothing process-wide).
void addRobotOption(CLI::App& command, app::RobotSource& robot);

/// Adds --trajectory (required), --duration and --rate into the options' SamplingOptions.
void addSamplingOptions(CLI::App& command, app::SamplingOptions& sampling);

/// Adds only --set NAME=VALUE to a command (for one naming its robot file otherwise).
void addParameterOption(CLI::App& command);

/// The parameters given with --set, in order (a later one for the same name wins).
[[nodiscard]] const io::ParameterSet& parameterOverrides();
/// Forgets every --set of an earlier command run in this process (the Python package runs many).
void clearParameterOverrides();
/// Adds --trajectory (required), --robot, --duration, --rate and --output.
void addTrajectoryOptions(CLI::App& command, TrajectoryOptions& options);

/// Any robot file (either form) with the --set parameters, or the paper's prototype
/// (robots/paper-3prr.yaml, built in) when the path is empty (then --set is refused).
[[nodiscard]] RobotDescription loadRobotDescriptionOrDefault(const std::string& path);

/// --duration if given, else the trajectory's own duration, else 0.2 s.
[[nodiscard]] double chooseDuration(const std::optional<double>& requested, const PoseTrajectory& trajectory);

/// The output named by --output: a file written safely (io::OutputFile), or stdout when empty.
[[nodiscard]] io::OutputFile openOutput(const std::string& path);

/// Writes the table to `path`, or to stdout when the path is empty.
void writeTable(const io::Table& table, const std::string& path);

/// Adds --plant (report::kPlantNames): every command that chooses a plant offers all three with
/// this one definition.
CLI::Option* addPlantOption(CLI::App& command, std::string& plant);

/// An application-layer option error as the command line spells its options: "--noise-u: ...
/// use --noise-pose and --noise-rate" for the field noise_u naming noise_pose and noise_rate.
[[nodiscard]] std::string commandLineMessage(const app::OptionError& e);

}  // namespace nocdyn::cli
