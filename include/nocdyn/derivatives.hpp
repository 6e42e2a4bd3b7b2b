// Exact first derivatives of the inverse and forward dynamics of any planar parallel robot
// (model.hpp), and of its actuator variables u, du, ddu: every limb type, redundant actuation,
// gravity and joint friction.
//
// Forward-mode automatic differentiation with a dual number carrying one derivative per
// input direction, through the NOC written once on a scalar type:
//   xi_P = S(c) dp,  gamma_dot_j = J_j^-1 xi_P,  gamma_ddot_j = J_j^-1 (dxi_P - dJ_j gamma_dot_j)
//   W_P = w_P + sum_j J_j^-T (U_j^T w_j + phi_j)        (the NOC on the bodies' wrenches)
//   A^T tau = W_P: tau = A^-T W_P, or A (A^T A)^-1 W_P with n > 3 actuators (eq. 20)
// with w_i = [I_i dw_i; m_i (a_i - g)] referred to O. The joint variables are never
// differentiated through the closed-form inverse displacement: the derivative of every
// position-level quantity along a pose direction e is a velocity-level one for dp = e
// (ds_k = [xi_(k-1), s_k], dx_i = the body point's velocity), so the seeds are exact.
// The derivatives are exact to rounding; finite differences only test them.
//
// Coulomb friction, friction_k sign(q'_k), is differentiated with the sign frozen: its
// derivative is 0 everywhere, and at a joint rate of exactly zero the value is 0 (sign 0 = 0)
// and so is its derivative (the force is not differentiable there; the derivative returned
// is that of the zero friction force the model uses at rest). Viscous damping is exact.
//
// Nothing allocates and nothing throws on the per-sample path; failures are the Status of the
// position and velocity stages (unreachable, singular_limb, singular_actuation, not_finite).
#pragma once

#include <span>

#include <Eigen/Core>

#include "nocdyn/batch.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// n x 3 derivative of the actuator forces with respect to a pose-space vector (columns in
/// the pose order [theta, x_c, y_c]). Fixed capacity: never allocates.
using ActuatorPoseJacobian = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxActuators, 3>;
/// 3 x n derivative of the platform acceleration with respect to the actuator forces.
using PoseActuatorJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxActuators>;

/// d tau / d(p, dp/dt, d2p/dt2) at a sample, and tau itself.
struct InverseDynamicsDerivatives {
    ActuatorVector tau;          ///< actuator forces (inverseDynamics' values)
    ActuatorPoseJacobian d_p;    ///< d tau / d p
    ActuatorPoseJacobian d_dp;   ///< d tau / d(dp/dt)
    ActuatorPoseJacobian d_ddp;  ///< d tau / d(d2p/dt2): the mass matrix mapped to the actuators
};

/// d(d2p/dt2) / d(p, dp/dt, tau) at a state and force, and d2p/dt2 itself.
struct ForwardDynamicsDerivatives {
    Twist ddp = Twist::Zero();       ///< d2p/dt2 (forwardDynamics' value)
    Matrix3 d_p = Matrix3::Zero();   ///< d(d2p/dt2) / d p
    Matrix3 d_dp = Matrix3::Zero();  ///< d(d2p/dt2) / d(dp/dt)
    PoseActuatorJacobian d_tau;      ///< d(d2p/dt2) / d tau = M_p^-1 A_p^T
    /// The platform-coordinate mass matrix M_p (forward_dynamics.hpp), d(A_p^T tau)/d(d2p/dt2).
    Matrix3 M_p = Matrix3::Zero();
};

/// Inverse dynamics and its exact derivatives at (p, dp/dt, d2p/dt2). `data` is workspace (its
/// position and velocity stages are left set). Allocation-free.
Status inverseDynamicsDerivatives(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                                  InverseDynamicsDerivatives& out);

/// Forward dynamics and its exact derivatives at the state (p, dp/dt) and forces tau (size n).
/// `data` is workspace. Fails as inverseDynamicsDerivatives, and with not_finite for a
/// non-finite force. Allocation-free.
Status forwardDynamicsDerivatives(const Model& model, Data& data, const Pose& p, const Twist& dp,
                                  const ActuatorVector& tau, ForwardDynamicsDerivatives& out);

/// The actuator variables u (the actuated joints' positions), their rates du and
/// accelerations ddu, and their exact derivatives at (p, dp/dt, d2p/dt2). Row a is actuator a
/// (joint model.actuator_joint[a] of limb model.actuator_limb[a]), columns the pose order
/// [theta, x_c, y_c]. du = A S(c) dp is linear in dp and ddu = A S(c) ddp + (terms in p, dp)
/// is linear in ddp with the same coefficients, so d du/d dp = d ddu/d ddp = d u/d p = A S(c)
/// (A: Data::A, S(c) = platformTwistMap). The rates and accelerations are the actuated entries
/// of gamma_dot_j = J_j^-1 xi_P and gamma_ddot_j of the same dual-number kernel as
/// inverseDynamicsDerivatives; u_p is A S(c) of the velocity stage.
struct ActuatorVariableDerivatives {
    ActuatorVector u;              ///< actuator variables (inverseDynamics' Data::u) [m or rad]
    ActuatorVector du;             ///< actuator rates (Data::du)
    ActuatorVector ddu;            ///< actuator accelerations (Data::ddu)
    ActuatorPoseJacobian u_p;      ///< d u / d p = A S(c)
    ActuatorPoseJacobian du_p;     ///< d du / d p
    ActuatorPoseJacobian du_dp;    ///< d du / d(dp/dt) (= u_p)
    ActuatorPoseJacobian ddu_p;    ///< d ddu / d p
    ActuatorPoseJacobian ddu_dp;   ///< d ddu / d(dp/dt)
    ActuatorPoseJacobian ddu_ddp;  ///< d ddu / d(d2p/dt2) (= u_p)
};

/// u, du, ddu and their exact derivatives at (p, dp/dt, d2p/dt2). `data` is workspace (its
/// position and velocity stages are left set). Fails as inverseDynamicsDerivatives.
/// Allocation-free.
Status actuatorVariableDerivatives(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                                   ActuatorVariableDerivatives& out);

/// The inverse dynamics' derivatives of N samples: (p, dp, ddp), N x 3 each -> d tau/d p,
/// d tau/d dp, d tau/d ddp, N x 3n each, row k = sample k, column 3 a + i = d tau_a / d x_i
/// (so that a row-major N x 3n array is an N x n x 3 one). `threads` as inverseDynamicsBatch.
/// `order`: the pose order of the inputs' columns and of i in the outputs' columns.
/// A failed sample's outputs are NaN. Throws nocdyn::Error when the sizes disagree.
BatchResult inverseDynamicsDerivativesBatch(const Model& model, const BatchInput& p, const BatchInput& dp,
                                            const BatchInput& ddp, BatchOutput d_p, BatchOutput d_dp, BatchOutput d_ddp,
                                            unsigned threads = 1, PoseColumns order = PoseColumns::theta_x_y);

/// The outputs of actuatorVariableDerivativesBatch over N samples, row k = sample k: u, du, ddu
/// N x n each; their derivatives N x 3n each, column 3 a + i = the derivative of actuator a's
/// variable by the pose coordinate i (so that a row-major N x 3n array is an N x n x 3 one).
/// `status`: empty, or N entries that get each sample's Status.
struct ActuatorVariableDerivativesBatch {
    BatchOutput u, du, ddu;
    BatchOutput u_p, du_p, du_dp, ddu_p, ddu_dp, ddu_ddp;
    std::span<Status> status = {};
};

/// actuatorVariableDerivatives of N samples (p, dp, ddp, N x 3 each), split over `threads` as
/// inverseDynamicsBatch; `order` as inverseDynamicsDerivativesBatch. Each sample's values are
/// actuatorVariableDerivatives' own (the same function on a workspace per thread); a failed
/// sample's outputs are NaN. Nothing is allocated per sample. Throws nocdyn::Error when the
/// sizes disagree.
BatchResult actuatorVariableDerivativesBatch(const Model& model, const BatchInput& p, const BatchInput& dp,
                                             const BatchInput& ddp, ActuatorVariableDerivativesBatch out,
                                             unsigned threads = 1, PoseColumns order = PoseColumns::theta_x_y);

}  // namespace nocdyn
