// The plants a closed loop runs on, by the name the command line gives: the independent
// Simbody model (when built in), nocdyn's error-controlled forward dynamics, or its fixed-step
// Runge-Kutta 4 (shake.hpp).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

#include "nocdyn/description.hpp"
#include "nocdyn/general_control.hpp"

namespace nocdyn::report {

/// "simbody" when built with the Simbody model, else "nocdyn".
[[nodiscard]] std::string defaultPlantName();

/// Adds --plant (simbody, nocdyn or nocdyn-rk4): every command that chooses a plant offers all
/// three with this one definition.
CLI::Option* addPlantOption(CLI::App& command, std::string& plant);

/// The plant `name` (simbody, nocdyn or nocdyn-rk4) built from `robot`; accuracy: Simbody's
/// integrator accuracy. Throws nocdyn::Error naming --plant for a plant not built in.
[[nodiscard]] std::unique_ptr<RobotPlant> makePlant(const std::string& name, const RobotDescription& robot,
                                                    double accuracy = 1e-10);

}  // namespace nocdyn::report
