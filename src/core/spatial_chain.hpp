// A spatial limb's chain as products of exponentials, shared by the inverse kinematics
// (spatial.cpp) and the direct kinematics (spatial_direct_kinematics.cpp). Not part of the API.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "nocdyn/spatial.hpp"

namespace nocdyn::spatial::chain {

/// A rigid displacement x -> R x + t.
struct Move {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    [[nodiscard]] Move then(const Move& o) const { return {R * o.R, R * o.t + t}; }
};

/// exp(s q) of one freedom: a rotation by q about the axis through its point, or a translation
/// by q along its direction.
inline Move freedomMove(const Freedom& f, double q) {
    if (!f.revolute) return {Eigen::Matrix3d::Identity(), q * f.axis};
    const Eigen::Matrix3d R = Eigen::AngleAxisd(q, f.axis).toRotationMatrix();
    return {R, f.point - R * f.point};
}

/// The screw of freedom f carried by the displacement g: Ad_g s.
inline Vector6 carriedScrew(const Freedom& f, const Move& g) {
    Vector6 s;
    if (f.revolute) {
        const Eigen::Vector3d a = g.R * f.axis;
        s << a, (g.R * f.point + g.t).cross(a);
    } else {
        s << Eigen::Vector3d::Zero(), g.R * f.axis;
    }
    return s;
}

}  // namespace nocdyn::spatial::chain
