// The natural orthogonal complement (NOC), independent of the robot architecture
// (paper Section IV-B, eqs. 20-23).
//
// A planar mechanism of B moving bodies driven by N actuators has, at each posture,
// twist-shaping matrices T_i (3 x N) with t_i = T_i du (eq. 22) and their time derivatives
// dT_i. With the constant inertia dyads M_i (eq. 9) the minimal dynamics model is
//   I = sum_i T_i^T M_i T_i,   C = sum_i T_i^T M_i dT_i          (eq. 23)
//   tau = I ddu + C du                                             (eq. 20)
// Because every M_i is constant in the plane, dI/dt = C + C^T exactly.
//
// The functions below work on fixed-size arrays and never allocate.
#pragma once

#include <array>
#include <cstddef>

#include "nocdyn/planar.hpp"

namespace nocdyn::noc {

/// Twist-shaping matrix of one body: 3 x N (eq. 22).
template <int N>
using ShapingMatrix = Eigen::Matrix<double, 3, N>;

/// Joint-space N x N matrix (I or C).
template <int N>
using JointMatrix = Eigen::Matrix<double, N, N>;

/// Joint-space N-vector (u, du, ddu, tau).
template <int N>
using JointVector = Eigen::Matrix<double, N, 1>;

/// M_i T_i for a diagonal inertia dyad, without forming the 3 x 3 matrix.
template <int N>
[[nodiscard]] inline ShapingMatrix<N> applyInertia(const InertiaDyad& M, const ShapingMatrix<N>& X) {
    ShapingMatrix<N> out;
    out.row(0) = M.inertia * X.row(0);
    out.template bottomRows<2>() = M.mass * X.template bottomRows<2>();
    return out;
}

/// Adds one body's term of eq. 23 to I: I += T_i^T M_i T_i. With M_i = diag(I_i, m_i, m_i)
/// (eq. 9), M_i T_i only scales rows: W = M_i T_i, then I += T_i^T W (fully unrolled).
template <int N>
void addInertia(const InertiaDyad& M, const ShapingMatrix<N>& T, JointMatrix<N>& I) {
    const ShapingMatrix<N> W = applyInertia(M, T);
    I += T.transpose().lazyProduct(W);
}

/// Adds one body's term of eq. 23 to C: C += T_i^T M_i dT_i.
template <int N>
void addCoriolis(const InertiaDyad& M, const ShapingMatrix<N>& T, const ShapingMatrix<N>& T_dot, JointMatrix<N>& C) {
    const ShapingMatrix<N> W = applyInertia(M, T);
    C += W.transpose().lazyProduct(T_dot);
}

/// eq. 23: I = sum_i T_i^T M_i T_i. Joint-space inertia [kg], N x N, symmetric.
template <int N, std::size_t B>
void inertia(const std::array<InertiaDyad, B>& M, const std::array<ShapingMatrix<N>, B>& T, JointMatrix<N>& I) {
    I.setZero();
    for (std::size_t i = 0; i < B; ++i) addInertia(M[i], T[i], I);
}

/// eq. 23: C = sum_i T_i^T M_i dT_i. Coriolis and centrifugal matrix [kg/s], N x N.
template <int N, std::size_t B>
void coriolis(const std::array<InertiaDyad, B>& M, const std::array<ShapingMatrix<N>, B>& T,
              const std::array<ShapingMatrix<N>, B>& T_dot, JointMatrix<N>& C) {
    C.setZero();
    for (std::size_t i = 0; i < B; ++i) addCoriolis(M[i], T[i], T_dot[i], C);
}

/// eq. 20: tau = I ddu + C du. Actuator forces (or torques) [N].
template <int N>
void inverseDynamics(const JointMatrix<N>& I, const JointMatrix<N>& C, const JointVector<N>& du,
                     const JointVector<N>& ddu, JointVector<N>& tau) {
    tau.noalias() = I * ddu;
    tau.noalias() += C * du;
}

/// Kinetic energy du^T I du / 2 [J].
template <int N>
[[nodiscard]] double kineticEnergy(const JointMatrix<N>& I, const JointVector<N>& du) {
    return 0.5 * du.dot(I * du);
}

}  // namespace nocdyn::noc
