#include "app/validate.hpp"

#include <array>
#include <map>

#include "app/pose_spatial.hpp"
#include "app/validate_spatial.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/printable.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/validation/agreement.hpp"

namespace nocdyn::app {

ValidateResult runValidate(const ValidateOptions& options, Observer& observer) {
    if (isSpatialRobot(options.robot)) return runSpatialValidate(options, observer);
    validate(static_cast<const SamplingOptions&>(options));
    if (options.engine != ValidateEngine::both)
        throw OptionError("engine", "a planar robot is compared with both engines: give --engine both or leave it out");
    const RobotDescription robot = loadRobot(options.robot);
    const PoseTrajectory trajectory =
        trajectoryFor(Model(robot), io::trajectoryByNameOrFile(options.trajectory), options.trajectory);
    const auto times = sampleTimes(chooseDuration(options.duration, trajectory), options.rate);
    stopIfRequested(observer);
    const validation::EngineComparison comparison = validation::compareWithEngines(robot, trajectory, times);
    ValidateResult out;
    out.robot = robot.name;
    out.trajectory = trajectory.name;
    out.samples = times.size();
    out.table = validation::toTable(comparison);
    out.agreement = validation::agreementTable(comparison);
    return out;
}

std::optional<std::string> checkSpatialRobot(const RobotSource& source) {
    if (source.description || source.path.empty()) return std::nullopt;
    const std::string text = io::readRobotFileText(source.path);
    if (!io::isSpatial(text, source.path)) return std::nullopt;
    const SpatialRobotDescription robot = io::parseSpatialRobotDescription(text, source.path, source.set);
    // counts by joint type (R, P, U, S) and by limb type, in file order
    const std::string letters = "RPUS";
    std::array<int, 4> joints{}, actuated{};
    std::vector<std::pair<std::string, int>> kinds;
    int listed = 0, freedoms = 0;
    for (const SpatialLimbDescription& limb : robot.limbs) {
        for (const SpatialJointDescription& joint : limb.joints) {
            const auto k = letters.find(joint.letter());
            ++joints[k];
            actuated[k] += joint.actuated ? 1 : 0;
            ++listed;
            freedoms += joint.freedoms();
        }
        const std::string type = limb.type();
        auto same = std::find_if(kinds.begin(), kinds.end(), [&](const auto& kind) { return kind.first == type; });
        if (same == kinds.end())
            kinds.emplace_back(type, 1);
        else
            ++same->second;
    }
    const auto byType = [&](const std::array<int, 4>& counts) {
        std::string out;
        for (std::size_t k = 0; k < 4; ++k) {
            if (counts[k] > 0) out += (out.empty() ? "" : ", ") + std::to_string(counts[k]) + " " + letters[k];
        }
        return out.empty() ? std::string("none") : out;
    };
    std::string limbs;
    for (const auto& [type, count] : kinds) limbs += (limbs.empty() ? "" : ", ") + std::to_string(count) + " " + type;
    const bool full = robot.motion == PlatformMotion::full;
    std::string out = text::printable(robot.name) + ": a spatial robot (motion " + (full ? "full" : "translation") +
                      ", pose [" + (full ? "x, y, z, roll, pitch, yaw" : "x, y, z") + "]), read and checked\n";
    out += "  limbs: " + std::to_string(robot.limbs.size()) + " (" + limbs + ")\n";
    out += "  joints: " + std::to_string(listed) + " (" + byType(joints) + "), " + std::to_string(freedoms) +
           " joint freedoms\n";
    out += "  actuators: " + std::to_string(robot.actuatorCount()) + " (" + byType(actuated) + ")\n";
    out +=
        "  mass: " + text::number(robot.totalMass()) + " kg (platform " + text::number(robot.platform.mass) + " kg)\n";
    out += "give --trajectory to compare its actuator forces with Simbody's and MuJoCo's spatial models along it\n";
    return out;
}

}  // namespace nocdyn::app
