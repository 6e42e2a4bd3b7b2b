// Trajectory files (see trajectory_yaml.hpp).
#include "nocdyn/io/trajectory_yaml.hpp"

#include <filesystem>

#include "nocdyn/error.hpp"
#include "yaml_util.hpp"

namespace nocdyn::io {

using detail::Context;

namespace {

// Plausibility limits of a trajectory file (README, "Files").
constexpr double kMaxAmplitude = 1e3;         // |offset|, |amplitude| [m or rad]
constexpr double kMaxFrequency = 1e6;         // [Hz]
constexpr double kMaxPhase = 1e6;             // |phase| [rad]
constexpr double kMaxDuration = 1e6;          // [s]
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

}  // namespace

PoseTrajectory parseTrajectory(const std::string& text, const std::string& source) {
    const YAML::Node root = detail::loadDocument(text, source);
    const Context top{source, ""};
    detail::requireMap(top, root, {"name", "duration", "x", "y", "theta"});
    PoseTrajectory traj;
    traj.name = std::filesystem::path(source).stem().string();
    if (const YAML::Node name = root["name"]; name.IsDefined()) {
        if (!name.IsScalar() || name.Scalar().empty()) detail::fail(top / "name", name, "expected a non-empty string");
        traj.name = name.Scalar();
    }
    if (root["duration"].IsDefined()) {
        const double duration = detail::requireNumber(top, root, "duration");
        if (!(duration > 0.0 && duration <= kMaxDuration)) {
            detail::fail(top / "duration", root["duration"],
                         "must be > 0 s and at most " + detail::formatted(kMaxDuration) + " s, got " +
                             detail::formatted(duration));
        }
        traj.duration = duration;
    }
    if (root["x"].IsDefined()) traj.x = parseAxis(top / "x", root["x"]);
    if (root["y"].IsDefined()) traj.y = parseAxis(top / "y", root["y"]);
    if (root["theta"].IsDefined()) traj.theta = parseAxis(top / "theta", root["theta"]);
    return traj;
}

PoseTrajectory loadTrajectory(const std::string& path) {
    return parseTrajectory(detail::readFile(path, "trajectory file"), path);
}

PoseTrajectory trajectoryByNameOrFile(const std::string& name_or_path) {
    if (name_or_path == "paper1") return paperTrajectory1();
    if (name_or_path == "paper2") return paperTrajectory2();
    return loadTrajectory(name_or_path);
}

}  // namespace nocdyn::io
