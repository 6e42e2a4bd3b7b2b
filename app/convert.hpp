// `convert`: any robot file (short or general form, parametric) as the plain general per-limb
// form, numbers in shortest round-trip form.
#pragma once

#include <string>

#include "app/observer.hpp"
#include "app/options.hpp"

namespace nocdyn::app {

struct ConvertOptions {
    /// The robot file (required: the built-in prototype has no file to convert) and its overrides.
    RobotSource robot;
};

struct ConvertResult {
    std::string robot;  ///< its name
    int limbs = 0, actuators = 0;
    /// A comment line naming the robot, its limbs and actuators, then the YAML of the general form.
    std::string text;
};

/// Throws OptionError("robot") when no robot is given.
void validate(const ConvertOptions& options);

/// The robot in the general form; its home posture must be regular, as for every command.
[[nodiscard]] ConvertResult runConvert(const ConvertOptions& options, Observer& observer);

}  // namespace nocdyn::app
