// `validate` of a spatial robot (space: spatial): nocdyn's actuator forces tau(t) along a pose
// trajectory p(t) (spatial::inverseDynamics, the NOC in six dimensions) against those of the
// independent Simbody model of the same robot file (validation::SimbodySpatialMechanism, its
// loops closed by ball and universal constraints). MuJoCo's models are planar for now. Built
// with both engines only, as the planar job (app/validate.hpp).
#pragma once

#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/validate.hpp"
#include "nocdyn/spatial.hpp"

namespace nocdyn::app {

/// The table's columns: t, the pose coordinates (x, y, z and, for motion full, roll, pitch,
/// yaw), u1..un, tau1..taun (nocdyn's), simbody_tau1..n and simbody_dtau1..n (Simbody's tau
/// minus nocdyn's), named as the planar table's.
[[nodiscard]] std::vector<std::string> spatialValidateColumns(const spatial::Model& model);

/// options.robot, a spatial robot file (with its overrides), along the trajectory file
/// options.trajectory, sampled as `inverse-dynamics` samples it (runSpatialInverseDynamics: the
/// same rows, limits recorded and warned of, not enforced). The agreement: per actuator
/// max_t |tau_a - tau_a^Simbody| and that over max_t |tau_a|, then the largest of the latter.
/// Throws nocdyn::Error as runSpatialInverseDynamics, and for a pose Simbody's model cannot
/// assemble or a singular closure.
[[nodiscard]] ValidateResult runSpatialValidate(const ValidateOptions& options, Observer& observer);

}  // namespace nocdyn::app
