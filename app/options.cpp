#include "app/options.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

void requireIn(double value, const Range& range, const std::string& field) {
    if (!std::isfinite(value)) throw OptionError(field, "expected a finite number");
    if (value < range.lo || value > range.hi) {
        std::ostringstream text;
        text.precision(17);
        text << value << " is outside [" << range.lo << ", " << range.hi << "] " << range.unit;
        throw OptionError(field, text.str());
    }
}

RobotDescription loadRobot(const RobotSource& source) {
    if (source.description) {
        if (!source.set.empty()) {
            throw OptionError("set", "a robot built in code has no file parameters: change the robot itself");
        }
        return *source.description;  // validated when it was built
    }
    if (source.path.empty()) {
        if (!source.set.empty())
            throw OptionError("set", "needs a robot file: the built-in prototype has no parameters");
        return io::exampleRobot("paper-3prr");
    }
    return io::loadRobotDescription(source.path, source.set);
}

std::string rigidPlantWarning(const RobotDescription& robot, const std::string& command) {
    const Model model(robot);
    const StiffnessModel compliance(model);
    if (!compliance.any) return {};
    // the first lumped natural frequency at home says where the rigid plant stops being the robot
    std::string first;
    StiffnessData stiffness;
    LumpedModes modes;
    Data data(model);
    TaskModes task;  // a two-DOF robot's over x, y (theta is free and massless)
    if (stiffnessAndModes(model, compliance, data, model.home, stiffness, modes)) {
        taskModes(model, data, stiffness, modes, task);
        if (std::isfinite(task.frequency(0)) && task.frequency(0) > 0.0)
            first = text::format(" (first resonance at home %.4g Hz)", task.frequency(0));
    }
    return command + ": the compliance the robot file declares (joint or drive stiffness, elastic links)" + first +
           " is not modelled: the plant is the rigid robot";
}

void addOverride(io::ParameterSet& set, const io::Parameter& parameter) {
    const auto same =
        std::find_if(set.begin(), set.end(), [&](const io::Parameter& q) { return q.name == parameter.name; });
    if (same != set.end())
        same->value = parameter.value;
    else
        set.push_back(parameter);
}

void validate(const SamplingOptions& options) {
    if (options.duration) requireIn(*options.duration, kDurationRange, "duration");
    requireIn(options.rate, kRateRange, "rate");
}

PoseTrajectory trajectoryOf(const SamplingOptions& options) {
    return options.given_trajectory ? *options.given_trajectory : io::trajectoryByNameOrFile(options.trajectory);
}

PoseTrajectory trajectoryFor(const Model& model, PoseTrajectory trajectory, const std::string& source) {
    if (model.task_dimension == 3) return trajectory;
    bool moves = trajectory.theta.offset != 0.0;
    for (const Harmonic& h : trajectory.theta.harmonics) moves = moves || h.amplitude != 0.0;
    if (trajectory.sampled && trajectory.sampled->theta) {
        for (const auto& piece : trajectory.sampled->theta->pieces) {
            for (const double c : piece) moves = moves || c != 0.0;
        }
    }
    if (moves) {
        throw Error("trajectory '" + (source.empty() ? trajectory.name : source) +
                    "': theta: not 0 throughout, but a two-DOF robot (motion: translation, pose [x, y]) has no "
                    "theta: key the trajectory x, y only");
    }
    trajectory.theta = AxisMotion{model.home(0), {}};  // 0: the core's pose [home(0), x, y]
    return trajectory;
}

double chooseDuration(const std::optional<double>& requested, const PoseTrajectory& trajectory) {
    if (requested) return *requested;
    if (trajectory.duration) return *trajectory.duration;
    return 0.2;
}

}  // namespace nocdyn::app
