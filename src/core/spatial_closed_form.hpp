// Closed-form inverse kinematics of the limbs that have one (UPS, RUS, RUU), on the home
// branch, for spatial.cpp. Not part of the API.
//
// The chain is the product of exponentials of the home screws, exp(s_1 q_1) ... exp(s_n q_n)
// = D, solved by the Paden-Kahan subproblems (Murray, Li, Sastry, ch. 3.3):
//   UPS  the leg from the U's point b to the S's point P: |v0 + q_P d| = |D(P) - b| (v0 = P - b),
//        the U's two angles turning v0 + q_P d onto D(P) - b (subproblem 2), the S's three
//        angles from R_U^T R_D = Rx Ry Rz;
//   RUS  the crank angle from the sphere |D(P) - u(q_1)| = l (u the U's point, on the crank's
//        circle), the U's two angles turning the distal link P - u onto its place, the S's
//        three angles as the UPS's;
//   RUU  the same crank and distal link, the platform U's two angles from R_1 R_U1 R_U2 = R_D.
// Each square root or arc cosine has two roots; the model keeps the sign of the one through
// q = 0 at home (Limb::branch, Limb::elbow), the root Newton from home converges to.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "nocdyn/spatial.hpp"
#include "spatial_chain.hpp"

namespace nocdyn::spatial::closed_form {

inline Eigen::Matrix3d turn(const Eigen::Vector3d& a, double q) { return Eigen::AngleAxisd(q, a).toRotationMatrix(); }

inline double sign(double x) { return x < 0.0 ? -1.0 : 1.0; }

/// Subproblem 1: the angle q with Rot(a, q) u = v, a unit (from u's and v's parts across a).
inline double subproblem1(const Eigen::Vector3d& a, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const Eigen::Vector3d u_p = u - a * a.dot(u), v_p = v - a * a.dot(v);
    return std::atan2(a.dot(u_p.cross(v_p)), u_p.dot(v_p));
}

/// Subproblem 2's intermediate vector's component along a1 x a2 (over |a1 x a2|^2) at home,
/// u = v: its sign picks the branch.
inline double subproblem2Branch(const Eigen::Vector3d& a1, const Eigen::Vector3d& a2, const Eigen::Vector3d& u) {
    return u.dot(a1.cross(a2));
}

/// Subproblem 2: Rot(a1, q1) Rot(a2, q2) u = v through z = Rot(a2, q2) u = alpha a1 + beta a2 +
/// gamma a1 x a2, gamma of the branch's sign; false when there is no solution.
inline bool subproblem2(const Eigen::Vector3d& a1, const Eigen::Vector3d& a2, const Eigen::Vector3d& u,
                        const Eigen::Vector3d& v, double branch, double& q1, double& q2) {
    const double c = a1.dot(a2), den = c * c - 1.0;
    const double alpha = (c * a2.dot(u) - a1.dot(v)) / den;
    const double beta = (c * a1.dot(v) - a2.dot(u)) / den;
    const Eigen::Vector3d n = a1.cross(a2);
    const double gamma2 = (u.squaredNorm() - alpha * alpha - beta * beta - 2.0 * alpha * beta * c) / n.squaredNorm();
    if (!(gamma2 >= 0.0)) return false;
    const Eigen::Vector3d z = alpha * a1 + beta * a2 + branch * std::sqrt(gamma2) * n;
    q2 = subproblem1(a2, u, z);
    q1 = subproblem1(a1, z, v);
    return true;
}

/// The S's angles: Rx(q0) Ry(q1) Rz(q2) = Q, the pitch q1 within +-90 degrees.
inline void sphericalAngles(const Eigen::Matrix3d& Q, double* q) {
    q[0] = std::atan2(-Q(1, 2), Q(2, 2));
    q[1] = std::asin(std::clamp(Q(0, 2), -1.0, 1.0));
    q[2] = std::atan2(-Q(0, 1), Q(0, 0));
}

/// The crank angle's two parts at the platform point's place T: A cos q + B sin q = C from
/// |T - r - Rot(a, q) c|^2 = l^2, c the U's point less the crank's point r.
struct Crank {
    double A = 0.0, B = 0.0, C = 0.0;
};
inline Crank crankEquation(const Freedom& crank, const Eigen::Vector3d& elbow, double l2, const Eigen::Vector3d& T) {
    const Eigen::Vector3d& a = crank.axis;
    const Eigen::Vector3d c = elbow - crank.point, e = T - crank.point;
    const Eigen::Vector3d c_along = a * a.dot(c);
    return {e.dot(c - c_along), e.dot(a.cross(c)), 0.5 * (e.squaredNorm() + c.squaredNorm() - l2) - e.dot(c_along)};
}

/// Detects the limb's topology from its joints and keeps the home roots' signs (Limb::solver
/// stays newton when a root is degenerate at home).
inline void detect(Limb& limb, const std::vector<SpatialJointType>& joints) {
    using T = SpatialJointType;
    const auto& f = limb.freedoms;
    constexpr double kDegenerate = 1e-6;
    const auto twoAxes = [&](std::size_t k) { return f[k].axis.cross(f[k + 1].axis).norm() > kDegenerate; };
    if (joints == std::vector<T>{T::universal, T::prismatic, T::spherical}) {
        const Eigen::Vector3d v0 = f[3].point - f[0].point;
        const double beta = v0.dot(f[2].axis), gamma = subproblem2Branch(f[0].axis, f[1].axis, v0);
        if (!twoAxes(0) || !(std::abs(beta) > kDegenerate * v0.norm()) ||
            !(std::abs(gamma) > kDegenerate * v0.norm())) {
            return;
        }
        limb.solver = LimbSolver::ups;
        limb.branch = sign(beta);
        limb.elbow = sign(gamma);
        return;
    }
    const bool rus = joints == std::vector<T>{T::revolute, T::universal, T::spherical};
    const bool ruu = joints == std::vector<T>{T::revolute, T::universal, T::universal};
    if (!rus && !ruu) return;
    const Eigen::Vector3d link = f[3].point - f[1].point;
    const Crank home = crankEquation(f[0], f[1].point, link.squaredNorm(), f[3].point);
    const double gamma = subproblem2Branch(f[1].axis, f[2].axis, link);
    const double scale = (f[3].point - f[0].point).norm() * (f[1].point - f[0].point).norm();
    if (!twoAxes(1) || (ruu && !twoAxes(3)) || !(std::abs(home.B) > kDegenerate * scale) ||
        !(std::abs(gamma) > kDegenerate * link.norm())) {
        return;
    }
    limb.solver = rus ? LimbSolver::rus : LimbSolver::ruu;
    // q = atan2(B, A) + branch acos(C / rho): the root through 0 has d(A cos q + B sin q)/dq = B
    // at home, of the sign -branch
    limb.branch = -sign(home.B);
    limb.elbow = sign(gamma);
}

/// The joint variables q of a limb with a closed form at the platform displacement D; false
/// when the pose is out of the limb's reach (no real root).
inline bool solve(const Limb& limb, const chain::Move& D, FreedomVector& q) {
    const auto& f = limb.freedoms;
    const Eigen::Vector3d P = f[3].point;  // the S's (or the platform U's) point
    const Eigen::Vector3d T = D.R * P + D.t;
    if (limb.solver == LimbSolver::ups) {
        // q_P from |v0 + q_P d|^2 = |L|^2, the root through 0 without cancellation
        const Eigen::Vector3d v0 = P - f[0].point, L = T - f[0].point, d = f[2].axis;
        const double beta = v0.dot(d), change = L.squaredNorm() - v0.squaredNorm();
        const double disc = beta * beta + change;
        if (!(disc >= 0.0)) return false;
        q(2) = change / (beta + limb.branch * std::sqrt(disc));
        if (!subproblem2(f[0].axis, f[1].axis, v0 + q(2) * d, L, limb.elbow, q(0), q(1))) return false;
        const Eigen::Matrix3d R_U = turn(f[0].axis, q(0)) * turn(f[1].axis, q(1));
        sphericalAngles(R_U.transpose() * D.R, &q(3));
        return true;
    }
    // the crank (eq. A cos q + B sin q = C), then the distal link P - u turned onto its place
    const Eigen::Vector3d link = P - f[1].point;
    const Crank k = crankEquation(f[0], f[1].point, link.squaredNorm(), T);
    const double rho = std::hypot(k.A, k.B);
    if (!(std::abs(k.C) <= rho)) return false;
    q(0) = std::remainder(std::atan2(k.B, k.A) + limb.branch * std::acos(k.C / rho), 2.0 * std::numbers::pi);
    const Eigen::Matrix3d R_1 = turn(f[0].axis, q(0));
    const Eigen::Vector3d place = R_1.transpose() * (T - f[0].point) - (f[1].point - f[0].point);
    if (!subproblem2(f[1].axis, f[2].axis, link, place, limb.elbow, q(1), q(2))) return false;
    const Eigen::Matrix3d Q = (R_1 * turn(f[1].axis, q(1)) * turn(f[2].axis, q(2))).transpose() * D.R;
    if (limb.solver == LimbSolver::rus) {
        sphericalAngles(Q, &q(3));
        return true;
    }
    // Rot(a4, q4) Rot(a5, q5) = Q: a5 is turned by the first alone, then a4 by the second
    const Eigen::Vector3d &a4 = f[3].axis, &a5 = f[4].axis;
    q(3) = subproblem1(a4, a5, Q * a5);
    q(4) = subproblem1(a5, a4, turn(a4, q(3)).transpose() * (Q * a4));
    return true;
}

}  // namespace nocdyn::spatial::closed_form
