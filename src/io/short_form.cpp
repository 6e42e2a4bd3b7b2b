// The short form of a robot file: the paper's symmetric 3-PRR by its parameters, validated and
// expanded to the general description (see short_form.hpp).
#include "nocdyn/io/short_form.hpp"

#include <cmath>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::io {

double RobotParameters::baseCircumradius() const { return base_side / std::sqrt(3.0); }
double RobotParameters::platformCircumradius() const { return platform_side / std::sqrt(3.0); }

namespace {

/// Requires lo <= value <= hi (NaN fails): "must be positive, in [lo, hi] UNIT; got V".
void requireIn(double value, double lo, double hi, const char* unit, const char* field, const std::string& robot) {
    if (value >= lo && value <= hi) return;
    throw ParameterError(robot, field,
                         "must be positive, in [" + text::number(lo) + ", " + text::number(hi) + "] " + unit +
                             "; got " + text::number(value));
}

}  // namespace

void validate(const RobotParameters& robot) {
    using namespace parameter_limits;
    const std::string& name = robot.name;
    requireIn(robot.base_side, kMinLength, kMaxLength, "m", "geometry.base_side", name);
    requireIn(robot.platform_side, kMinLength, kMaxLength, "m", "geometry.platform_side", name);
    requireIn(robot.link_length, kMinLength, kMaxLength, "m", "geometry.link_length", name);
    if (!(robot.link_com >= 0.0 && robot.link_com <= robot.link_length)) {
        throw ParameterError(name, "geometry.link_com",
                             "must lie in [0, link_length = " + text::number(robot.link_length) + "] m; got " +
                                 text::number(robot.link_com));
    }
    requireIn(robot.slider_mass, kMinMass, kMaxMass, "kg", "slider.mass", name);
    requireIn(robot.link_mass, kMinMass, kMaxMass, "kg", "link.mass", name);
    requireIn(robot.link_inertia, kMinInertia, kMaxInertia, "kg m^2", "link.inertia", name);
    requireIn(robot.platform_mass, kMinMass, kMaxMass, "kg", "platform.mass", name);
    requireIn(robot.platform_inertia, kMinInertia, kMaxInertia, "kg m^2", "platform.inertia", name);
    requireIn(robot.stroke, kMinLength, kMaxLength, "m", "actuator.stroke", name);
    requireIn(robot.peak_force, kMinForce, kMaxForce, "N", "actuator.peak_force", name);
    if (!(robot.max_condition > 1.0 && robot.max_condition <= kMaxCondition)) {
        throw ParameterError(
            name, "limits.max_condition",
            "must be a number in (1, " + text::number(kMaxCondition) + "]; got " + text::number(robot.max_condition));
    }
    // Reference posture (theta = 0, C = O): every M_j lies (R - r) / 2 from its rail line
    // (eqs. 37-38); the limb closes only when 0 < d_j^M < l (eq. 39).
    const double d_ref = 0.5 * (robot.baseCircumradius() - robot.platformCircumradius());
    if (d_ref <= 0.0) {
        throw ParameterError(name, "geometry.platform_side",
                             "cannot be assembled at the reference posture: the platform (platform_side " +
                                 text::number(robot.platform_side) + " m) must be smaller than the base (base_side " +
                                 text::number(robot.base_side) + " m)");
    }
    if (d_ref >= robot.link_length) {
        throw ParameterError(name, "geometry.link_length",
                             "cannot be assembled at the reference posture: each platform vertex is " +
                                 text::number(d_ref) + " m from its rail but geometry.link_length is only " +
                                 text::number(robot.link_length) + " m");
    }
}

RobotDescription expand(const RobotParameters& robot) {
    validate(robot);
    RobotDescription out;
    out.name = robot.name;
    out.max_condition = robot.max_condition;
    out.platform.mass = robot.platform_mass;
    out.platform.inertia = robot.platform_inertia;
    const double R = robot.baseCircumradius();
    const double r = robot.platformCircumradius();
    const double l = robot.link_length;
    // Reference posture (theta = 0, C = O): M_j - B_j has inward distance d = (R - r) / 2 from
    // rail L_j (eqs. 37-38), so phi_Aj = asin(d / l) and A_j = M_j - m_j (eqs. 39-40).
    const double d = 0.5 * (R - r);
    const double sin_A = d / l;
    const double cos_A = std::sqrt((1.0 - sin_A) * (1.0 + sin_A));
    for (int j = 0; j < 3; ++j) {
        const double phi = (j == 0 ? 0.0 : (j == 1 ? 2.0 : -2.0)) * std::numbers::pi / 3.0;  // eq. 8
        const Eigen::Vector2d e(std::cos(phi), std::sin(phi));
        const Eigen::Vector2d n(-e.y(), e.x());
        const double angle = phi - std::numbers::pi / 6.0;
        const Eigen::Vector2d M = r * Eigen::Vector2d(std::cos(angle), std::sin(angle));  // eq. 41
        const Eigen::Vector2d m = l * (cos_A * e + sin_A * n);                            // eq. 40
        const Eigen::Vector2d A = M - m;
        LimbDescription limb;
        limb.name = "limb" + std::to_string(j + 1);
        JointDescription& rail = limb.joints[0];
        rail.type = JointType::prismatic;
        rail.direction = e;
        rail.point = A;
        rail.actuated = true;
        rail.limits.lower = -0.5 * robot.stroke;
        rail.limits.upper = 0.5 * robot.stroke;
        rail.limits.effort = robot.peak_force;
        limb.joints[1].type = JointType::revolute;
        limb.joints[1].point = A;
        limb.joints[2].type = JointType::revolute;
        limb.joints[2].point = M;
        limb.bodies[0] = {robot.slider_mass, 0.0, A, 0, {}};
        limb.bodies[1] = {robot.link_mass, robot.link_inertia, A + (robot.link_com / l) * m, 0, {}};
        out.limbs.push_back(limb);
    }
    validate(out);
    return out;
}

}  // namespace nocdyn::io
