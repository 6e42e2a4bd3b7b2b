// Drawable points of the general robot at a pose (drawing.hpp).
#include "nocdyn/drawing.hpp"

#include <cmath>

#include "nocdyn/kinematics.hpp"

namespace nocdyn {

namespace {

/// A planar rigid displacement x -> R x + t, R = [c -s; s c].
struct Rigid {
    double c = 1.0, s = 0.0;
    Vector2 t = Vector2::Zero();
    [[nodiscard]] Vector2 rotate(const Vector2& v) const { return {c * v.x() - s * v.y(), s * v.x() + c * v.y()}; }
    [[nodiscard]] Vector2 apply(const Vector2& x) const { return rotate(x) + t; }
    /// this o other: first other, then this.
    [[nodiscard]] Rigid then(const Rigid& other) const {
        return {c * other.c - s * other.s, s * other.c + c * other.s, apply(other.t)};
    }
};

/// exp(s_k q_k) of joint k at home: a turn about its axis or a slide along its direction.
Rigid jointMotion(const LimbModel& limb, const LimbData& ld, int k) {
    const auto kk = static_cast<std::size_t>(k);
    if (limb.type[kk] == JointType::prismatic) return {1.0, 0.0, ld.q(k) * limb.direction[kk]};
    Rigid turn{ld.cos_q(k), ld.sin_q(k), Vector2::Zero()};
    const Vector2& r = limb.point_home[kk];
    turn.t = r - turn.rotate(r);
    return turn;
}

double railBound(double limit, double fallback) { return std::isfinite(limit) ? limit : fallback; }

}  // namespace

Vector2 jointReferencePoint(const LimbModel& limb, int k) {
    for (const int offset : {0, 1, -1, 2, -2}) {
        const int m = k + offset;
        if (m >= 0 && m < 3 && limb.type[static_cast<std::size_t>(m)] == JointType::revolute) {
            return limb.point_home[static_cast<std::size_t>(m)];
        }
    }
    return Vector2::Zero();  // three P joints: refused by validate(RobotDescription&)
}

Status drawRobot(const Model& model, Data& data, const Pose& p, RobotDrawing& out) {
    if (const Status status = inverseDisplacement(model, data, p); !status) return status;
    out.limbs = model.limbs;
    out.C = p.tail<2>();
    out.theta = p(0);
    const double unlimited = kUnlimitedRail * model.length_scale;
    for (int j = 0; j < model.limbs; ++j) {
        const auto jj = static_cast<std::size_t>(j);
        const LimbModel& limb = model.limb[jj];
        const LimbData& ld = data.limb[jj];
        Rigid inboard;  // B_k, from the base (k = 0) outwards
        for (int k = 0; k < 3; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            const Rigid outboard = inboard.then(jointMotion(limb, ld, k));  // B_(k+1)
            const Vector2 x = jointReferencePoint(limb, k);
            JointDrawing& joint = out.limb[jj].joint[kk];
            joint.type = limb.type[kk];
            joint.actuator = limb.actuator[kk];
            joint.q = ld.q(k);
            joint.position = outboard.apply(x);
            if (joint.type == JointType::prismatic) {
                const Vector2& d = limb.direction[kk];
                joint.direction = inboard.rotate(d);
                joint.rail_start = inboard.apply(x + railBound(limb.limits[kk].lower, -unlimited) * d);
                joint.rail_end = inboard.apply(x + railBound(limb.limits[kk].upper, unlimited) * d);
            } else {
                joint.direction = Vector2::UnitX();
                joint.rail_start = joint.rail_end = joint.position;
            }
            inboard = outboard;
        }
        out.platform[jj] = out.limb[jj].joint[2].position;
    }
    return {};
}

}  // namespace nocdyn
