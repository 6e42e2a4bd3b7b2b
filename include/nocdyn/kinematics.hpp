// Kinematics of the general planar parallel robot (model.hpp): position, velocity and
// twist shaping. Only the inverse displacement of one limb depends on the limb type
// (limb_ik.hpp); everything else is written once with planar screws:
//   J_j = [s_1 s_2 s_3]                      limb Jacobian, xi_P = J_j gamma_dot_j  (eq. 3, 4a)
//   du = A xi_P, A = actuated rows of J_j^-1  (eq. 5 generalised)
//   xi_b1 = s_1 gd_1,  xi_b2 = xi_b1 + s_2 gd_2   body twists (eq. 28 generalised, U_i)
//   ds_k/dt = [xi_(k-1), s_k]                the Lie bracket of planar twists
//   t_i = Ad(x_i) U_i J_j^-1 xi_P = T_i v     twist shaping (eqs. 29-31 generalised)
// with xi_P = S(c) t_M, S(c) = [1 0 0; c_y 1 0; -c_x 0 1]: the platform twist referred to O.
// None of these functions allocates, throws or logs; failures are a Status naming the limb.
#pragma once

#include <array>

#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Lie bracket of planar twists referred to O: [a, b] = [0; a_w E b_v - b_w E a_v].
[[nodiscard]] inline Twist bracket(const Twist& a, const Twist& b) {
    return {0.0, -a(0) * b(2) + b(0) * a(2), a(0) * b(1) - b(0) * a(1)};
}

/// Twist at a point x (e.g. a c.o.m.) from a twist referred to O: [w; v_O + w E x].
[[nodiscard]] inline Twist twistAt(const Twist& xi, const Vector2& x) {
    return {xi(0), xi(1) - xi(0) * x.y(), xi(2) + xi(0) * x.x()};
}

/// Position stage: every limb's joint variables on its home branch, the current joint
/// screws, body c.o.m. positions and the actuator variables u.
/// Fails with unreachable (limb, by how much) or singular_limb (a limb with a unique
/// solution whose equations are singular), or not_finite.
Status inverseDisplacement(const Model& model, Data& data, const Pose& p);

/// Inverse-kinematics branch of every limb (as LimbModel::branch: +1 or -1, 0 for limbs with
/// one solution), for the assembly modes other than the working one.
using LimbBranches = std::array<int, kMaxLimbs>;

/// The position stage with limb j on branches[j] instead of its home branch. The velocity and
/// later stages then hold for that assembly mode.
Status inverseDisplacement(const Model& model, Data& data, const Pose& p, const LimbBranches& branches);

/// Velocity stage from the platform twist t_M = dp/dt: J_j, J_j^-1 and their conditioning,
/// A, xi_P, joint rates, body twists, screw rates and du = A xi_P.
/// Fails with singular_limb or singular_actuation beyond model.max_condition.
Status velocityFromPlatformTwist(const Model& model, Data& data, const Twist& t_M);

/// Velocity stage from the actuator rates (three actuators only: xi_P = A^-1 du).
/// Fails as above, and with singular_actuation when the robot is redundantly actuated.
Status velocityFromActuatorRates(const Model& model, Data& data, const ActuatorVector& du);

/// Velocity stage from actuator rates of any robot: dp/dt from du = A S(c) dp/dt by least
/// squares (exact with three actuators; with more, the rates of the nearest platform motion),
/// then velocityFromPlatformTwist(dp/dt). Needs the position stage. Fails as
/// velocityFromPlatformTwist, with not_finite, and with inconsistent_rates when du misses
/// A S(c) dp/dt by more than `tolerance` (1 + max |du|). Allocation-free.
Status velocityFromActuatorRatesLeastSquares(const Model& model, Data& data, const ActuatorVector& du, Twist& dp,
                                             double tolerance = 1e-9);

/// Acceleration stage from d2p/dt2: xi_P_dot, joint accelerations and ddu.
/// Needs the velocity stage.
void accelerationFromPlatform(const Model& model, Data& data, const Twist& t_M_dot);

/// Acceleration stage from the actuator accelerations (three actuators only).
void accelerationFromActuators(const Model& model, Data& data, const ActuatorVector& ddu);

/// Shaping stage: T_i and dT_i for every body in the independent coordinates, Xi, dXi/dt.
/// Needs the velocity stage.
void twistShaping(const Model& model, Data& data);

/// Checks every joint's range and velocity limits (position and velocity stages needed).
[[nodiscard]] Status checkJointLimits(const Model& model, const Data& data);

}  // namespace nocdyn
