// The plants a closed loop runs on, by kind (PlantKind, nocdyn/sim/plant.hpp): the independent
// Simbody model (when built in: validation/simbody, SimbodyPlant), nocdyn's error-controlled
// forward dynamics, or its fixed-step Runge-Kutta 4.
#pragma once

#include <memory>

#include "nocdyn/description.hpp"
#include "nocdyn/sim/plant.hpp"

namespace nocdyn::app {

/// Simbody when built with the Simbody model, else nocdyn.
[[nodiscard]] PlantKind defaultPlant();

/// The plant of `kind` built from `robot`; accuracy: Simbody's integrator accuracy. Throws
/// nocdyn::Error naming --plant for a plant not built in.
[[nodiscard]] std::unique_ptr<RobotPlant> makePlant(PlantKind kind, const RobotDescription& robot,
                                                    double accuracy = 1e-10);

}  // namespace nocdyn::app
