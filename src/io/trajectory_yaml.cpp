// Trajectory files (see trajectory_yaml.hpp).
#include "nocdyn/io/trajectory_yaml.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "nocdyn/io/csv.hpp"
#include "nocdyn/spatial_trajectory.hpp"

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"
#include "file_util.hpp"
#include "yaml_util.hpp"

namespace nocdyn::io {

using detail::Context;

namespace {

// Plausibility limits of a trajectory file (README, "Files").
constexpr double kMaxAmplitude = 1e3;         // |offset|, |amplitude| [m or rad]
constexpr double kMaxFrequency = 1e6;         // [Hz]
constexpr double kMaxPhase = 1e6;             // |phase| [rad]
constexpr double kMaxDuration = 1e6;          // [s]
constexpr double kMaxAcceleration = 1e6;      // |sampled acceleration| [m/s^2 or rad/s^2]
constexpr double kMinTimeStep = 1e-9;         // between samples [s]
constexpr std::size_t kMaxHarmonics = 10000;  // per axis

AxisMotion parseAxis(const Context& context, const YAML::Node& node) {
    detail::requireMap(context, node, {"offset", "harmonics"});
    AxisMotion axis;
    axis.offset = detail::optionalNumber(context, node, "offset", 0.0);
    detail::requireRange(context, node, "offset", axis.offset, -kMaxAmplitude, kMaxAmplitude, "(m or rad)");
    const YAML::Node list = node["harmonics"];
    if (!list.IsDefined() || list.IsNull()) return axis;
    if (!list.IsSequence()) detail::fail(context / "harmonics", list, "expected a list of harmonics");
    if (list.size() > kMaxHarmonics) {
        detail::fail(
            context / "harmonics", list,
            "at most " + std::to_string(kMaxHarmonics) + " harmonics per axis, got " + std::to_string(list.size()));
    }
    for (std::size_t k = 0; k < list.size(); ++k) {
        const Context item = context / ("harmonics[" + std::to_string(k) + "]");
        const YAML::Node h = list[k];
        detail::requireMap(item, h, {"amplitude", "frequency", "phase"});
        Harmonic harmonic;
        harmonic.amplitude = detail::requireNumber(item, h, "amplitude");
        detail::requireRange(item, h, "amplitude", harmonic.amplitude, -kMaxAmplitude, kMaxAmplitude, "(m or rad)");
        harmonic.frequency = detail::requireNumber(item, h, "frequency");
        detail::requireRange(item, h, "frequency", harmonic.frequency, 0.0, kMaxFrequency, "Hz");
        harmonic.phase = detail::optionalNumber(item, h, "phase", 0.0);
        detail::requireRange(item, h, "phase", harmonic.phase, -kMaxPhase, kMaxPhase, "rad");
        axis.harmonics.push_back(harmonic);
    }
    return axis;
}

/// The file's name: its key `name`, else the file name's stem.
std::string nameOf(const Context& top, const YAML::Node& root) {
    if (const YAML::Node name = root["name"]; name.IsDefined()) {
        if (!name.IsScalar() || name.Scalar().empty()) detail::fail(top / "name", name, "expected a non-empty string");
        return name.Scalar();
    }
    return std::filesystem::path(top.source).stem().string();
}

/// The file's key `duration` [s], when given: within (0, kMaxDuration].
std::optional<double> durationOf(const Context& top, const YAML::Node& root) {
    if (!root["duration"].IsDefined()) return std::nullopt;
    const double duration = detail::requireNumber(top, root, "duration");
    if (!(duration > 0.0 && duration <= kMaxDuration)) {
        detail::fail(top / "duration", root["duration"],
                     "must be > 0 s and at most " + text::number(kMaxDuration) + " s, got " + text::number(duration));
    }
    return duration;
}

}  // namespace

PoseTrajectory parseTrajectory(const std::string& text, const std::string& source) {
    const YAML::Node root = detail::loadDocument(text, source);
    const Context top{source, ""};
    detail::requireMap(top, root, {"name", "duration", "x", "y", "theta"});
    PoseTrajectory traj;
    traj.name = nameOf(top, root);
    traj.duration = durationOf(top, root);
    if (root["x"].IsDefined()) traj.x = parseAxis(top / "x", root["x"]);
    if (root["y"].IsDefined()) traj.y = parseAxis(top / "y", root["y"]);
    if (root["theta"].IsDefined()) traj.theta = parseAxis(top / "theta", root["theta"]);
    return traj;
}

PoseTrajectory loadTrajectory(const std::string& path) {
    return parseTrajectory(detail::readFile(path, "trajectory file"), path);
}

namespace {

bool endsWithCsv(const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext.size() != 4) return false;
    std::string lower;
    for (const char c : ext) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return lower == ".csv";
}

}  // namespace

namespace {

/// "SOURCE:LINE: " of a CSV table's data row (0-based).
std::string rowPrefix(const Table& table, const std::string& source, std::size_t row) {
    return source + ":" + std::to_string(row < table.lines.size() ? table.lines[row] : row + 2) + ": ";
}

/// The sample times of a CSV trajectory: column t, at least 2 rows, within the duration limit,
/// strictly increasing by at least kMinTimeStep and without a gap (kMaxTimeStepRatio).
std::vector<double> sampleTimesOf(const Table& table, const std::string& source) {
    const std::string header = source + ":1: ";
    if (!table.has("t")) throw Error(header + "column 't': missing (the sample times, s)");
    const std::size_t n = table.rows.size();
    if (n < 2) throw Error(header + "column 't': at least 2 samples are needed, found " + std::to_string(n));
    const std::size_t ct = table.column("t");
    std::vector<double> t(n);
    for (std::size_t i = 0; i < n; ++i) t[i] = table.rows[i][ct];
    for (std::size_t i = 0; i < n; ++i) {
        if (!(std::abs(t[i]) <= kMaxDuration)) {
            throw Error(rowPrefix(table, source, i) + "column 't': time " + text::precise(t[i]) +
                        " s is out of range (|t| <= " + text::precise(kMaxDuration) + " s)");
        }
    }
    for (std::size_t i = 1; i < n; ++i) {
        if (!(t[i] > t[i - 1])) {
            throw Error(rowPrefix(table, source, i) + "column 't': time " + text::precise(t[i]) +
                        " s is not after the previous " + text::precise(t[i - 1]) + " s (times must increase)");
        }
        if (t[i] - t[i - 1] < kMinTimeStep) {
            throw Error(rowPrefix(table, source, i) + "column 't': time " + text::precise(t[i]) + " s is less than " +
                        text::precise(kMinTimeStep) + " s after the previous " + text::precise(t[i - 1]) + " s");
        }
    }
    std::vector<double> steps(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) steps[i] = t[i + 1] - t[i];
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (std::size_t i = 0; i + 1 < n; ++i) {
        if (steps[i] > kMaxTimeStepRatio * median) {
            throw Error(rowPrefix(table, source, i + 1) + "column 't': gap of " + text::precise(steps[i]) +
                        " s after " + text::precise(t[i]) + " s (more than " + text::precise(kMaxTimeStepRatio) +
                        " times the median step " + text::precise(median) + " s)");
        }
    }
    return t;
}

/// Column `name` of a CSV trajectory, every value within +-limit (as a harmonic's amplitude).
std::vector<double> sampleColumn(const Table& table, const std::string& source, const char* name, double limit,
                                 const char* unit) {
    const std::size_t n = table.rows.size();
    std::vector<double> v(n);
    const std::size_t c = table.column(name);
    for (std::size_t i = 0; i < n; ++i) {
        v[i] = table.rows[i][c];
        if (!(std::abs(v[i]) <= limit)) {
            throw Error(rowPrefix(table, source, i) + "column '" + name + "': " + text::precise(v[i]) +
                        " is out of range (|" + name + "| <= " + text::precise(limit) + " " + unit + ")");
        }
    }
    return v;
}

}  // namespace

PoseTrajectory parseTrajectoryCsv(const std::string& text, const std::string& source) {
    const Table table = parseCsv(text, source);
    const std::string header = source + ":1: ";
    static constexpr std::array<const char*, 7> known = {"t", "x", "y", "theta", "ax", "ay", "alpha"};
    for (const std::string& c : table.columns) {
        if (std::find_if(known.begin(), known.end(), [&](const char* k) { return c == k; }) == known.end()) {
            std::string message = header;
            message.append("column '")
                .append(c)
                .append("': unknown (expected t and any of x, y, theta or ax, ay, alpha)");
            throw Error(message);
        }
    }
    const std::vector<double> t = sampleTimesOf(table, source);
    const auto column = [&](const char* name, double limit, const char* unit) {
        return sampleColumn(table, source, name, limit, unit);
    };
    auto sampled = std::make_shared<SampledPose>();
    const auto axis = [&](const char* position, const char* acceleration, std::optional<SampledAxis>& out) {
        const bool p = table.has(position);
        const bool a = table.has(acceleration);
        if (p && a) {
            throw Error(header + "column '" + acceleration + "': axis already given by its position column '" +
                        position + "' (give one of the two)");
        }
        if (p) out = splineOfPositions(t, column(position, kMaxAmplitude, "m or rad"));
        if (a) out = splineOfAccelerations(t, column(acceleration, kMaxAcceleration, "m/s^2 or rad/s^2"));
    };
    axis("theta", "alpha", sampled->theta);
    axis("x", "ax", sampled->x);
    axis("y", "ay", sampled->y);
    if (!sampled->theta && !sampled->x && !sampled->y) {
        throw Error(header + "missing columns: at least one of x, y, theta, ax, ay, alpha besides t");
    }
    PoseTrajectory traj;
    traj.name = std::filesystem::path(source).stem().string();
    traj.duration = t.back();
    traj.sampled = std::move(sampled);
    return traj;
}

PoseTrajectory loadTrajectoryCsv(const std::string& path) {
    return parseTrajectoryCsv(detail::readRegularFile(path, "trajectory file", detail::kMaxCsvBytes), path);
}

PoseTrajectory trajectoryByNameOrFile(const std::string& name_or_path) {
    if (name_or_path == "paper1") return paperTrajectory1();
    if (name_or_path == "paper2") return paperTrajectory2();
    // neither a built-in name nor a file: say what the names are
    std::error_code error;
    if (!std::filesystem::exists(name_or_path, error)) {
        throw Error("trajectory '" + name_or_path +
                    "': no such file, and not a built-in trajectory (paper1, paper2: the paper's trajectories 1 "
                    "and 2)");
    }
    if (endsWithCsv(name_or_path)) return loadTrajectoryCsv(name_or_path);
    return loadTrajectory(name_or_path);
}

namespace {

std::string axisYaml(const char* name, const AxisMotion& axis) {
    std::string text = std::string(name) + ": {offset: " + text::allDigits(axis.offset) + ", harmonics: [";
    for (std::size_t k = 0; k < axis.harmonics.size(); ++k) {
        const Harmonic& h = axis.harmonics[k];
        text += (k == 0 ? "\n    " : ",\n    ");
        text += "{amplitude: " + text::allDigits(h.amplitude) + ", frequency: " + text::allDigits(h.frequency) +
                ", phase: " + text::allDigits(h.phase) + "}";
    }
    return text + "]}\n";
}

}  // namespace

std::string trajectoryToYaml(const PoseTrajectory& trajectory) {
    if (trajectory.sampled) throw Error("trajectory '" + trajectory.name + "' is sampled: no harmonic YAML form");
    // the name as a single-quoted YAML scalar (a quote doubled)
    std::string name;
    for (const char c : trajectory.name) name += c == '\'' ? std::string("''") : std::string(1, c);
    std::string text = "name: '" + name + "'\n";
    if (trajectory.duration) text += "duration: " + text::allDigits(*trajectory.duration) + "   # [s]\n";
    text += axisYaml("theta", trajectory.theta) + axisYaml("x", trajectory.x) + axisYaml("y", trajectory.y);
    return text;
}

// --- a spatial robot's trajectory (spatial_trajectory.hpp) -----------------------------------

namespace {

/// "x, y, z" or "x, y, z, roll, pitch, yaw".
std::string coordinateList(int dimension) {
    std::string list;
    for (int i = 0; i < dimension; ++i) {
        list += (i == 0 ? "" : ", ") + std::string(spatial::kCoordinateNames[static_cast<std::size_t>(i)]);
    }
    return list;
}

/// Why a key or column that is not one of the robot's coordinates is refused, or "" when it is
/// one: theta (a planar robot's), roll, pitch, yaw for a translation robot.
std::string misplacedCoordinate(const std::string& key, int dimension) {
    if (key == "theta" || key == "alpha" || key == "ax" || key == "ay") {
        return "a planar robot's coordinate: a spatial robot's trajectory is keyed " + coordinateList(dimension);
    }
    for (int i = dimension; i < 6; ++i) {
        if (key == spatial::kCoordinateNames[static_cast<std::size_t>(i)]) {
            return "a translation robot (motion: translation, pose [x, y, z]) keeps its orientation: its trajectory "
                   "is keyed x, y, z only";
        }
    }
    return "";
}

void requireDimension(int dimension) {
    if (dimension != 3 && dimension != 6) {
        throw Error("a spatial trajectory has 3 or 6 coordinates, not " + std::to_string(dimension));
    }
}

}  // namespace

spatial::Trajectory parseSpatialTrajectory(const std::string& text, const std::string& source, int dimension) {
    requireDimension(dimension);
    const YAML::Node root = detail::loadDocument(text, source);
    const Context top{source, ""};
    if (root.IsMap()) {
        for (const auto& entry : root) {
            if (!entry.first.IsScalar()) continue;  // requireMap names it
            const std::string reason = misplacedCoordinate(entry.first.Scalar(), dimension);
            if (!reason.empty()) detail::fail(top / entry.first.Scalar(), entry.first, reason);
        }
    }
    if (dimension == 3) {
        detail::requireMap(top, root, {"name", "duration", "x", "y", "z"});
    } else {
        detail::requireMap(top, root, {"name", "duration", "x", "y", "z", "roll", "pitch", "yaw"});
    }
    spatial::Trajectory traj;
    traj.dimension = dimension;
    traj.name = nameOf(top, root);
    traj.duration = durationOf(top, root);
    for (int i = 0; i < dimension; ++i) {
        const char* key = spatial::kCoordinateNames[static_cast<std::size_t>(i)];
        const YAML::Node axis = root[key];
        if (!axis.IsDefined()) {
            detail::fail(top / key, root,
                         "missing: a spatial robot's trajectory gives every coordinate (" + coordinateList(dimension) +
                             "), each {offset, harmonics}");
        }
        traj.axis[static_cast<std::size_t>(i)] = parseAxis(top / key, axis);
    }
    return traj;
}

spatial::Trajectory parseSpatialTrajectoryCsv(const std::string& text, const std::string& source, int dimension) {
    requireDimension(dimension);
    const Table table = parseCsv(text, source);
    const std::string header = source + ":1: ";
    for (const std::string& c : table.columns) {
        if (c == "t") continue;
        const auto refuse = [&](const std::string& reason) {
            std::string message = header;
            message.append("column '").append(c).append("': ").append(reason);
            throw Error(message);
        };
        if (const std::string reason = misplacedCoordinate(c, dimension); !reason.empty()) refuse(reason);
        bool known = false;
        for (int i = 0; i < dimension; ++i)
            known = known || c == spatial::kCoordinateNames[static_cast<std::size_t>(i)];
        if (!known) refuse("unknown (expected t, " + coordinateList(dimension) + ")");
    }
    for (int i = 0; i < dimension; ++i) {
        const char* name = spatial::kCoordinateNames[static_cast<std::size_t>(i)];
        if (!table.has(name)) {
            throw Error(header + "column '" + name + "': missing (a spatial robot's samples give t, " +
                        coordinateList(dimension) + ")");
        }
    }
    const std::vector<double> t = sampleTimesOf(table, source);
    spatial::Trajectory traj;
    traj.dimension = dimension;
    traj.name = std::filesystem::path(source).stem().string();
    traj.duration = t.back();
    for (int i = 0; i < dimension; ++i) {
        const char* name = spatial::kCoordinateNames[static_cast<std::size_t>(i)];
        traj.sampled[static_cast<std::size_t>(i)] = std::make_shared<const SampledAxis>(
            splineOfPositions(t, sampleColumn(table, source, name, kMaxAmplitude, "m or rad")));
    }
    return traj;
}

spatial::Trajectory loadSpatialTrajectory(const std::string& path, int dimension) {
    if (path == "paper1" || path == "paper2") {
        throw Error("trajectory '" + path + "': the paper's planar trajectory; a spatial robot takes a trajectory " +
                    "file keyed " + coordinateList(dimension) + " (YAML) or samples t, " + coordinateList(dimension) +
                    " (.csv)");
    }
    std::error_code error;
    if (!std::filesystem::exists(path, error)) throw Error("trajectory '" + path + "': no such file");
    if (endsWithCsv(path)) {
        return parseSpatialTrajectoryCsv(detail::readRegularFile(path, "trajectory file", detail::kMaxCsvBytes), path,
                                         dimension);
    }
    return parseSpatialTrajectory(detail::readFile(path, "trajectory file"), path, dimension);
}

}  // namespace nocdyn::io
