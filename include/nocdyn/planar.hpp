// Planar screw algebra (paper Sections III and IV-A).
//
// In the plane, a twist is t = [omega; v] (eq. 10): the angular rate about Z and the
// velocity of a reference point (for a body's dynamics, its centre of mass). A wrench is
// w = [n; f] (eq. 11): the moment about Z at that point and the force. An inertia dyad is
// M = diag(I, m, m) (eq. 9), constant in the plane because I is taken about the c.o.m.
// E is the rotation of a plane vector through +90 degrees (eq. 4a).
//
// Nothing here is specific to any robot architecture.
#pragma once

#include <cmath>

#include <Eigen/Core>

namespace nocdyn {

using Vector2 = Eigen::Vector2d;
using Vector3 = Eigen::Vector3d;
using Matrix2 = Eigen::Matrix2d;
using Matrix3 = Eigen::Matrix3d;

/// Planar twist [omega; v_x; v_y] (eq. 10) [rad/s, m/s].
using Twist = Eigen::Vector3d;
/// Planar wrench [n; f_x; f_y] (eq. 11) [N m, N].
using Wrench = Eigen::Vector3d;
/// Platform pose p = [theta; x_c; y_c] (eq. 1) [rad, m, m].
using Pose = Eigen::Vector3d;

/// Inertia dyad of a rigid body in the plane (eq. 9). Stored as its diagonal.
struct InertiaDyad {
    double inertia = 0.0;  ///< I_i: moment of inertia about Z at the c.o.m. [kg m^2]
    double mass = 0.0;     ///< m_i [kg]

    /// The full 3x3 matrix diag(I, m, m) of eq. 9.
    [[nodiscard]] Matrix3 matrix() const { return Eigen::Vector3d(inertia, mass, mass).asDiagonal(); }
};

/// E v: v rotated through +90 degrees about Z (eq. 4a, E = [0 -1; 1 0]).
[[nodiscard]] inline Vector2 perp(const Vector2& v) { return {-v.y(), v.x()}; }

/// The scalar planar cross product a x b = a_x b_y - a_y b_x = (E a) . b.
[[nodiscard]] inline double cross(const Vector2& a, const Vector2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Unit vector at angle phi from the X axis.
[[nodiscard]] inline Vector2 unitVector(double phi) { return {std::cos(phi), std::sin(phi)}; }

/// Planar Pluecker array of a revolute axis through point a, expressed at reference point c:
/// [1; E (c - a)] (the columns of J_j in eq. 4a).
[[nodiscard]] inline Twist revoluteTwist(const Vector2& c_minus_a) { return {1.0, -c_minus_a.y(), c_minus_a.x()}; }

/// Planar Pluecker array of a prismatic joint along unit vector e: [0; e] (eq. 24).
[[nodiscard]] inline Twist prismaticTwist(const Vector2& e) { return {0.0, e.x(), e.y()}; }

/// S(c): the platform twist referred to O from the pose rates, xi_P = S(c) dp/dt, with
/// c = (x_c, y_c) the platform's reference point (eq. 5 in the pose's own rates):
/// S(c) = [1 0 0; c_y 1 0; -c_x 0 1].
[[nodiscard]] inline Matrix3 platformTwistMap(const Vector2& c) {
    return (Matrix3() << 1.0, 0.0, 0.0, c.y(), 1.0, 0.0, -c.x(), 0.0, 1.0).finished();
}

/// S(c) dp/dt without forming S: [omega; v_x + omega c_y; v_y - omega c_x].
[[nodiscard]] inline Twist platformTwistOfPoseRate(const Vector2& c, const Twist& dp) {
    return {dp(0), dp(1) + dp(0) * c.y(), dp(2) - dp(0) * c.x()};
}

/// dS/dt at the pose rates dp/dt = [omega; v_c]: [0 0 0; v_y 0 0; -v_x 0 0].
[[nodiscard]] inline Matrix3 platformTwistMapRate(const Twist& dp) {
    return (Matrix3() << 0.0, 0.0, 0.0, dp(2), 0.0, 0.0, -dp(1), 0.0, 0.0).finished();
}

/// S(c)^-1 xi_P: the pose rates [omega; v_c] of the platform twist xi_P referred to O.
[[nodiscard]] inline Twist poseRateOfPlatformTwist(const Vector2& c, const Twist& xi_P) {
    return {xi_P(0), xi_P(1) - xi_P(0) * c.y(), xi_P(2) + xi_P(0) * c.x()};
}

/// S(c)^T w: the generalized force in the pose coordinates of a wrench w referred to O,
/// [n + c_y f_x - c_x f_y; f_x; f_y].
[[nodiscard]] inline Vector3 poseForceOfPlatformWrench(const Vector2& c, const Wrench& w) {
    return {w(0) + c.y() * w(1) - c.x() * w(2), w(1), w(2)};
}

/// S(c)^-T Q: the wrench referred to O whose generalized force in the pose coordinates is Q,
/// [Q_0 - c_y Q_1 + c_x Q_2; Q_1; Q_2].
[[nodiscard]] inline Wrench platformWrenchOfPoseForce(const Vector2& c, const Vector3& Q) {
    return {Q(0) - c.y() * Q(1) + c.x() * Q(2), Q(1), Q(2)};
}

/// Kinetic energy of a body with inertia dyad M and twist t at its c.o.m.: t^T M t / 2.
[[nodiscard]] inline double kineticEnergy(const InertiaDyad& M, const Twist& t) {
    return 0.5 * (M.inertia * t(0) * t(0) + M.mass * t.tail<2>().squaredNorm());
}

}  // namespace nocdyn
