// Robot files of either form (robot_file.hpp).
#include "nocdyn/io/robot_file.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_yaml.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/pose_order.hpp"
#include "nocdyn/text.hpp"
#include "expression.hpp"
#include "file_util.hpp"
#include "spatial_robot_file.hpp"
#include "yaml_util.hpp"

namespace nocdyn::io {

using detail::Context;
using detail::flag;
using detail::lineOf;

namespace {

Eigen::Vector2d vector2(const Context& context, const YAML::Node& map, const char* key) {
    const YAML::Node node = map[key];
    if (!node.IsDefined() || node.IsNull()) detail::fail(context / key, map, "required [x, y] is missing");
    if (!node.IsSequence() || node.size() != 2)
        detail::fail(context / key, node, "expected a list of 2 numbers [x, y]");
    return {detail::toNumber(context / key, node[0]), detail::toNumber(context / key, node[1])};
}

JointDescription parseJoint(const Context& context, const YAML::Node& node) {
    detail::requireMap(context, node,
                       {"type", "point", "direction", "actuated", "limits", "damping", "friction", "stiffness"});
    JointDescription joint;
    joint.line = lineOf(node);
    const YAML::Node type = node["type"];
    if (!type.IsDefined()) detail::fail(context / "type", node, "required joint type is missing (R or P)");
    if (!type.IsScalar() || (type.Scalar() != "R" && type.Scalar() != "P")) {
        detail::fail(
            context / "type", type,
            "unknown joint type '" + (type.IsScalar() ? type.Scalar() : std::string("?")) + "' (expected R or P)");
    }
    if (type.Scalar() == "R") {
        joint.type = JointType::revolute;
        if (node["direction"].IsDefined())
            detail::fail(context / "direction", node["direction"], "an R joint takes a point, not a direction");
        joint.point = vector2(context, node, "point");
    } else {
        joint.type = JointType::prismatic;
        if (node["point"].IsDefined())
            detail::fail(context / "point", node["point"], "a P joint takes a direction, not a point");
        joint.direction = vector2(context, node, "direction");
    }
    joint.actuated = flag(context, node, "actuated");
    if (const YAML::Node limits = node["limits"]; limits.IsDefined()) {
        const Context here = context / "limits";
        detail::requireMap(here, limits, {"lower", "upper", "effort", "velocity"});
        joint.limits.lower = detail::optionalNumber(here, limits, "lower", joint.limits.lower);
        joint.limits.upper = detail::optionalNumber(here, limits, "upper", joint.limits.upper);
        joint.limits.effort = detail::optionalNumber(here, limits, "effort", joint.limits.effort);
        joint.limits.velocity = detail::optionalNumber(here, limits, "velocity", joint.limits.velocity);
    }
    joint.damping = detail::optionalNumber(context, node, "damping", 0.0);
    joint.friction = detail::optionalNumber(context, node, "friction", 0.0);
    if (node["stiffness"].IsDefined()) joint.stiffness = detail::requireNumber(context, node, "stiffness");
    return joint;
}

BodyDescription parseBody(const Context& context, const YAML::Node& node) {
    detail::requireMap(context, node, {"mass", "inertia", "com", "elastic"});
    BodyDescription body;
    body.line = lineOf(node);
    body.mass = detail::requireNumber(context, node, "mass");
    body.inertia = detail::requireNumber(context, node, "inertia");
    body.com = vector2(context, node, "com");
    if (const YAML::Node elastic = node["elastic"]; elastic.IsDefined()) {
        const Context here = context / "elastic";
        detail::requireMap(here, elastic, {"EA", "EI"});
        body.elastic =
            ElasticBeam{detail::requireNumber(here, elastic, "EA"), detail::requireNumber(here, elastic, "EI")};
    }
    return body;
}

RobotDescription parseGeneral(const YAML::Node& root, const std::string& source) {
    const Context top{source, ""};
    detail::requireMap(
        top, root,
        {"name", "space", "motion", "gravity", "home", "max_condition", "damping_ratio", "platform", "limbs"});
    RobotDescription robot;
    robot.source = source;
    robot.name = std::filesystem::path(source).stem().string();
    if (const YAML::Node name = root["name"]; name.IsDefined()) {
        if (!name.IsScalar() || name.Scalar().empty()) detail::fail(top / "name", name, "expected a non-empty string");
        robot.name = name.Scalar();
    }
    if (const YAML::Node space = root["space"]; space.IsDefined()) {
        if (!space.IsScalar() || (space.Scalar() != "planar" && space.Scalar() != "spatial"))
            detail::fail(top / "space", space, "expected planar or spatial");
    }
    if (const YAML::Node motion = root["motion"]; motion.IsDefined()) {
        if (!motion.IsScalar() || (motion.Scalar() != "full" && motion.Scalar() != "translation"))
            detail::fail(top / "motion", motion, "expected full or translation");
        robot.motion = motion.Scalar() == "translation" ? PlatformMotion::translation : PlatformMotion::full;
    }
    const bool translation = robot.motion == PlatformMotion::translation;
    if (root["gravity"].IsDefined()) robot.gravity = vector2(top, root, "gravity");
    if (const YAML::Node home = root["home"]; home.IsDefined()) {
        // the user's order, as every pose a user writes (pose_order.hpp); the core's inside
        if (translation) {
            // the tool point [x, y]; the core's pose [theta = 0, x, y]
            if (!home.IsSequence() || home.size() != 2) detail::fail(top / "home", home, "expected [x, y]");
            robot.home = Vector3(0.0, detail::toNumber(top / "home", home[0]), detail::toNumber(top / "home", home[1]));
        } else {
            if (!home.IsSequence() || home.size() != 3) detail::fail(top / "home", home, "expected [x, y, theta]");
            Vector3 user;
            for (std::size_t i = 0; i < 3; ++i)
                user(static_cast<Eigen::Index>(i)) = detail::toNumber(top / "home", home[i]);
            robot.home = corePose(user);
        }
    }
    robot.max_condition = detail::optionalNumber(top, root, "max_condition", robot.max_condition);
    robot.damping_ratio = detail::optionalNumber(top, root, "damping_ratio", robot.damping_ratio);
    const YAML::Node platform = root["platform"];
    if (!platform.IsDefined()) detail::fail(top / "platform", root, "required section is missing");
    detail::requireMap(top / "platform", platform, {"mass", "inertia", "com"});
    robot.platform.line = lineOf(platform);
    robot.platform.mass = detail::requireNumber(top / "platform", platform, "mass");
    // a translating point tool has no rotational inertia: optional, and 0 if given
    robot.platform.inertia = translation ? detail::optionalNumber(top / "platform", platform, "inertia", 0.0)
                                         : detail::requireNumber(top / "platform", platform, "inertia");
    if (platform["com"].IsDefined()) robot.platform.com = vector2(top / "platform", platform, "com");
    const YAML::Node limbs = root["limbs"];
    // (a missing key of a const node is invalid: IsDefined first, before any other question)
    if (!limbs.IsDefined() || !limbs.IsSequence()) detail::fail(top / "limbs", root, "expected a list of limbs");
    if (limbs.size() < 2 || limbs.size() > static_cast<std::size_t>(kMaxLimbs)) {
        detail::fail(top / "limbs", limbs,
                     "a robot has 2 to " + std::to_string(kMaxLimbs) + " limbs, got " + std::to_string(limbs.size()));
    }
    for (std::size_t j = 0; j < limbs.size(); ++j) {
        const YAML::Node node = limbs[j];
        const Context limb_context = top / ("limbs[" + std::to_string(j) + "]");
        detail::requireMap(limb_context, node, {"name", "joints", "bodies"});
        LimbDescription limb;
        limb.line = lineOf(node);
        limb.name = "limb" + std::to_string(j + 1);
        if (const YAML::Node name = node["name"]; name.IsDefined()) {
            if (!name.IsScalar() || name.Scalar().empty())
                detail::fail(limb_context / "name", name, "expected a non-empty string");
            limb.name = name.Scalar();
        }
        const YAML::Node joints = node["joints"];
        if (!joints.IsDefined() || !joints.IsSequence() || joints.size() != 3) {
            detail::fail(limb_context / "joints", joints.IsDefined() ? joints : node,
                         "a limb has exactly 3 joints, base to platform");
        }
        for (std::size_t k = 0; k < 3; ++k) {
            limb.joints[k] = parseJoint(limb_context / ("joints[" + std::to_string(k) + "]"), joints[k]);
        }
        const YAML::Node bodies = node["bodies"];
        if (!bodies.IsDefined() || !bodies.IsSequence() || bodies.size() != 2) {
            detail::fail(limb_context / "bodies", bodies.IsDefined() ? bodies : node,
                         "a limb has exactly 2 moving bodies (between joints 1-2 and 2-3)");
        }
        for (std::size_t b = 0; b < 2; ++b) {
            limb.bodies[b] = parseBody(limb_context / ("bodies[" + std::to_string(b) + "]"), bodies[b]);
        }
        robot.limbs.push_back(limb);
    }
    validate(robot);
    return robot;
}

/// Shortest decimal that reads back as the same double.

std::string pair(const Eigen::Vector2d& v) {
    std::string out("[");
    out.append(text::shortest(v.x())).append(", ").append(text::shortest(v.y())).append("]");
    return out;
}

/// Whether a parsed root is a spatial robot file (`space: spatial`).
bool spatialRoot(const YAML::Node& root) {
    if (!root.IsMap()) return false;
    const YAML::Node space = root["space"];
    return space.IsDefined() && space.IsScalar() && space.Scalar() == "spatial";
}

}  // namespace

std::string readRobotFileText(const std::string& path) { return detail::readFile(path, "robot file"); }

bool isSpatial(const std::string& text, const std::string& source) {
    return spatialRoot(detail::loadDocument(text, source));
}

SpatialRobotDescription parseSpatialRobotDescription(const std::string& text, const std::string& source,
                                                     const ParameterSet& overrides) {
    const YAML::Node root = detail::loadDocument(text, source);
    detail::ExpressionEvaluator evaluator;
    (void)detail::declareParameters(root, source, overrides, evaluator);
    const detail::ExpressionScope expressions(evaluator);
    if (!spatialRoot(root)) {
        throw Error(source + ": not a spatial robot file (it has no `space: spatial`)");
    }
    return detail::spatial::parse(root, source);
}

SpatialRobotDescription loadSpatialRobotDescription(const std::string& path, const ParameterSet& overrides) {
    return parseSpatialRobotDescription(readRobotFileText(path), path, overrides);
}

bool isGeneralForm(const std::string& text, const std::string& source) {
    const YAML::Node root = detail::loadDocument(text, source);
    return root.IsMap() && root["limbs"].IsDefined();
}

RobotDescription parseRobotDescription(const std::string& text, const std::string& source,
                                       const ParameterSet& overrides) {
    const YAML::Node root = detail::loadDocument(text, source);
    detail::ExpressionEvaluator evaluator;
    (void)detail::declareParameters(root, source, overrides, evaluator);
    const detail::ExpressionScope expressions(evaluator);
    if (spatialRoot(root)) {
        // read and checked in full, so that its errors come first; then refused in one line
        (void)detail::spatial::parse(root, source);
        throw Error(source + ": " + kSpatialNotComputed);
    }
    if (root.IsMap() && root["limbs"].IsDefined()) return parseGeneral(root, source);
    RobotDescription robot = expand(detail::parseShortForm(root, source));
    robot.source = source;
    return robot;
}

RobotDescription loadRobotDescription(const std::string& path, const ParameterSet& overrides) {
    return parseRobotDescription(readRobotFileText(path), path, overrides);
}

ParameterSet robotFileParameters(const std::string& text, const std::string& source, const ParameterSet& overrides) {
    detail::ExpressionEvaluator evaluator;
    return detail::declareParameters(detail::loadDocument(text, source), source, overrides, evaluator);
}

Parameter parseParameterAssignment(const std::string& text) {
    const auto equals = text.find('=');
    const std::string name = equals == std::string::npos ? text : text.substr(0, equals);
    if (equals == std::string::npos || !detail::isParameterName(name)) {
        throw Error("'" + terminalText(text) + "': expected NAME=VALUE, NAME a parameter's name");
    }
    const std::string value = text.substr(equals + 1);
    const auto number = detail::parseDecimal(value);
    if (!number) throw Error("'" + terminalText(text) + "': the value " + detail::numberProblem(value));
    return {name, *number};
}

std::string descriptionToYaml(const RobotDescription& robot) {
    std::ostringstream out;
    out << "name: " << yamlQuoted(robot.name) << "\n";
    const bool translation = robot.motion == PlatformMotion::translation;
    if (translation) out << "motion: translation  # pose [x, y] of the tool point\n";
    if (!robot.gravity.isZero()) out << "gravity: " << pair(robot.gravity) << "  # [m/s^2]\n";
    if (translation && !robot.home.isZero()) {
        out << "home: " << pair(robot.home.tail<2>()) << "  # [x, y] of the tool point at home\n";
    } else if (!robot.home.isZero()) {
        // the user's order, as the reader takes it (the core's is [theta, x, y])
        const Vector3 user = userPose(robot.home);
        out << "home: [" << text::shortest(user(0)) << ", " << text::shortest(user(1)) << ", "
            << text::shortest(user(2)) << "]  # [x, y, theta] at home\n";
    }
    out << "max_condition: " << text::shortest(robot.max_condition) << "\n";
    if (robot.damping_ratio != RobotDescription{}.damping_ratio) {
        out << "damping_ratio: " << text::shortest(robot.damping_ratio) << "  # of each lumped mode\n";
    }
    if (translation) {
        out << "platform: {mass: " << text::shortest(robot.platform.mass) << "}  # a point mass at the tool point\n";
    } else {
        out << "platform: {mass: " << text::shortest(robot.platform.mass)
            << ", inertia: " << text::shortest(robot.platform.inertia) << ", com: " << pair(robot.platform.com)
            << "}\n";
    }
    out << "limbs:\n";
    for (const LimbDescription& limb : robot.limbs) {
        out << "  - name: " << yamlQuoted(limb.name) << "\n    joints:\n";
        for (const JointDescription& joint : limb.joints) {
            out << "      - {type: "
                << (joint.type == JointType::revolute ? "R, point: " + pair(joint.point)
                                                      : "P, direction: " + pair(joint.direction));
            if (joint.actuated) out << ", actuated: true";
            std::string limits;
            const auto add = [&](const char* key, double value) {
                if (std::isfinite(value))
                    limits += (limits.empty() ? "" : ", ") + std::string(key) + ": " + text::shortest(value);
            };
            add("lower", joint.limits.lower);
            add("upper", joint.limits.upper);
            add("effort", joint.limits.effort);
            add("velocity", joint.limits.velocity);
            if (!limits.empty()) out << ", limits: {" << limits << "}";
            if (joint.damping != 0.0) out << ", damping: " << text::shortest(joint.damping);
            if (joint.friction != 0.0) out << ", friction: " << text::shortest(joint.friction);
            if (joint.stiffness) out << ", stiffness: " << text::shortest(*joint.stiffness);
            out << "}\n";
        }
        out << "    bodies:\n";
        for (const BodyDescription& body : limb.bodies) {
            out << "      - {mass: " << text::shortest(body.mass) << ", inertia: " << text::shortest(body.inertia)
                << ", com: " << pair(body.com);
            if (body.elastic) {
                out << ", elastic: {EA: " << text::shortest(body.elastic->EA)
                    << ", EI: " << text::shortest(body.elastic->EI) << "}";
            }
            out << "}\n";
        }
    }
    return out.str();
}

}  // namespace nocdyn::io
