// 3-PRR twist-shaping matrices and dynamics (eqs. 20-31).
#pragma once

#include "nocdyn/prr3/model.hpp"
#include "nocdyn/prr3/status.hpp"

namespace nocdyn::prr3 {

/// Shaping stage. Needs the position and velocity stages. Computes the twist-shaping
/// matrices T_i of the seven bodies (eqs. 25-31) and their exact time derivatives dT_i,
/// together with dH/dt and dD/dt.
void twistShaping(const Model& model, Data& data);

/// Dynamics stage: I and C (eq. 23). Needs the shaping stage.
void jointSpaceDynamics(const Model& model, Data& data);

/// Forces stage: tau = I ddu + C du (eq. 20). Needs the dynamics stage and ddu.
void actuatorForces(Data& data);

/// The whole per-sample path in pose space: (p, dp, ddp) -> u, du, ddu, T, dT, I, C, tau.
/// Allocation-free; the Status reports unreachable or singular poses.
Status inverseDynamics(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp);

/// Checks |tau_j| <= peak force for every limb (forces stage needed).
[[nodiscard]] Status checkForce(const Model& model, const Data& data);

/// Kinetic energy of the whole robot, sum_i t_i^T M_i t_i / 2 with t_i = T_i du [J].
[[nodiscard]] double kineticEnergy(const Model& model, const Data& data);

}  // namespace nocdyn::prr3
