// Robot files (YAML). The only code that reads robot descriptions from disk.
//
//   name: paper-3prr                      # optional (default: the file's stem)
//   geometry: {base_side: 0.400, platform_side: 0.110, link_length: 0.15915, link_com: 0.079575}
//   slider:   {mass: 1.46966}
//   link:     {mass: 0.63863, inertia: 1.5786066e-3}     # about its c.o.m.
//   platform: {mass: 1.75257, inertia: 6.17311382e-3}    # about C
//   actuator: {stroke: 0.0249, peak_force: 262.0}
//   limits:   {max_condition: 1.0e4}      # optional
//
// SI units. Every key above except `name` and `limits` is required; unknown keys are errors.
#pragma once

#include <string>

#include "nocdyn/io/short_form.hpp"

namespace nocdyn::io {

/// Reads and validates a robot file. Throws nocdyn::Error "FILE:LINE: field: reason".
[[nodiscard]] RobotParameters loadRobot(const std::string& path);

/// Parses robot YAML text; `source` names it in error messages.
[[nodiscard]] RobotParameters parseRobot(const std::string& text, const std::string& source);

/// The robot as YAML text in the schema above (round-trips through parseRobot).
[[nodiscard]] std::string robotToYaml(const RobotParameters& robot);

}  // namespace nocdyn::io
