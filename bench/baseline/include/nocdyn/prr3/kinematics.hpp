// 3-PRR kinematics: inverse displacement (Appendix A, completed in model-notes.md) and
// velocity kinematics (eqs. 3-8, 29). All functions fill a Data, never allocate or throw,
// and report unreachable or singular postures through the returned Status.
#pragma once

#include "nocdyn/prr3/model.hpp"
#include "nocdyn/prr3/status.hpp"

namespace nocdyn::prr3 {

/// Position stage. Given the pose p = [theta, x_c, y_c], computes d_j^M (eqs. 37-38,
/// signed: positive inside the base triangle), phi_Aj and phi_Mj (eq. 39), M_j, A_j, m_j,
/// p_Aj, p_Mj (eqs. 40-42) and u_j = e_j . (A_j - A_j_ref).
/// Fails with outside_workspace when d_j^M <= 0 or d_j^M >= l for some limb.
Status inverseDisplacement(const Model& model, Data& data, const Pose& p);

/// Velocity stage from the platform twist t_M = dp/dt (eq. 2). Needs the position stage.
/// Computes J_j (eq. 4a), H and D (eqs. 6-7), their conditioning, du = D^{-1} H t_M (eq. 5)
/// and the limb rates gamma_dot_j = J_j^{-1} t_M (eq. 3).
/// Fails when H or D is ill-conditioned beyond model.parameters.max_condition.
Status velocityFromPlatformTwist(const Model& model, Data& data, const Twist& t_M);

/// Velocity stage from the actuator rates du: t_M = H^{-1} D du (eq. 5); otherwise as above.
Status velocityFromActuatorRates(const Model& model, Data& data, const JointVector& du);

/// Actuator accelerations from the time derivative of eq. 5:
///   H dt_M + dH t_M = D ddu + dD du  =>  ddu = D^{-1} (H dt_M + dH t_M - dD du).
/// Needs the shaping stage (for dH, dD). Stores t_M_dot and ddu.
void actuatorAccelerations(Data& data, const Twist& t_M_dot);

/// Platform acceleration from actuator accelerations (the inverse of the above).
/// Needs the shaping stage. Stores ddu and t_M_dot.
void platformAcceleration(Data& data, const JointVector& ddu);

/// Checks |u_j| <= stroke / 2 for every limb (position stage needed).
[[nodiscard]] Status checkStroke(const Model& model, const Data& data);

}  // namespace nocdyn::prr3
