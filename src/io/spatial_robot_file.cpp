// The reader of spatial robot files (`space: spatial`, ../shared/robot-files-spatial.md): every
// field read and checked where the YAML node is at hand, so that each error names the file, the
// node's line, and the limb, joint or body with the field.
#include "spatial_robot_file.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "nocdyn/error.hpp"
#include "nocdyn/printable.hpp"
#include "nocdyn/spatial_description.hpp"
#include "nocdyn/text.hpp"
#include "yaml_util.hpp"

namespace nocdyn::io::detail::spatial {

namespace {

// The planar form's plausibility ranges, carried over.
inline constexpr double kMaxLength = 1.0e3;   // [m]
inline constexpr double kMaxMass = 1.0e6;     // [kg]
inline constexpr double kMaxInertia = 1.0e9;  // [kg m^2]
inline constexpr double kMaxGravity = 1.0e4;  // [m/s^2]
inline constexpr double kMaxCoefficient = 1.0e9;
inline constexpr double kMaxStiffness = 1.0e15;
inline constexpr double kMinStiffness = 1.0e-9;
/// Below it a vector is zero, and a U's axes parallel (the sine of their angle).
inline constexpr double kTiny = 1.0e-9;

std::string vectorText(const Eigen::Vector3d& v) {
    return "[" + text::shortest(v.x()) + ", " + text::shortest(v.y()) + ", " + text::shortest(v.z()) + "]";
}

/// A list of 3 finite numbers at map[key], each of magnitude at most `bound`.
Eigen::Vector3d vector3(const Context& context, const YAML::Node& map, const char* key, double bound,
                        const char* unit) {
    const YAML::Node node = map[key];
    if (!node.IsDefined() || node.IsNull()) fail(context / key, map, "required [x, y, z] is missing");
    if (!node.IsSequence() || node.size() != 3) fail(context / key, node, "expected a list of 3 numbers [x, y, z]");
    Eigen::Vector3d v;
    for (std::size_t i = 0; i < 3; ++i) {
        const Context here = context / (std::string(key) + "[" + std::to_string(i) + "]");
        v(static_cast<Eigen::Index>(i)) = toNumber(here, node[i]);
        if (std::abs(v(static_cast<Eigen::Index>(i))) > bound) {
            fail(here, node[i],
                 "must be at most " + text::number(bound) + " " + unit + " in magnitude, got " +
                     text::number(v(static_cast<Eigen::Index>(i))));
        }
    }
    return v;
}

/// A non-zero axis or direction, normalised (kept as written when unit to round-off, so that
/// a file's unit vectors read back bit for bit).
Eigen::Vector3d unit(const Context& context, const YAML::Node& map, const char* key) {
    Eigen::Vector3d v = vector3(context, map, key, kMaxLength, "");
    const double norm = v.norm();
    if (!(norm > kTiny)) fail(context / key, map[key], "must be a non-zero vector, got " + vectorText(v));
    if (std::abs(norm - 1.0) > 4.0 * std::numeric_limits<double>::epsilon()) v /= norm;
    return v;
}

/// A 3x3 inertia tensor [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]], physically possible.
Eigen::Matrix3d tensor(const Context& context, const YAML::Node& map, const char* key) {
    const YAML::Node node = map[key];
    const Context here = context / key;
    if (!node.IsDefined() || node.IsNull()) fail(here, map, "required 3x3 inertia tensor is missing");
    const char* shape = "expected the 3x3 tensor [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]] [kg m^2]";
    if (!node.IsSequence() || node.size() != 3) fail(here, node, shape);
    Eigen::Matrix3d inertia;
    for (std::size_t i = 0; i < 3; ++i) {
        const YAML::Node row = node[i];
        if (!row.IsSequence() || row.size() != 3) fail(here, row, shape);
        for (std::size_t k = 0; k < 3; ++k) {
            const Context entry =
                context / (std::string(key) + "[" + std::to_string(i) + "][" + std::to_string(k) + "]");
            const double value = toNumber(entry, row[k]);
            if (std::abs(value) > kMaxInertia) {
                fail(entry, row[k],
                     "must be at most " + text::number(kMaxInertia) + " kg m^2 in magnitude, got " +
                         text::number(value));
            }
            inertia(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = value;
        }
    }
    if (const std::string problem = inertiaProblem(inertia); !problem.empty()) fail(here, node, problem);
    return inertia;
}

double mass(const Context& context, const YAML::Node& map) {
    const double m = requireNumber(context, map, "mass");
    requireRange(context, map, "mass", m, 0.0, kMaxMass, "kg");
    return m;
}

/// The keys only R and P joints take (the drive and its friction).
inline constexpr const char* kDriveKeys[] = {"actuated", "limits", "damping", "friction", "stiffness"};

SpatialJointDescription parseJoint(const Context& context, const YAML::Node& node) {
    requireMap(
        context, node,
        {"type", "point", "axis", "direction", "axes", "actuated", "limits", "damping", "friction", "stiffness"});
    SpatialJointDescription joint;
    joint.line = lineOf(node);
    const YAML::Node type = node["type"];
    if (!type.IsDefined()) fail(context / "type", node, "required joint type is missing (R, P, U or S)");
    const std::string name = type.IsScalar() ? type.Scalar() : std::string("?");
    if (name == "R") {
        joint.type = SpatialJointType::revolute;
    } else if (name == "P") {
        joint.type = SpatialJointType::prismatic;
    } else if (name == "U") {
        joint.type = SpatialJointType::universal;
    } else if (name == "S") {
        joint.type = SpatialJointType::spherical;
    } else {
        fail(context / "type", type, "unknown joint type '" + text::printable(name) + "' (expected R, P, U or S)");
    }
    // the geometry keys each type takes
    const auto refuse = [&](const char* key, const char* takes) {
        if (node[key].IsDefined()) {
            fail(context / key, node[key],
                 "a" + std::string(name == "R" || name == "S" ? "n " : " ") + name + " joint takes " + takes +
                     ", not " + key);
        }
    };
    switch (joint.type) {
        case SpatialJointType::revolute:
            refuse("direction", "a point and an axis");
            refuse("axes", "a point and an axis");
            joint.point = vector3(context, node, "point", kMaxLength, "m");
            joint.axis = unit(context, node, "axis");
            break;
        case SpatialJointType::prismatic:
            refuse("point", "a direction");
            refuse("axis", "a direction");
            refuse("axes", "a direction");
            joint.direction = unit(context, node, "direction");
            break;
        case SpatialJointType::universal: {
            refuse("axis", "a point and two axes (axes: [[a1], [a2]])");
            refuse("direction", "a point and two axes (axes: [[a1], [a2]])");
            joint.point = vector3(context, node, "point", kMaxLength, "m");
            const YAML::Node axes = node["axes"];
            if (!axes.IsDefined() || axes.IsNull()) fail(context / "axes", node, "required [[a1], [a2]] is missing");
            if (!axes.IsSequence() || axes.size() != 2) {
                fail(context / "axes", axes,
                     "expected two axes [[a1x, a1y, a1z], [a2x, a2y, a2z]] (a1 in the inboard body, a2 in the "
                     "outboard)");
            }
            // as a map {a1: axes[0], a2: axes[1]} so that each is checked with its line
            YAML::Node pair(YAML::NodeType::Map);
            pair["axes[0]"] = axes[0];
            pair["axes[1]"] = axes[1];
            joint.axis1 = unit(context, pair, "axes[0]");
            joint.axis2 = unit(context, pair, "axes[1]");
            const double sine = joint.axis1.cross(joint.axis2).norm();
            if (!(sine >= kTiny)) {
                fail(context / "axes", axes,
                     "a U joint's two axes must not be parallel (the sine of their angle is " + text::number(sine) +
                         ", below 1e-9)");
            }
            break;
        }
        case SpatialJointType::spherical:
            refuse("axis", "only a point");
            refuse("axes", "only a point");
            refuse("direction", "only a point");
            joint.point = vector3(context, node, "point", kMaxLength, "m");
            break;
    }
    if (joint.type == SpatialJointType::universal || joint.type == SpatialJointType::spherical) {
        if (flag(context, node, "actuated")) {
            fail(context / "actuated", node["actuated"],
                 "a" + std::string(name == "S" ? "n " : " ") + name +
                     " joint cannot be actuated: only R and P joints are driven");
        }
        for (const char* key : kDriveKeys) {
            if (node[key].IsDefined()) {
                fail(context / key, node[key],
                     "a" + std::string(name == "S" ? "n " : " ") + name +
                         " joint takes no actuated, limits, damping, friction or stiffness (only R and P joints do)");
            }
        }
        return joint;
    }
    joint.actuated = flag(context, node, "actuated");
    if (const YAML::Node limits = node["limits"]; limits.IsDefined()) {
        const Context here = context / "limits";
        requireMap(here, limits, {"lower", "upper", "effort", "velocity"});
        JointLimits& lim = joint.limits;
        lim.lower = optionalNumber(here, limits, "lower", lim.lower);
        lim.upper = optionalNumber(here, limits, "upper", lim.upper);
        lim.effort = optionalNumber(here, limits, "effort", lim.effort);
        lim.velocity = optionalNumber(here, limits, "velocity", lim.velocity);
        if (!(lim.lower < lim.upper) || lim.lower > 0.0 || lim.upper < 0.0) {
            fail(here, limits, "need lower < upper with the home value 0 inside [lower, upper]");
        }
        if (!(lim.effort > 0.0)) fail(here / "effort", limits["effort"], "must be a positive number");
        if (!(lim.velocity > 0.0)) fail(here / "velocity", limits["velocity"], "must be a positive number");
    }
    joint.damping = optionalNumber(context, node, "damping", 0.0);
    requireRange(context, node, "damping", joint.damping, 0.0, kMaxCoefficient, "");
    joint.friction = optionalNumber(context, node, "friction", 0.0);
    requireRange(context, node, "friction", joint.friction, 0.0, kMaxCoefficient, "");
    if (node["stiffness"].IsDefined()) {
        const double k = requireNumber(context, node, "stiffness");
        if (k != 0.0 && !(k >= kMinStiffness && k <= kMaxStiffness)) {
            fail(context / "stiffness", node["stiffness"],
                 "must be 0 (free) or in [1e-09, 1e+15] " +
                     std::string(joint.type == SpatialJointType::revolute ? "N m/rad" : "N/m") + ", got " +
                     text::number(k));
        }
        joint.stiffness = k;
    }
    return joint;
}

SpatialBodyDescription parseBody(const Context& context, const YAML::Node& node) {
    requireMap(context, node, {"mass", "com", "inertia"});
    SpatialBodyDescription body;
    body.line = lineOf(node);
    body.mass = mass(context, node);
    body.com = vector3(context, node, "com", kMaxLength, "m");
    body.inertia = tensor(context, node, "inertia");
    return body;
}

/// Reads and checks a `space: spatial` robot file's root (expressions already in scope).
}  // namespace

SpatialRobotDescription parse(const YAML::Node& root, const std::string& source) {
    const Context top{source, ""};
    requireMap(top, root, {"name", "space", "motion", "gravity", "home", "max_condition", "platform", "limbs"});
    SpatialRobotDescription robot;
    robot.source = source;
    robot.name = std::filesystem::path(source).stem().string();
    if (const YAML::Node name = root["name"]; name.IsDefined()) {
        if (!name.IsScalar() || name.Scalar().empty()) fail(top / "name", name, "expected a non-empty string");
        robot.name = name.Scalar();
    }
    const YAML::Node motion = root["motion"];
    if (motion.IsDefined()) {
        if (!motion.IsScalar() || (motion.Scalar() != "full" && motion.Scalar() != "translation"))
            fail(top / "motion", motion, "expected full or translation");
        robot.motion = motion.Scalar() == "translation" ? PlatformMotion::translation : PlatformMotion::full;
    }
    const bool translation = robot.motion == PlatformMotion::translation;
    if (root["gravity"].IsDefined()) robot.gravity = vector3(top, root, "gravity", kMaxGravity, "m/s^2");
    if (const YAML::Node home = root["home"]; home.IsDefined()) {
        const std::size_t n = translation ? 3 : 6;
        if (!home.IsSequence() || home.size() != n) {
            fail(top / "home", home,
                 translation ? "expected [x, y, z] (motion translation)" : "expected [x, y, z, roll, pitch, yaw]");
        }
        for (std::size_t i = 0; i < n; ++i) {
            const Context here = top / ("home[" + std::to_string(i) + "]");
            const double value = toNumber(here, home[i]);
            const double bound = i < 3 ? kMaxLength : std::numbers::pi;
            if (std::abs(value) > bound) {
                fail(here, home[i],
                     "must be at most " + text::number(bound) + (i < 3 ? " m" : " rad") + " in magnitude, got " +
                         text::number(value));
            }
            robot.home(static_cast<Eigen::Index>(i)) = value;
        }
        if (!translation && std::abs(std::cos(robot.home(4))) <= kTiny) {
            fail(top / "home[4]", home[4],
                 "pitch = +-90 degrees, where roll, pitch and yaw are singular: choose another home pose");
        }
    }
    robot.max_condition = optionalNumber(top, root, "max_condition", robot.max_condition);
    if (!(robot.max_condition > 1.0 && robot.max_condition <= 1.0e12))
        fail(top / "max_condition", root["max_condition"], "must be a finite number in (1, 1e12]");

    const YAML::Node platform = root["platform"];
    if (!platform.IsDefined()) fail(top / "platform", root, "required section is missing");
    const Context at_platform = top / "platform";
    requireMap(at_platform, platform, {"mass", "com", "inertia"});
    robot.platform.line = lineOf(platform);
    robot.platform.mass = mass(at_platform, platform);
    if (platform["com"].IsDefined()) robot.platform.com = vector3(at_platform, platform, "com", kMaxLength, "m");
    // required on a full-motion platform; optional (and without effect) on a translating one
    if (!translation || platform["inertia"].IsDefined())
        robot.platform.inertia = tensor(at_platform, platform, "inertia");

    const YAML::Node limbs = root["limbs"];
    if (!limbs.IsDefined() || !limbs.IsSequence()) fail(top / "limbs", root, "expected a list of limbs");
    if (limbs.size() < 2 || limbs.size() > static_cast<std::size_t>(kMaxLimbs)) {
        fail(top / "limbs", limbs,
             "a robot has 2 to " + std::to_string(kMaxLimbs) + " limbs, got " + std::to_string(limbs.size()));
    }
    for (std::size_t j = 0; j < limbs.size(); ++j) {
        const YAML::Node node = limbs[j];
        const Context bare = top / ("limbs[" + std::to_string(j) + "]");
        requireMap(bare, node, {"name", "joints", "bodies"});
        SpatialLimbDescription limb;
        limb.line = lineOf(node);
        limb.name = "limb" + std::to_string(j + 1);
        if (const YAML::Node name = node["name"]; name.IsDefined()) {
            if (!name.IsScalar() || name.Scalar().empty()) fail(bare / "name", name, "expected a non-empty string");
            limb.name = name.Scalar();
        }
        // every later message names the limb
        const Context context{source, bare.field + " (" + text::printable(limb.name) + ")"};
        const YAML::Node joints = node["joints"];
        if (!joints.IsDefined() || !joints.IsSequence() || joints.size() == 0) {
            fail(context / "joints", joints.IsDefined() ? joints : node,
                 "expected a list of joints (R, P, U or S), base to platform");
        }
        for (std::size_t k = 0; k < joints.size(); ++k) {
            limb.joints.push_back(parseJoint(context / ("joints[" + std::to_string(k) + "]"), joints[k]));
            if (limb.freedoms() > 6) {
                fail(context / ("joints[" + std::to_string(k) + "]"), joints[k],
                     "a limb has at most six joint freedoms (R, P 1; U 2; S 3), but " + limb.type() + " has " +
                         std::to_string(limb.freedoms()));
            }
        }
        if (!translation && limb.freedoms() != 6) {
            fail(context / "joints", joints,
                 "motion full needs exactly six joint freedoms per limb (R, P 1; U 2; S 3), but " + limb.type() +
                     " has " + std::to_string(limb.freedoms()));
        }
        const std::size_t expected = joints.size() - 1;
        const YAML::Node bodies = node["bodies"];
        if (!bodies.IsDefined() || !bodies.IsSequence() || bodies.size() != expected) {
            const std::string got =
                bodies.IsDefined() && bodies.IsSequence() ? std::to_string(bodies.size()) : std::string("none");
            fail(context / "bodies", bodies.IsDefined() ? bodies : node,
                 "a limb of " + std::to_string(joints.size()) + " listed joints (" + limb.type() + ") has " +
                     std::to_string(expected) +
                     " bodies, one between each pair of consecutive joints (U and S carry no mass), got " + got);
        }
        for (std::size_t b = 0; b < expected; ++b) {
            limb.bodies.push_back(parseBody(context / ("bodies[" + std::to_string(b) + "]"), bodies[b]));
        }
        robot.limbs.push_back(std::move(limb));
    }
    if (!(robot.totalMass() > 0.0)) fail(at_platform / "mass", platform, "the robot has no mass at all");
    const int actuators = robot.actuatorCount();
    if (actuators < robot.taskDimension()) {
        fail(top / "limbs", limbs,
             "a platform of " + std::to_string(robot.taskDimension()) + " pose coordinates (motion " +
                 (translation ? "translation" : "full") + ") needs at least " + std::to_string(robot.taskDimension()) +
                 " actuated joints, got " + std::to_string(actuators));
    }
    if (translation) {
        // the limbs keep the platform's orientation at home: no twist every limb allows turns it
        const Eigen::Matrix<double, 3, Eigen::Dynamic> free = freeRotationsAtHome(robot);
        if (free.cols() > 0) {
            // a readable axis: the largest component positive, round-off cleared
            const auto readable = [](Eigen::Vector3d axis) {
                Eigen::Index largest = 0;
                axis.cwiseAbs().maxCoeff(&largest);
                if (axis(largest) < 0.0) axis = -axis;
                for (Eigen::Index i = 0; i < 3; ++i) axis(i) = std::abs(axis(i)) < 1e-12 ? 0.0 : axis(i);
                return text::format("[%.6g, %.6g, %.6g]", axis(0), axis(1), axis(2));
            };
            std::string axes;
            if (free.cols() == 1) {
                axes = readable(free.col(0));
            } else if (free.cols() == 2) {
                axes = "any axis normal to " + readable(free.col(0).cross(free.col(1)));
            } else {
                axes = "any axis";
            }
            fail(top / "motion", motion,
                 "translation, but at home the limbs leave the platform free to turn about " + axes +
                     " (every limb's joint screws allow that rotation): their constraints must keep the "
                     "platform's orientation");
        }
    }
    return robot;
}

}  // namespace nocdyn::io::detail::spatial
