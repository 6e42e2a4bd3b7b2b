// Validation of robot parameters (see robot.hpp).
#include "nocdyn/robot.hpp"

#include <cmath>
#include <sstream>

#include "nocdyn/error.hpp"

namespace nocdyn {

double RobotParameters::baseCircumradius() const { return base_side / std::sqrt(3.0); }
double RobotParameters::platformCircumradius() const { return platform_side / std::sqrt(3.0); }

namespace {

void requirePositive(double value, const char* field, const std::string& robot) {
    if (!std::isfinite(value) || value <= 0.0) {
        std::ostringstream msg;
        msg << "robot '" << robot << "': " << field << " must be a positive finite number, got "
            << value;
        throw Error(msg.str());
    }
}

}  // namespace

void validate(const RobotParameters& robot) {
    const std::string& name = robot.name;
    requirePositive(robot.base_side, "geometry.base_side", name);
    requirePositive(robot.platform_side, "geometry.platform_side", name);
    requirePositive(robot.link_length, "geometry.link_length", name);
    if (!std::isfinite(robot.link_com) || robot.link_com < 0.0 || robot.link_com > robot.link_length) {
        std::ostringstream msg;
        msg << "robot '" << name << "': geometry.link_com must lie in [0, link_length = "
            << robot.link_length << "] m, got " << robot.link_com;
        throw Error(msg.str());
    }
    requirePositive(robot.slider_mass, "slider.mass", name);
    requirePositive(robot.link_mass, "link.mass", name);
    requirePositive(robot.link_inertia, "link.inertia", name);
    requirePositive(robot.platform_mass, "platform.mass", name);
    requirePositive(robot.platform_inertia, "platform.inertia", name);
    requirePositive(robot.stroke, "actuator.stroke", name);
    requirePositive(robot.peak_force, "actuator.peak_force", name);
    if (!std::isfinite(robot.max_condition) || robot.max_condition <= 1.0) {
        std::ostringstream msg;
        msg << "robot '" << name << "': limits.max_condition must be a finite number > 1, got "
            << robot.max_condition;
        throw Error(msg.str());
    }
    // Reference posture (theta = 0, C = O): every M_j lies (R - r) / 2 from its rail line
    // (eqs. 37-38); the limb closes only when 0 < d_j^M < l (eq. 39).
    const double d_ref = 0.5 * (robot.baseCircumradius() - robot.platformCircumradius());
    if (d_ref <= 0.0) {
        std::ostringstream msg;
        msg << "robot '" << name << "': cannot be assembled at the reference posture: the platform"
            << " (platform_side " << robot.platform_side << " m) must be smaller than the base"
            << " (base_side " << robot.base_side << " m)";
        throw Error(msg.str());
    }
    if (d_ref >= robot.link_length) {
        std::ostringstream msg;
        msg << "robot '" << name << "': cannot be assembled at the reference posture: each platform"
            << " vertex is " << d_ref << " m from its rail but geometry.link_length is only "
            << robot.link_length << " m";
        throw Error(msg.str());
    }
}

}  // namespace nocdyn
