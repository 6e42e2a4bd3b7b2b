// Closed-form inverse displacement per limb type (limb_ik.hpp).
#include "nocdyn/limb_ik.hpp"

#include <cmath>

#include "limb_ik_impl.hpp"

namespace nocdyn {

Status solveLimb(const LimbModel& limb, int j, const PlatformDisplacement& G, bool angles, LimbData& out) {
    return detail::solveLimbData(limb, j, G, limb.branch, angles, out);
}

Status solveLimb(const LimbModel& limb, int j, int branch, const PlatformDisplacement& G, bool angles, LimbData& out) {
    return detail::solveLimbData(limb, j, G, branch, angles, out);
}

int homeBranch(const LimbModel& limb) {
    const auto sign = [](double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); };
    const bool r1 = limb.type[0] == JointType::revolute;
    const bool r2 = limb.type[1] == JointType::revolute;
    const bool r3 = limb.type[2] == JointType::revolute;
    const auto& p = limb.point_home;
    const auto& d = limb.direction;
    if (r1 && r2 && r3) return sign(cross(p[2] - p[0], p[1] - p[0]));
    if (!r1 && r2 && r3) return sign(d[0].dot(p[2] - p[1]));
    if (r1 && !r2 && r3) return sign(d[1].dot(p[2] - p[0]));
    if (r1 && r2 && !r3) return sign(-d[2].dot(p[1] - p[0]));
    return 0;
}

}  // namespace nocdyn
