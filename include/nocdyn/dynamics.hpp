// Dynamics of the general planar parallel robot by the NOC (paper Section IV, eqs. 20-23),
// with gravity, joint friction and redundant actuation.
//
// Full path (T_i, I and C stored, as the paper writes them):
//   I = sum_i T_i^T M_i T_i,  C = sum_i T_i^T M_i dT_i              (eq. 23)
//   Q = I dv + C v + Q_gf,    Q_gf = -sum_i T_i^T [0; m_i g] + sum_j (J_j^-1 Xi)^T phi_j
// with phi_j the friction to overcome at the limb's joints (damping q' + friction sign q').
// Three actuators: v = du and tau = Q (eq. 20). More: v = dp/dt, and tau is the minimum-norm
// solution of A_p^T tau = Q, A_p = A Xi (the actuators share the load).
//
// Lean path (inverseDynamicsFast, no T, I or C): the NOC applied to the bodies' inertia
// wrenches, tau from A^T tau = W_P with W_P = sum_i T_i^{xi T} (M_i dt_i - gravity) + friction,
// the same numbers as the full path (tested).
#pragma once

#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Dynamics stage: I, C and Q_gf (eq. 23). Needs the shaping stage.
void jointSpaceDynamics(const Model& model, Data& data);

/// Force stage: Q and tau (eq. 20, minimum norm when redundant). Needs the dynamics and
/// acceleration stages.
void actuatorForces(const Model& model, Data& data);

/// Every stage from a pose, its rate and acceleration (the full path).
Status inverseDynamics(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp);

/// Every stage from a pose and the actuator rates and accelerations (three actuators only).
Status inverseDynamicsFromActuators(const Model& model, Data& data, const Pose& p, const ActuatorVector& du,
                                    const ActuatorVector& ddu);

/// The lean per-sample path: u, du, ddu and tau only (also data.W_P, p, t_M and t_M_dot; the
/// other fields of data are left as they were). Same numbers as inverseDynamics, and its
/// Status: a sample the lean kernel rejects is handed to the full path, which gives the exact
/// Status (only a sample whose condition number equals max_condition to rounding can be
/// judged differently, the kernel's test being division-free). Allocation-free.
Status inverseDynamicsFast(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp);

/// Kinetic energy sum_i t_i^T M_i t_i / 2 [J] (velocity stage needed).
[[nodiscard]] double kineticEnergy(const Model& model, const Data& data);

/// Potential energy of gravity, -sum_i m_i g . x_i [J] (position stage needed).
[[nodiscard]] double potentialEnergy(const Model& model, const Data& data);

/// Power dissipated by joint friction, sum (damping q'^2 + friction |q'|) [W].
[[nodiscard]] double frictionPower(const Model& model, const Data& data);

/// Checks every actuator's |tau| against its effort limit (force stage needed).
[[nodiscard]] Status checkEffort(const Model& model, const Data& data);

}  // namespace nocdyn
