// Joint reaction forces: the constraint wrenches the NOC eliminates (eq. 19), recovered limb by
// limb from each body's Newton-Euler equations once the motion and tau are known.
//
// Every body b needs the net wrench w_b = M_b dt_b - [0; m_b g] (eqs. 9-12; planar, so no
// gyroscopic term), referred here to O: [n_c + x_b x f; f] with f = m_b (a_b - g), n_c = I_b dw.
// Let F_k be the wrench that joint k of a limb transmits from its inboard body to its outboard
// body (the base to body 1 for k = 1, body 2 to the platform for k = 3), referred to O. The two
// bodies' balances give F_2 = F_3 + w_2 and F_1 = F_2 + w_1, and each joint passes, along its
// screw s_k, exactly its effort e_k (the actuator's force or torque tau, less the friction phi_k
// to overcome): s_k^T F_k = e_k. Hence
//   J_j^T F_3 = e - [s_1^T (w_1 + w_2); s_2^T w_2; 0],   F_3 = J_j^-T (...)
// and then F_2, F_1 by back-substitution; no new unknowns. The platform's balance,
// sum_j F_3 = w_P, holds when tau is the inverse dynamics' (a test checks it).
//
// Convention of the reported reaction (base frame; the wrench of the inboard body on the
// outboard body, the joint's own effort and friction taken out):
//   R joint: the force (fx, fy) at the joint axis, m = 0 (the moment about the axis is the effort);
//   P joint: the force normal to the joint's current direction (fx, fy), and the couple m about
//            the outboard body's c.o.m. (the effort is a force along the direction through it).
#pragma once

#include <array>

#include "nocdyn/batch.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Reactions of every joint of one sample. Fixed capacity: never allocates.
struct Reactions {
    /// F_k: the whole wrench joint k of limb j transmits to its outboard body, referred to O,
    /// [n_O; f_x; f_y] [N m; N; N], effort and friction included.
    std::array<std::array<Wrench, 3>, kMaxLimbs> transmitted{};
    /// The reaction in the convention above, [fx; fy; m] [N; N; N m], base frame.
    std::array<std::array<Vector3, 3>, kMaxLimbs> joint{};
    /// w_b: the net wrench body b needs (M_b dt_b - gravity), referred to O; platform last.
    std::array<Wrench, kMaxBodies> body{};
};

/// Design loads of one joint over a motion: the peak and RMS of its reaction force |(fx, fy)|,
/// the peak of its couple |m|, each peak with the time and platform pose where it occurs.
struct JointLoad {
    double peak_force = 0.0;  ///< [N]
    double peak_force_t = 0.0;
    Pose peak_force_pose = Pose::Zero();
    double peak_moment = 0.0;  ///< [N m]
    double peak_moment_t = 0.0;
    Pose peak_moment_pose = Pose::Zero();
    double sum_squared_force = 0.0;  ///< sum of |f|^2 over the samples [N^2]
    long samples = 0;
    /// RMS of |f| over the samples [N].
    [[nodiscard]] double rmsForce() const;
};

/// Every joint's design loads, accumulated sample by sample (allocation-free).
struct JointLoads {
    int limbs = 0;
    std::array<std::array<JointLoad, 3>, kMaxLimbs> joint{};
    /// Adds the reactions of the sample at time t and pose p.
    void add(double t, const Pose& p, const Reactions& reactions);
    /// Adds another run's loads: the larger peaks, the RMS over both runs' samples.
    void merge(const JointLoads& other);
};

/// The reactions at the state in `data`: needs the position, velocity and acceleration stages
/// (kinematics.hpp) and data.tau (the forces actually applied: for a redundant robot, those
/// of the inverse dynamics, the minimum-norm ones, or any others given). Allocation-free.
void jointReactions(const Model& model, const Data& data, Reactions& reactions);

/// Inverse dynamics and the reactions that go with its forces, without T, I or C: the lean
/// kernel of inverseDynamicsFast (closed-form limb IK, J_j^-1 by cofactors), which also gives
/// the bodies' wrenches and tau from the platform's balance A^T tau = w_P + sum_j J_j^-T
/// (phi_j + k_j) (W_P; minimum-norm with more than three actuators), then the
/// back-substitution. The same tau (to rounding) and Status as inverseDynamics. Sets data's
/// u, du, ddu, tau, W_P, p, its rates, xi_P and its rate, x_P, and per limb s, s_dot, J_inv, x,
/// xi, gamma_dot and gamma_ddot (all jointReactions reads); the other fields (q, J, A, T_i, I,
/// C, ...) may be left as they were. Allocation-free.
Status inverseDynamicsWithReactions(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                                    Reactions& reactions);

/// inverseDynamicsWithReactions over N samples: (p, dp, ddp), N x 3 each (batch.hpp's layout)
/// -> `out`, N x 9 limbs, row k = sample k's Reactions::joint limb by limb, joint by joint,
/// [fx, fy, m] each (NumPy's (N, limbs, 3, 3) in C order). A failed sample's row is NaN; the
/// result names the first failure and its Status (inverseDynamics's). `threads` as in
/// inverseDynamicsBatch, `order` the pose order of the inputs' columns. Nothing is allocated
/// per sample. Throws nocdyn::Error when the arrays' sizes disagree (before any sample is
/// computed).
BatchResult reactionsBatch(const Model& model, const BatchInput& p, const BatchInput& dp, const BatchInput& ddp,
                           BatchOutput out, unsigned threads = 1, PoseColumns order = PoseColumns::theta_x_y);

}  // namespace nocdyn
