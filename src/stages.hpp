// Internal stages shared by kinematics.cpp and dynamics.cpp (not installed).
#pragma once

#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn::detail {

/// Position stage; R angles are computed only when `angles` (or the joint is actuated).
Status positionStage(const Model& model, Data& data, const Pose& p, bool angles);
/// J_j, J_j^-1, their conditioning, A, Xi (actuator coordinates) and cond_A.
Status jacobianStage(const Model& model, Data& data);
/// Joint rates, body twists, screw rates and du from xi_P.
void rateStage(const Model& model, Data& data);

}  // namespace nocdyn::detail
