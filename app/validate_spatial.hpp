// `validate` of a spatial robot (space: spatial): nocdyn's actuator forces tau(t) along a pose
// trajectory p(t) (spatial::inverseDynamics, the NOC in six dimensions) against those of the
// independent Simbody and MuJoCo models of the same robot file
// (validation::SimbodySpatialMechanism, validation::MujocoSpatialMechanism: their loops closed
// by ball and universal constraints), both or one (options.engine). Built with both engines
// only, as the planar job (app/validate.hpp).
#pragma once

#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/validate.hpp"
#include "nocdyn/spatial.hpp"

namespace nocdyn::app {

/// The names of options.engine's engines: both is {"simbody", "mujoco"}, simbody or mujoco itself.
[[nodiscard]] std::vector<std::string> spatialValidateEngines(ValidateEngine engine);

/// The table's columns: t, the pose coordinates (x, y, z and, for motion full, roll, pitch,
/// yaw), u1..un, tau1..taun (nocdyn's), then <engine>_tau1..n of each engine and
/// <engine>_dtau1..n (the engine's tau minus nocdyn's), named as the planar table's
/// (simbody_tau, mujoco_tau, simbody_dtau, mujoco_dtau for both).
[[nodiscard]] std::vector<std::string> spatialValidateColumns(const spatial::Model& model,
                                                              const std::vector<std::string>& engines);

/// options.robot, a spatial robot file (with its overrides), along the trajectory file
/// options.trajectory, sampled as `inverse-dynamics` samples it (runSpatialInverseDynamics: the
/// same rows, limits recorded and warned of, not enforced). The agreement: per actuator
/// max_t |tau_a - tau_a^engine| and that over max_t |tau_a| per engine, then the largest of the
/// latter. Throws nocdyn::Error as runSpatialInverseDynamics, and for a pose an engine's model
/// cannot assemble or a singular closure.
[[nodiscard]] ValidateResult runSpatialValidate(const ValidateOptions& options, Observer& observer);

}  // namespace nocdyn::app
