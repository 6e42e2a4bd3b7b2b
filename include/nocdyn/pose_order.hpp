// The pose as a user writes and reads it: [x, y, theta] (command line, tables, JSON, Python).
// The core keeps the NOC's planar twist order [theta, x, y] (eq. 5) inside; these functions are
// where the two orders meet.
#pragma once

#include "nocdyn/planar.hpp"

namespace nocdyn {

/// [x, y, theta] of the core's pose [theta, x, y].
[[nodiscard]] inline Vector3 userPose(const Pose& p) { return {p(1), p(2), p(0)}; }
/// The core's pose [theta, x, y] of a user's [x, y, theta].
[[nodiscard]] inline Pose corePose(const Vector3& user) { return {user(2), user(0), user(1)}; }
/// P with p = P p_user: a map on the core's pose coordinates times P acts on the user's order
/// (A P), and a quadratic form becomes P^T I P.
[[nodiscard]] inline Matrix3 userToCoreMap() {
    return (Matrix3() << 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0).finished();
}

}  // namespace nocdyn
