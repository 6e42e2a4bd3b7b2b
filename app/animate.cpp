#include "app/animate.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "app/animate_spatial.hpp"
#include "app/pose_spatial.hpp"
#include "render/animation.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"

namespace nocdyn::app {

namespace {

/// Whether `path` is a CSV of a recorded motion with its forces (its header has t, x, y, theta
/// and tau1: what simulate, control, inverse-dynamics and shake write; a two-DOF robot's has no
/// theta), not a trajectory's samples.
bool recordedMotion(const std::string& path, bool two_dof) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension != ".csv") return false;
    std::ifstream in(path);
    std::string header;
    if (!in || !std::getline(in, header)) return false;
    std::vector<std::string> names;
    std::stringstream fields(header);
    for (std::string name; std::getline(fields, name, ',');) {
        if (!name.empty() && name.back() == '\r') name.pop_back();
        names.push_back(name);
    }
    const auto has = [&](const char* name) { return std::find(names.begin(), names.end(), name) != names.end(); };
    return has("t") && has("x") && has("y") && (two_dof || has("theta")) && has("tau1");
}

/// A two-DOF robot's pose is [x, y]: a trajectory that moves theta (no coordinate) is refused.
void requireFixedTheta(const Model& model, const PoseTrajectory& trajectory, const std::string& source) {
    const bool moves = !trajectory.theta.harmonics.empty() || trajectory.theta.offset != model.home(0) ||
                       (trajectory.sampled && trajectory.sampled->theta);
    if (moves) {
        throw OptionError("trajectory", source +
                                            " moves theta, but a two-DOF robot (motion: translation) has no theta: its "
                                            "pose is [x, y] (give x and y only)");
    }
}

}  // namespace

void validate(const AnimateOptions& o) {
    validate(static_cast<const SamplingOptions&>(o));
    const int motions = (o.trajectory.empty() ? 0 : 1) + (o.motion.empty() ? 0 : 1) + (o.motion_table ? 1 : 0);
    if (motions == 0) throw OptionError("trajectory", "give a trajectory or a motion");
    if (motions > 1) throw OptionError("motion", "give a trajectory or a motion, not both");
    if (o.slow_motion != 0.0) requireIn(o.slow_motion, kSlowMotionRange, "slow_motion");
    requireIn(o.magnify, kMagnifyRange, "magnify");
    if (o.frame) requireIn(*o.frame, kFrameRange, "frame");
}

AnimateResult runAnimate(const AnimateOptions& options, Observer& observer) {
    validate(options);
    if (isSpatialRobot(options.robot)) return runSpatialAnimate(options, observer);
    // a two-DOF robot too: the tool point, arms and forearms along x, y
    const Model model(loadRobot(options.robot));
    const bool two_dof = model.task_dimension == 2;
    render::MotionSamples motion;
    // a recorded motion given as the trajectory (a replay's shake.csv): played as a motion, forces and all
    const bool recorded = !options.trajectory.empty() && recordedMotion(options.trajectory, two_dof);
    if (recorded && (options.duration || options.rate != SamplingOptions{}.rate)) {
        throw OptionError("trajectory", options.trajectory +
                                            " is a recorded motion (t, x, y, theta, tau1..): it is played as "
                                            "recorded, without duration or rate");
    }
    if (options.motion_table) {
        motion = render::motionFromTable(model, *options.motion_table, options.motion_name);
    } else if (!options.motion.empty() || recorded) {
        motion = render::motionFromCsv(model, recorded ? options.trajectory : options.motion);
    } else {
        const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
        if (two_dof) requireFixedTheta(model, trajectory, options.trajectory);
        motion =
            render::motionFromTrajectory(model, trajectory, chooseDuration(options.duration, trajectory), options.rate);
    }
    for (const std::string& warning : motion.warnings) observer.warning(warning);
    AnimateResult out;
    if (options.frame) out.frame = render::frameFigure(model, motion, *options.frame);
    out.html = render::animationPage(model, motion, {options.slow_motion, options.magnify});
    return out;
}

}  // namespace nocdyn::app
