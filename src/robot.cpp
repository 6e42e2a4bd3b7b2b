// Validation of robot parameters (see robot.hpp).
#include "nocdyn/robot.hpp"

#include <cmath>
#include <sstream>

#include "nocdyn/error.hpp"

namespace nocdyn {

double RobotParameters::baseCircumradius() const { return base_side / std::sqrt(3.0); }
double RobotParameters::platformCircumradius() const { return platform_side / std::sqrt(3.0); }

namespace {

std::string formatted(double value) {
    std::ostringstream out;
    out.precision(6);
    out << value;
    return out.str();
}

/// Requires lo <= value <= hi (NaN fails): "must be positive, in [lo, hi] UNIT; got V".
void requireIn(double value, double lo, double hi, const char* unit, const char* field, const std::string& robot) {
    if (value >= lo && value <= hi) return;
    throw ParameterError(
        robot, field,
        "must be positive, in [" + formatted(lo) + ", " + formatted(hi) + "] " + unit + "; got " + formatted(value));
}

}  // namespace

void validate(const RobotParameters& robot) {
    using namespace parameter_limits;
    const std::string& name = robot.name;
    requireIn(robot.base_side, kMinLength, kMaxLength, "m", "geometry.base_side", name);
    requireIn(robot.platform_side, kMinLength, kMaxLength, "m", "geometry.platform_side", name);
    requireIn(robot.link_length, kMinLength, kMaxLength, "m", "geometry.link_length", name);
    if (!(robot.link_com >= 0.0 && robot.link_com <= robot.link_length)) {
        throw ParameterError(
            name, "geometry.link_com",
            "must lie in [0, link_length = " + formatted(robot.link_length) + "] m; got " + formatted(robot.link_com));
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
            "must be a number in (1, " + formatted(kMaxCondition) + "]; got " + formatted(robot.max_condition));
    }
    // Reference posture (theta = 0, C = O): every M_j lies (R - r) / 2 from its rail line
    // (eqs. 37-38); the limb closes only when 0 < d_j^M < l (eq. 39).
    const double d_ref = 0.5 * (robot.baseCircumradius() - robot.platformCircumradius());
    if (d_ref <= 0.0) {
        throw ParameterError(name, "geometry.platform_side",
                             "cannot be assembled at the reference posture: the platform (platform_side " +
                                 formatted(robot.platform_side) + " m) must be smaller than the base (base_side " +
                                 formatted(robot.base_side) + " m)");
    }
    if (d_ref >= robot.link_length) {
        throw ParameterError(name, "geometry.link_length",
                             "cannot be assembled at the reference posture: each platform vertex is " +
                                 formatted(d_ref) + " m from its rail but geometry.link_length is only " +
                                 formatted(robot.link_length) + " m");
    }
}

}  // namespace nocdyn
