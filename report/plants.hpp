// The plants a closed loop runs on, by the name the command line gives: the independent
// Simbody model (when built in), nocdyn's error-controlled forward dynamics, or its fixed-step
// Runge-Kutta 4 (shake.hpp).
#pragma once

#include <memory>
#include <string>

#include "nocdyn/description.hpp"
#include "nocdyn/sim/control.hpp"

namespace nocdyn::report {

/// "simbody" when built with the Simbody model, else "nocdyn".
[[nodiscard]] std::string defaultPlantName();

/// The plants by name: the choices of every command and function that chooses a plant.
inline constexpr const char* kPlantNames[] = {"simbody", "nocdyn", "nocdyn-rk4"};

/// The plant `name` (simbody, nocdyn or nocdyn-rk4) built from `robot`; accuracy: Simbody's
/// integrator accuracy. Throws nocdyn::Error naming --plant for a plant not built in.
[[nodiscard]] std::unique_ptr<RobotPlant> makePlant(const std::string& name, const RobotDescription& robot,
                                                    double accuracy = 1e-10);

}  // namespace nocdyn::report
