// Inverse displacement of one limb in closed form: the only code that depends on the limb
// type. Given the platform's displacement from home (rotation dtheta, current C), finds the
// joint variables q_1..q_3 of the limb on its home branch.
//
// With G(x) = Rot(dtheta) (x - C_home) + C the platform's displacement, each type reduces
// to one planar construction:
//   RRR        circle (r_1, |r_2 - r_1|) meets circle (G(r_3), |r_3 - r_2|)   two branches
//   PRR, RRP   line meets circle                                              two branches
//   RPR        line meets circle (in the first body's frame)                  two branches
//   PRP, RPP, PPR   2 x 2 linear system (the R angle is dtheta)               one solution
// A branch is the sign of (P - centre) . w (line and circle, w along the line) or of the
// elbow's side (two circles) at home; it is kept for every pose.
#pragma once

#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Platform displacement from home: G(x) = Rot(dtheta) x + C for x relative to C_home.
struct PlatformDisplacement {
    double dtheta = 0.0;
    double cos_dtheta = 1.0;
    double sin_dtheta = 0.0;
    Vector2 C = Vector2::Zero();

    [[nodiscard]] Vector2 rotate(const Vector2& v) const {
        return {cos_dtheta * v.x() - sin_dtheta * v.y(), sin_dtheta * v.x() + cos_dtheta * v.y()};
    }
    [[nodiscard]] Vector2 apply(const Vector2& x) const { return rotate(x) + C; }
};

/// Solves limb `j` for q, cos q and sin q (R joints). Angles of R joints are computed only
/// when `angles` is set or the joint is actuated (the rest of the model needs only cos and
/// sin). Fails with unreachable (value: distance out of reach [m]) or singular_limb.
Status solveLimb(const LimbModel& limb, int j, const PlatformDisplacement& G, bool angles, LimbData& out);
/// The same on a chosen branch (+1 or -1; limb.branch is the home branch, and the types with
/// one solution ignore it): the limb's other assembly for the same platform pose.
Status solveLimb(const LimbModel& limb, int j, int branch, const PlatformDisplacement& G, bool angles, LimbData& out);

/// The branch (+1 / -1, 0 for single-solution types) a limb has at home; 0 also when the
/// home posture is a branch point (then the Model reports the limb singular at home).
[[nodiscard]] int homeBranch(const LimbModel& limb);

}  // namespace nocdyn
