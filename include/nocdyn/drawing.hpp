// What a picture of the robot shows at a platform pose: every joint where it is, the rails of
// the prismatic joints with their stroke, the links, the platform polygon and the operation
// point C. Pure geometry, no drawing library: the animation page and the static frames of the
// CLI draw these points.
//
// The robot file gives every joint at home (all q = 0), so body b of a limb is placed by the
// product of exponentials of the joints inboard of it (description.hpp):
//   B_0 = identity (base),  B_(k+1) = B_k o exp(s_k q_k),
// R at point r: x -> Rot(q)(x - r) + r;  P along d: x -> x + q d;
// and B_3 is the platform's displacement G(x) = Rot(dtheta)(x - C_home) + C (limb_ik.hpp).
// Joint k joins B_k (inboard) to B_(k+1) (outboard). A P joint has no point of its own: it is
// drawn at a reference point x_k, the axis of the nearest R joint in the chain at home, which
// slides with the outboard body along a rail fixed to the inboard body.
#pragma once

#include <array>

#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// One joint as drawn (base frame, metres).
struct JointDrawing {
    JointType type = JointType::revolute;
    int actuator = -1;                     ///< actuator index, or -1
    double q = 0.0;                        ///< joint variable [rad or m]
    Vector2 position = Vector2::Zero();    ///< R: axis; P: reference point on the outboard body
    Vector2 direction = Vector2::UnitX();  ///< P: current unit direction (turns with B_k)
    Vector2 rail_start = Vector2::Zero();  ///< P: B_k(x_k + lower d_k); R: the axis
    Vector2 rail_end = Vector2::Zero();    ///< P: B_k(x_k + upper d_k); R: the axis
};

/// One limb: its three joints, base to platform. Body 1 is drawn from joint 1 to joint 2,
/// body 2 from joint 2 to joint 3.
struct LimbDrawing {
    std::array<JointDrawing, 3> joint{};
};

/// Everything drawable at one pose. Fixed capacity: filling it allocates nothing.
struct RobotDrawing {
    int limbs = 0;
    std::array<LimbDrawing, kMaxLimbs> limb{};
    /// Platform polygon: vertex j is limb j's platform joint (its position).
    std::array<Vector2, kMaxLimbs> platform{};
    Vector2 C = Vector2::Zero();  ///< operation point [m]
    double theta = 0.0;           ///< platform orientation [rad]
};

/// Rail extent used for a P joint without a range limit: +-kUnlimitedRail * model.length_scale.
inline constexpr double kUnlimitedRail = 0.5;

/// The reference point x_k of joint k at home (base frame): its axis for an R joint; for a P
/// joint the axis of the nearest R joint in the chain (outboard first).
[[nodiscard]] Vector2 jointReferencePoint(const LimbModel& limb, int k);

/// Fills `out` for pose p = [theta, x_c, y_c] (eq. 1): runs the inverse displacement
/// (kinematics.hpp, home branches) into `data`, then places every body. Fails as
/// inverseDisplacement (unreachable, singular_limb, not_finite), leaving `out` unspecified.
Status drawRobot(const Model& model, Data& data, const Pose& p, RobotDrawing& out);

}  // namespace nocdyn
