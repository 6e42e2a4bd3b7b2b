// The standard inertia and friction parameters pi of the general planar parallel robot and
// the regressor Y of its dynamics (dynamics.hpp) written linearly in them,
//   tau = Y(q, dq, ddq) pi.
// Standard parameters pi, per body i (model body order, the platform last), in the body's own
// frame: [m, m c_x, m c_y, I_O], with c the c.o.m. and I_O the moment of inertia about the
// frame's origin O_i (I_O = I + m |c|^2). A limb body's frame coincides with the base frame at
// home and moves with the body (product of exponentials: c is the c.o.m. at home, base axes);
// the platform's frame has its origin at C and turns with theta (c = the file's platform com).
// Then per joint (limb order, chain order): [damping, friction].
//
// Regressor. A planar body whose frame origin o (at r) moves with acceleration a_o, turning at
// omega with rate domega, needs the wrench (inertial minus weight, referred to the base origin O)
//   f   = m (a_o - g) + domega E h - omega^2 h,           h = R(phi) [m c_x; m c_y]
//   n_O = I_O domega + h x (a_o - g) + r x f
// linear in [m, m c_x, m c_y, I_O]: its 3 x 4 wrench regressor Y_w,i. The NOC maps it to the
// platform coordinates with the body's twist shaping referred to O, xi_i = U_i xi_P (U_i =
// [s_1 .. s_k] rows of J_j^-1, identity for the platform), W = sum_i U_i^T Y_w,i, plus the
// friction columns J_j^-T e_k (q'_k, sign q'_k); then tau = A^-T W (three actuators) or the
// minimum-norm A (A^T A)^-1 W (redundant), exactly as inverse dynamics applies them. For a
// two-DOF robot (motion: translation, task map E) only the force rows count, E^T S(c)^T W = [W_x; W_y]:
// tau = A_E (A_E^T A_E)^-1 [W_x; W_y], A_E = A S(c) E the x, y columns of A. Its platform is a point
// mass at the tool point that never turns, so the platform's m c_x, m c_y and I_O columns are zero,
// as are the friction columns of each limb's last R joint (it turns with the fictitious theta).
#pragma once

#include <string>

#include <Eigen/Core>

#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Inertial parameters per body and friction parameters per joint.
inline constexpr int kBodyParameters = 4;
inline constexpr int kJointParameters = 2;
/// Largest number of standard parameters a model has.
inline constexpr int kMaxParameters = kBodyParameters * kMaxBodies + kJointParameters * 3 * kMaxLimbs;

/// Regressor Y: n actuators x P standard parameters. Fixed capacity: never allocates.
using RegressorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxActuators, kMaxParameters>;
/// The standard parameter vector pi. Fixed capacity.
using ParameterVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxParameters, 1>;

/// Number of standard parameters P = 4 bodies + 2 * 3 limbs.
[[nodiscard]] int parameterCount(const Model& model);
/// Index of body i's first parameter (m), and of joint k of limb j's damping (friction + 1).
[[nodiscard]] int bodyParameterIndex(int body);
[[nodiscard]] int jointParameterIndex(const Model& model, int limb, int joint);
/// "platform.m", "limb2.body1.I_O", "limb1.joint3.damping": the name of parameter `index`.
[[nodiscard]] std::string parameterName(const Model& model, int index);
/// The unit of parameter `index` ("kg", "kg m", "kg m^2", "N s/m", "N", ...).
[[nodiscard]] std::string parameterUnit(const Model& model, int index);

/// pi of the model (the values the robot file gives).
[[nodiscard]] ParameterVector standardParameters(const Model& model);
/// The inertial parameters [m, m c_x, m c_y, I_O] of a body of mass m, c.o.m. c (in its frame)
/// and moment of inertia I about the c.o.m.
[[nodiscard]] Eigen::Vector4d inertialParameters(double mass, const Vector2& com, double inertia);

/// Regressor stage: Y with tau = Y pi for the motion in `data`. Needs the position (with q),
/// velocity and acceleration stages (not the shaping stage). Allocation-free.
void regressor(const Model& model, const Data& data, RegressorMatrix& Y);

/// Position, velocity and acceleration stages from p, dp/dt, d2p/dt2, then Y.
Status inverseDynamicsRegressor(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                                RegressorMatrix& Y);

}  // namespace nocdyn
