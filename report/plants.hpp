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

/// The plants by name, with what each is: the choices of every command that chooses a plant.
inline constexpr const char* kPlantNames[] = {"simbody", "nocdyn", "nocdyn-rk4"};
inline constexpr const char* kPlantHelp =
    "simbody (the independent model, integrated to its accuracy: about 0.4 s of motion per CPU "
    "second at 10 kHz), nocdyn (nocdyn's forward dynamics, error-controlled to 1e-10: about 17 s "
    "per CPU second) or nocdyn-rk4 (the same, one Runge-Kutta 4 step per controller tick: about "
    "26 s per CPU second; docs/validation.md, earthquake replay)";

/// The plant `name` (simbody, nocdyn or nocdyn-rk4) built from `robot`; accuracy: Simbody's
/// integrator accuracy. Throws nocdyn::Error naming --plant for a plant not built in.
[[nodiscard]] std::unique_ptr<RobotPlant> makePlant(const std::string& name, const RobotDescription& robot,
                                                    double accuracy = 1e-10);

}  // namespace nocdyn::report
