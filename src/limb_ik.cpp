// Closed-form inverse displacement per limb type (limb_ik.hpp).
#include "nocdyn/limb_ik.hpp"

#include <cmath>

#include "limb_ik_impl.hpp"

namespace nocdyn {

Status solveLimb(const LimbModel& limb, int j, const PlatformDisplacement& G, bool angles, LimbData& out) {
    detail::JointSolution solution;
    if (const Status status = detail::solveJoints(limb, j, G, solution); !status) return status;
    for (int k = 0; k < 3; ++k) {
        out.q(k) = solution.q(k);
        out.cos_q(k) = solution.c(k);
        out.sin_q(k) = solution.s(k);
        if (limb.type[static_cast<std::size_t>(k)] != JointType::revolute) continue;
        if (angles || limb.actuator[static_cast<std::size_t>(k)] >= 0) {
            out.q(k) = detail::atan2Of(out.sin_q(k), out.cos_q(k));
        }
    }
    return {};
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
