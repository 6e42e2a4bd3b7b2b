// Human-readable descriptions of the 3-PRR kernel's per-sample failures.
#include "nocdyn/prr3/status.hpp"

#include <cmath>
#include <sstream>

#include "nocdyn/io/short_form.hpp"

namespace nocdyn::prr3 {

std::string describe(const Status& status, const io::RobotParameters& robot) {
    std::ostringstream out;
    out.precision(6);
    const int j = status.limb + 1;  // the paper numbers limbs 1..3
    switch (status.code) {
        case StatusCode::ok:
            return "ok";
        case StatusCode::outside_workspace:
            if (std::isnan(status.value)) {
                out << "pose outside the workspace: limb " << j << ": the distance d_" << j
                    << "^M from platform vertex M_" << j << " to rail line L_" << j
                    << " is not a number (a non-finite pose or input)";
            } else if (status.value <= 0.0) {
                out << "pose outside the workspace: limb " << j << ": platform vertex M_" << j << " is "
                    << -status.value * 1e3 << " mm on or beyond its rail line L_" << j << " (d_" << j
                    << "^M = " << status.value << " m must be > 0)";
            } else {
                out << "pose outside the workspace: limb " << j << ": platform vertex M_" << j << " is " << status.value
                    << " m from rail line L_" << j << ", beyond the link length l = " << robot.link_length << " m by "
                    << (status.value - robot.link_length) * 1e3 << " mm";
            }
            return out.str();
        case StatusCode::singular_forward_jacobian:
            out << "singular posture: the forward Jacobian H has condition number " << status.value << " (limit "
                << robot.max_condition << ")";
            return out.str();
        case StatusCode::singular_inverse_jacobian:
            out << "singular posture: limb " << j << ": link A_" << j << "M_" << j
                << " is nearly normal to its rail; D has condition number " << status.value << " (limit "
                << robot.max_condition << ")";
            return out.str();
        case StatusCode::stroke_exceeded:
            if (!std::isfinite(status.value)) {
                out << "actuator displacement not finite: limb " << j << ": u_" << j << " = " << status.value << " m";
                return out.str();
            }
            out << "actuator stroke exceeded: limb " << j << ": u_" << j << " = " << status.value * 1e3
                << " mm, but the stroke allows +-" << robot.stroke * 0.5e3 << " mm about the reference posture";
            return out.str();
        case StatusCode::force_exceeded:
            if (!std::isfinite(status.value)) {
                out << "actuator force not finite: limb " << j << ": tau_" << j << " = " << status.value
                    << " N (a non-finite pose, velocity or acceleration)";
                return out.str();
            }
            out << "actuator peak force exceeded: limb " << j << ": tau_" << j << " = " << status.value
                << " N, peak force " << robot.peak_force << " N";
            return out.str();
    }
    return "unknown status";
}

}  // namespace nocdyn::prr3
