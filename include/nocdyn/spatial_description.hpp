// A spatial parallel robot as described in a robot file with `space: spatial`
// (../shared/robot-files-spatial.md is the schema): a rigid platform joined to the base by limbs,
// each a serial chain of R, P, U and S joints with one moving body between consecutive listed
// joints (U and S carry no mass). Everything is given at a home posture where every joint
// variable is 0: points, axes and directions in the base frame, SI units, radians.
//
// Joint screws at home (the base frame's origin as reference point, s = [angular; linear]):
// R, s = [a; p x a] (axis a through p); P, s = [0; d]; U, two R screws through its point (a1
// fixed in the inboard body, then a2 in the outboard body); S, three R screws through its point
// along the base axes. The pose is [x, y, z, roll, pitch, yaw] with R = Rz(yaw) Ry(pitch)
// Rx(roll) (motion full), or [x, y, z] (motion translation: the platform keeps the base frame's
// orientation).
//
// Nothing here computes kinematics or dynamics: the description is read and checked
// (io/robot_file.hpp); nocdyn/spatial.hpp computes them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/description.hpp"

namespace nocdyn {

enum class SpatialJointType { revolute, prismatic, universal, spherical };

struct SpatialJointDescription {
    SpatialJointType type = SpatialJointType::revolute;
    Eigen::Vector3d point = Eigen::Vector3d::Zero();       ///< R, U, S: a point of the axis / centre at home [m]
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();       ///< R: the axis at home (unit)
    Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  ///< P: the direction at home (unit)
    /// U: a1 (fixed in the inboard body) and a2 (fixed in the outboard body) at home, unit.
    Eigen::Vector3d axis1 = Eigen::Vector3d::UnitX();
    Eigen::Vector3d axis2 = Eigen::Vector3d::UnitY();
    bool actuated = false;            ///< R and P only
    JointLimits limits;               ///< R and P only; absent ones infinite
    double damping = 0.0;             ///< R and P only [N s/m or N m s/rad]
    double friction = 0.0;            ///< R and P only [N or N m]
    std::optional<double> stiffness;  ///< R and P only [N/m or N m/rad]
    int line = 0;                     ///< line in the robot file (0 when not read from a file)

    /// The joint's freedoms: R, P 1; U 2; S 3.
    [[nodiscard]] int freedoms() const;
    /// 'R', 'P', 'U' or 'S'.
    [[nodiscard]] char letter() const;
};

/// A moving body: mass, c.o.m. and the 3x3 inertia tensor about it (base frame at home; the
/// platform's in the platform frame). The tensor's entries as URDF's: Ixy = -sum m x y.
struct SpatialBodyDescription {
    double mass = 0.0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    int line = 0;
};

struct SpatialLimbDescription {
    std::string name;                             ///< e.g. "limb1"
    std::vector<SpatialJointDescription> joints;  ///< base to platform; the last one joins the platform
    std::vector<SpatialBodyDescription> bodies;   ///< joints.size() - 1: body k between joints k and k + 1
    int line = 0;

    /// "UPS", "RUU", ...: the joint types, base to platform.
    [[nodiscard]] std::string type() const;
    /// The sum of its joints' freedoms.
    [[nodiscard]] int freedoms() const;
};

struct SpatialRobotDescription {
    std::string name = "robot";
    PlatformMotion motion = PlatformMotion::full;
    std::string source;  ///< the file it came from, for messages
    Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
    /// The platform pose at home [x, y, z, roll, pitch, yaw] (motion translation: the angles 0).
    Eigen::Matrix<double, 6, 1> home = Eigen::Matrix<double, 6, 1>::Zero();
    double max_condition = 1.0e4;
    SpatialBodyDescription platform;  ///< com and inertia in the platform frame
    std::vector<SpatialLimbDescription> limbs;

    /// The pose coordinates: 6 (motion full) or 3 (translation).
    [[nodiscard]] int taskDimension() const { return motion == PlatformMotion::full ? 6 : 3; }
    [[nodiscard]] int actuatorCount() const;
    /// The platform's and every body's mass [kg].
    [[nodiscard]] double totalMass() const;
};

/// The joint screws of a limb at home, one column per freedom (6 x freedoms), rows
/// [angular; linear] about the base frame's origin.
[[nodiscard]] Eigen::Matrix<double, 6, Eigen::Dynamic> limbScrews(const SpatialLimbDescription& limb);

/// The platform's rotations the limbs all allow at home: an orthonormal basis (3 x r, r = 0 when
/// the limbs keep the platform's orientation) of the angular parts of the twists in the
/// intersection of the limbs' screw spans.
[[nodiscard]] Eigen::Matrix<double, 3, Eigen::Dynamic> freeRotationsAtHome(const SpatialRobotDescription& robot);

/// Empty when the 3x3 inertia tensor is physically possible (symmetric, positive semi-definite,
/// the triangle inequalities of its principal moments, each within 1e-12 of the largest
/// principal moment), else the reason.
[[nodiscard]] std::string inertiaProblem(const Eigen::Matrix3d& inertia);

}  // namespace nocdyn
