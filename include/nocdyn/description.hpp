// A planar parallel robot as described in a robot file, general form: a rigid platform
// joined to the base by two or more limbs, each a serial chain of three 1-DOF joints (R or P)
// with two moving bodies between them. Everything is given at a home posture at which every
// joint variable is zero (product of exponentials): points and directions in the base frame,
// SI units, radians.
//
// Joint variable q: R, the counter-clockwise angle of the outboard body relative to the
// inboard one; P, the displacement of the outboard body along the joint direction (which
// turns with the body that carries the joint). Actuators are numbered in file order (limbs in
// order, joints in chain order). The friction force of a joint on its outboard body is
// -(damping q' + friction sign q').
//
// The symmetric 3-PRR of the paper (the short form of a robot file) expands to this form in io
// (io/short_form.hpp). Nothing here computes kinematics beyond the home posture.
#pragma once

#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace nocdyn {

enum class JointType { revolute, prismatic };

/// Limits of one joint; absent ones are infinite.
struct JointLimits {
    double lower = -std::numeric_limits<double>::infinity();    ///< smallest q [m or rad]
    double upper = std::numeric_limits<double>::infinity();     ///< largest q [m or rad]
    double effort = std::numeric_limits<double>::infinity();    ///< peak |force| or |torque| [N, N m]
    double velocity = std::numeric_limits<double>::infinity();  ///< peak |q'| [m/s, rad/s]
};

struct JointDescription {
    JointType type = JointType::revolute;
    Eigen::Vector2d point = Eigen::Vector2d::Zero();       ///< R: axis at home, base frame [m]
    Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  ///< P: direction at home (unit after validation)
    bool actuated = false;
    JointLimits limits;
    double damping = 0.0;   ///< viscous coefficient [N s/m or N m s/rad]
    double friction = 0.0;  ///< Coulomb force or torque [N or N m]
    int line = 0;           ///< line in the robot file (0 when not read from a file)
    /// Spring about the joint's position at the pose analysed [N/m for P, N m/rad for R]
    /// (analysis/stiffness.hpp). Actuated: the drive's stiffness, absent = locked (rigid),
    /// 0 = a force actuator. Passive: a flexure hinge, absent = free.
    std::optional<double> stiffness;
};

/// A straight, uniform Euler-Bernoulli beam between a body's two (revolute) joints.
struct ElasticBeam {
    double EA = 0.0;  ///< axial rigidity [N]
    double EI = 0.0;  ///< bending rigidity in the plane [N m^2]
};

/// A moving body: mass, moment of inertia about its c.o.m., c.o.m. at home (base frame).
struct BodyDescription {
    double mass = 0.0;                              ///< [kg]
    double inertia = 0.0;                           ///< about the c.o.m. [kg m^2]
    Eigen::Vector2d com = Eigen::Vector2d::Zero();  ///< base frame, at home [m]
    int line = 0;
    std::optional<ElasticBeam> elastic;  ///< absent: rigid
};

struct LimbDescription {
    std::string name;                        ///< e.g. "limb1"
    std::array<JointDescription, 3> joints;  ///< base to platform
    std::array<BodyDescription, 2> bodies;   ///< body 1 between joints 1 and 2, body 2 between 2 and 3
    int line = 0;

    /// "RRR", "PRR", ...: the joint types, base to platform.
    [[nodiscard]] std::string type() const;
};

struct PlatformDescription {
    double mass = 0.0;                              ///< [kg]
    double inertia = 0.0;                           ///< about its c.o.m. [kg m^2]
    Eigen::Vector2d com = Eigen::Vector2d::Zero();  ///< in the platform frame (origin C) [m]
    int line = 0;
};

/// What the platform does (robot file key `motion`): turn and translate (pose [theta, x, y]), or
/// translate only (pose [x, y]: a point tool where every limb's last R joint meets, the
/// platform a point mass there, its rotation no coordinate).
enum class PlatformMotion { full, translation };

struct RobotDescription {
    std::string name = "robot";
    PlatformMotion motion = PlatformMotion::full;
    std::string source;                                 ///< the file it came from, for messages
    Eigen::Vector2d gravity = Eigen::Vector2d::Zero();  ///< base frame [m/s^2]
    /// Platform pose [theta, x, y] at home (motion translation: theta = 0 and [x, y] the tool point).
    Eigen::Vector3d home = Eigen::Vector3d::Zero();
    double max_condition = 1.0e4;  ///< largest condition number accepted
    /// Damping ratio zeta of each mode of the lumped compliant model (stiffness.hpp), modal
    /// damping C = M Phi diag(2 zeta w_i) Phi^T M: 0.02 by default, a bolted aluminium or steel
    /// structure (0.005 to 0.02 welded or monolithic, 0.02 to 0.05 bolted, up to 0.1 and more
    /// with a damped drive loop). Used only when compliance is declared.
    double damping_ratio = 0.02;
    PlatformDescription platform;
    std::vector<LimbDescription> limbs;

    /// Number of actuated joints.
    [[nodiscard]] int actuatorCount() const;
    /// Whether any joint has a stiffness or any body is elastic.
    [[nodiscard]] bool hasCompliance() const;
    /// Whether any body is elastic.
    [[nodiscard]] bool hasElasticBody() const;
};

/// Largest number of limbs and actuators a model holds (fixed-capacity storage).
inline constexpr int kMaxLimbs = 6;
inline constexpr int kMaxActuators = 3 * kMaxLimbs;

/// Throws nocdyn::Error, naming the source file, line, limb, joint and field, when the
/// description is not a robot nocdyn can model: fewer than 2 or more than kMaxLimbs limbs,
/// fewer than 3 actuated joints (2 with motion translation), a zero P direction, non-finite numbers, negative or
/// implausible masses and inertias, a zero-mass robot, inconsistent limits, a limb of three
/// prismatic joints, a negative or non-finite stiffness, an EA or EI not positive, an elastic
/// body not between two revolute joints (or of zero length); with motion translation, a limb
/// whose last joint is not R, last R joints that do not meet at one point (the tool point, at
/// home), a last joint actuated or with limits, damping, friction or stiffness, a platform with
/// an inertia or a c.o.m. off the tool point. Normalises P directions to unit length. The posture checks
/// (every limb closes and is regular at home) are made by the Model.
void validate(RobotDescription& robot);

/// "SOURCE:LINE: " (or "SOURCE: " or "" when unknown), to prefix messages.
[[nodiscard]] std::string where(const RobotDescription& robot, int line);

}  // namespace nocdyn
