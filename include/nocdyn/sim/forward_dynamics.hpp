// Forward dynamics of the general planar parallel robot (model.hpp): the platform coordinates'
// accelerations from the state and the actuator forces. Their time integration: simulator.hpp.
//
// The state is the platform pose p = [theta, x_c, y_c] (eq. 1) and its rate dp/dt = t_M
// (eq. 2) for every robot, whatever its number n of actuators: every other coordinate follows
// from p by the closed-form inverse displacement of each limb (kinematics.hpp), so the motion
// stays on the constraint manifold exactly (no drift, no direct-kinematics tracker). With the
// twist-shaping matrices of the platform coordinates (xi_P = S(c) t_M, eqs. 28-31 generalised)
// the NOC gives (eq. 23 in these coordinates)
//   M_p d2p/dt2 + h_p(p, dp/dt) = A_p^T tau,
//   M_p = sum_i T_i^T M_i T_i,  h_p = C_p dp/dt + Q_gf,  A_p = A S(c),
// where A_p^T tau is the generalized force of the n actuator forces on the platform
// coordinates (the actuators' resultant; with n > 3 the redundant forces add up, and the
// minimum-norm forces of the inverse dynamics give back the same motion), and Q_gf holds
// gravity and joint friction, phi_k = damping q'_k + friction sign q'_k, sign 0 = 0, as the
// model defines them. The Coulomb term makes the right-hand side discontinuous where a joint
// rate changes sign: the integrator's error control then shortens its steps there (there is
// no stiction model: a joint at rest under a small load does not stick).
//
// A two-DOF robot (motion: translation, task coordinates p_t = [x, y], dp/dt = E dp_t/dt with
// the task map E of model.hpp) has no dynamics in theta: a rotation about the tool point C
// moves no body (every limb's last joint takes it up) and the point-mass platform has no
// rotational inertia, so M_p's theta row and column are zero. Its forward dynamics is eq. 23
// in the task coordinates,
//   M_t d2p_t/dt2 = A_t^T tau - h_t,   M_t = E^T M_p E,  h_t = E^T h_p,  A_t = A_p E,
// and d2p/dt2 = E d2p_t/dt2: theta's acceleration is exactly zero, so a motion started at
// theta = home(0) at rest in theta keeps it exactly (the integrator adds zeros to it).
#pragma once

#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Platform-coordinate dynamics stage: data.M_p and data.h_p (see above), for any number of
/// actuators. Needs the position and velocity stages (inverseDisplacement,
/// velocityFromPlatformTwist). Leaves data.Xi, T, T_dot, I, C and Q_gf in the platform
/// coordinates v = dp/dt (whatever model.coordinates). Allocation-free.
void platformDynamics(const Model& model, Data& data);

/// Forward dynamics stage from the state (p, dp/dt) and the n actuator forces tau: every
/// stage from position to platformDynamics, then d2p/dt2 = M_p^-1 (A_p^T tau - h_p) into
/// data.t_M_dot, with the acceleration stage (joint accelerations, ddu) and data.tau = tau
/// (a two-DOF robot: d2p/dt2 = E M_t^-1 E^T (A_p^T tau - h_p), as above).
/// Fails as inverseDisplacement and velocityFromPlatformTwist do (unreachable, singular_limb
/// naming the limb, singular_actuation), and with not_finite for a non-finite force or
/// acceleration. Allocation-free.
Status forwardDynamics(const Model& model, Data& data, const Pose& p, const Twist& dp, const ActuatorVector& tau);

}  // namespace nocdyn

// The time integration (Simulator, ForceSignal), for the callers that include this header for it.
#include "nocdyn/sim/simulator.hpp"  // IWYU pragma: export
