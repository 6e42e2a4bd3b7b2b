// Internal stages and small kernels shared by kinematics.cpp, dynamics.cpp and the batch
// (not installed).
#pragma once

#include <cmath>

#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

// On x86-64 with GCC, the stages of the full path are built twice, for the baseline ISA and
// for x86-64-v3 (AVX2, FMA: fewer instructions for the 3 x 3 products), chosen at load time.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(NOCDYN_NO_TARGET_CLONES)
#define NOCDYN_TARGET_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define NOCDYN_TARGET_CLONES
#endif
// Helpers (and lambdas) of a cloned stage must be inlined into each clone.
#if defined(__GNUC__)
#define NOCDYN_INLINE_LAMBDA __attribute__((always_inline))
#else
#define NOCDYN_INLINE_LAMBDA
#endif

namespace nocdyn::detail {

/// Position stage; R angles are computed only when `angles` (or the joint is actuated). Limb j
/// is solved on branches[j], or on its home branch when `branches` is null.
Status positionStage(const Model& model, Data& data, const Pose& p, bool angles, const int* branches = nullptr);
/// J_j, J_j^-1, their conditioning, A, Xi (actuator coordinates) and cond_A.
Status jacobianStage(const Model& model, Data& data);
/// Joint rates, body twists, screw rates and du from xi_P.
void rateStage(const Model& model, Data& data);
/// tau from A^T tau = W (W referred to O): Xi^T W = A^-T W with three actuators, else the
/// minimum-norm A (A^T A)^-1 W. Needs the velocity stage.
void distribute(const Model& model, Data& data, const Vector3& W);
/// T_i and dT_i of every body (eqs. 28-31 generalised) for the independent coordinates whose
/// map data.Xi (xi_P = Xi v) and its rate data.Xi_dot are set. Needs the velocity stage.
void shapeBodies(const Model& model, Data& data);

/// Xi = S(c) and dXi/dt for the platform coordinates v = dp/dt (xi_P = S(c) t_M).
inline void platformCoordinates(Data& data) {
    data.Xi = platformTwistMap(data.p.tail<2>());
    data.Xi_dot = platformTwistMapRate(data.t_M);
}

/// A planar rigid displacement x -> R(c, s) x + t.
struct Displacement {
    double c = 1.0, s = 0.0;
    Vector2 t = Vector2::Zero();

    [[nodiscard]] Vector2 rotate(const Vector2& v) const { return {c * v.x() - s * v.y(), s * v.x() + c * v.y()}; }
    [[nodiscard]] Vector2 apply(const Vector2& v) const { return rotate(v) + t; }
    /// this o other
    [[nodiscard]] Displacement then(const Displacement& other) const {
        return {c * other.c - s * other.s, s * other.c + c * other.s, rotate(other.t) + t};
    }
};

/// exp of joint k's home screw times q_k: a rotation about r_k or a translation along d_k.
[[nodiscard]] inline Displacement jointDisplacement(const LimbModel& limb, const LimbData& ld, int k) {
    const auto kk = static_cast<std::size_t>(k);
    if (limb.type[kk] == JointType::prismatic) return {1.0, 0.0, ld.q(k) * limb.direction[kk]};
    Displacement g{ld.cos_q(k), ld.sin_q(k), Vector2::Zero()};
    g.t = limb.point_home[kk] - g.rotate(limb.point_home[kk]);
    return g;
}

/// Current screw of joint k carried by the body displaced by g (referred to O).
[[nodiscard]] inline Twist currentScrew(const LimbModel& limb, const Displacement& g, int k) {
    const auto kk = static_cast<std::size_t>(k);
    if (limb.type[kk] == JointType::revolute) {
        const Vector2 r = g.apply(limb.point_home[kk]);
        return {1.0, r.y(), -r.x()};
    }
    return {0.0, g.c * limb.direction[kk].x() - g.s * limb.direction[kk].y(),
            g.s * limb.direction[kk].x() + g.c * limb.direction[kk].y()};
}

/// From the limb's joint variables (q, cos q, sin q): its current joint screws s and its
/// bodies' c.o.m. x, by the product of exponentials.
inline void limbScrews(const LimbModel& limb, LimbData& ld) {
    const Displacement g1 = jointDisplacement(limb, ld, 0);
    const Displacement g2 = g1.then(jointDisplacement(limb, ld, 1));
    ld.s[0] = limb.screw_home[0];
    ld.s[1] = currentScrew(limb, g1, 1);
    ld.s[2] = currentScrew(limb, g2, 2);
    ld.x[0] = g1.apply(limb.com_home[0]);
    ld.x[1] = g2.apply(limb.com_home[1]);
}

/// The cross product of two 3-arrays (the cofactors of a 3 x 3 matrix).
[[nodiscard]] inline Vector3 cross3(const Vector3& a, const Vector3& b) {
    return {a(1) * b(2) - a(2) * b(1), a(2) * b(0) - a(0) * b(2), a(0) * b(1) - a(1) * b(0)};
}

/// Cofactor form of the inverse of J = [a b c]: the rows of adj J are b x c, c x a and a x b
/// (J^-1 = adj J / det J, det J = a . (b x c)).
inline double adjugateOfColumns(const Vector3& a, const Vector3& b, const Vector3& c, Matrix3& adj) {
    adj.row(0) = cross3(b, c).transpose();
    adj.row(1) = cross3(c, a).transpose();
    adj.row(2) = cross3(a, b).transpose();
    return a.dot(adj.row(0).transpose());
}

/// The two 1-norms whose product over |det J| is the scaled condition number of a limb
/// Jacobian: || diag(1, 1/L, 1/L) J diag(c) ||_1 and || diag(1/c) adj J diag(1, L, L) ||_1,
/// c_k the joint scales (kinematics.cpp). Division-free.
struct ConditionNorms {
    double norm = 0.0;      ///< of the scaled J
    double adj_norm = 0.0;  ///< of the scaled adj J
};

inline ConditionNorms limbConditionNorms(const LimbModel& limb, double L, double inv_L, const Matrix3& J,
                                         const Matrix3& adj) {
    ConditionNorms out;
    for (int k = 0; k < 3; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        const double col = limb.joint_scale[kk] * (std::abs(J(0, k)) + (std::abs(J(1, k)) + std::abs(J(2, k))) * inv_L);
        out.norm = std::max(out.norm, col);
    }
    const auto& ic = limb.inv_joint_scale;
    const double c0 = std::abs(adj(0, 0)) * ic[0] + std::abs(adj(1, 0)) * ic[1] + std::abs(adj(2, 0)) * ic[2];
    const double c1 = std::abs(adj(0, 1)) * ic[0] + std::abs(adj(1, 1)) * ic[1] + std::abs(adj(2, 1)) * ic[2];
    const double c2 = std::abs(adj(0, 2)) * ic[0] + std::abs(adj(1, 2)) * ic[1] + std::abs(adj(2, 2)) * ic[2];
    out.adj_norm = std::max(c0, L * std::max(c1, c2));
    return out;
}

/// Column sums' maximum: the matrix 1-norm of a 3 x 3 matrix.
[[nodiscard]] inline double norm1(const Matrix3& m) {
    return std::max({std::abs(m(0, 0)) + std::abs(m(1, 0)) + std::abs(m(2, 0)),
                     std::abs(m(0, 1)) + std::abs(m(1, 1)) + std::abs(m(2, 1)),
                     std::abs(m(0, 2)) + std::abs(m(1, 2)) + std::abs(m(2, 2))});
}

/// Actuation map for three actuators, rows a_0..a_2 of A (du = A xi_P) with weights
/// w_a = 1 / (joint scale): the columns of adj A (A^-1 = adj A / det A) and the two 1-norms of
/// the scaled condition number || diag(w) A diag(1, L, L) ||_1 || diag(1, 1/L, 1/L) A^-1
/// diag(1/w) ||_1 (the second times |det A|). Division-free.
inline double actuationAdjugate(const Vector3* a, Matrix3& adj) {
    adj.col(0) = cross3(a[1], a[2]);
    adj.col(1) = cross3(a[2], a[0]);
    adj.col(2) = cross3(a[0], a[1]);
    return a[0].dot(adj.col(0));
}

inline ConditionNorms actuationConditionNorms(const Vector3* a, const double* w, double L, double inv_L,
                                              const Matrix3& adj) {
    ConditionNorms out;
    const double c0 = w[0] * std::abs(a[0](0)) + w[1] * std::abs(a[1](0)) + w[2] * std::abs(a[2](0));
    const double c1 = w[0] * std::abs(a[0](1)) + w[1] * std::abs(a[1](1)) + w[2] * std::abs(a[2](1));
    const double c2 = w[0] * std::abs(a[0](2)) + w[1] * std::abs(a[1](2)) + w[2] * std::abs(a[2](2));
    out.norm = std::max(c0, L * std::max(c1, c2));
    for (int k = 0; k < 3; ++k) {
        const double col = (std::abs(adj(0, k)) + (std::abs(adj(1, k)) + std::abs(adj(2, k))) * inv_L) / w[k];
        out.adj_norm = std::max(out.adj_norm, col);
    }
    return out;
}

/// Inverse of a symmetric 3 x 3 matrix by cofactors (times its determinant): adj B, det B.
inline double symmetricAdjugate(const Matrix3& B, Matrix3& adj) {
    adj(0, 0) = B(1, 1) * B(2, 2) - B(1, 2) * B(1, 2);
    adj(0, 1) = B(0, 2) * B(1, 2) - B(0, 1) * B(2, 2);
    adj(0, 2) = B(0, 1) * B(1, 2) - B(0, 2) * B(1, 1);
    adj(1, 1) = B(0, 0) * B(2, 2) - B(0, 2) * B(0, 2);
    adj(1, 2) = B(0, 1) * B(0, 2) - B(0, 0) * B(1, 2);
    adj(2, 2) = B(0, 0) * B(1, 1) - B(0, 1) * B(0, 1);
    adj(1, 0) = adj(0, 1);
    adj(2, 0) = adj(0, 2);
    adj(2, 1) = adj(1, 2);
    return B(0, 0) * adj(0, 0) + B(0, 1) * adj(0, 1) + B(0, 2) * adj(0, 2);
}

}  // namespace nocdyn::detail
