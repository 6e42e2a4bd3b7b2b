// Robot files of either form (YAML): the general per-limb form, or the paper's symmetric
// 3-PRR short form (robot_yaml.hpp), which means the general robot it expands to.
//
//   name: example                 # optional
//   gravity: [0.0, 0.0]           # optional, base frame [m/s^2]
//   home: [0.0, 0.0, 0.0]         # optional: platform pose [theta, x, y] at home
//   max_condition: 1.0e4          # optional
//   platform: {mass: 1.75, inertia: 6.2e-3, com: [0.0, 0.0]}   # com optional, platform frame
//   limbs:
//     - name: limb1               # optional
//       joints:                   # exactly 3, base to platform
//         - {type: P, direction: [1.0, 0.0], actuated: true,
//            limits: {lower: -0.01245, upper: 0.01245, effort: 262.0, velocity: 1.0},
//            damping: 0.0, friction: 0.0}
//         - {type: R, point: [-0.080353, -0.115470]}
//         - {type: R, point: [0.055000, -0.031754]}
//       bodies:                   # exactly 2
//         - {mass: 1.46966, inertia: 0.0, com: [-0.080353, -0.115470]}
//         - {mass: 0.63863, inertia: 1.5786066e-3, com: [-0.012676, -0.073612]}
//
// Every error names the file, line, limb, joint and field.
#pragma once

#include <string>

#include "nocdyn/description.hpp"

namespace nocdyn::io {

/// Reads a robot file of either form and validates it. Throws nocdyn::Error.
[[nodiscard]] RobotDescription loadRobotDescription(const std::string& path);

/// Parses robot YAML text of either form; `source` names it in messages.
[[nodiscard]] RobotDescription parseRobotDescription(const std::string& text, const std::string& source);

/// The text of a robot file, read as every reader reads (a regular file, size-capped).
[[nodiscard]] std::string readRobotFileText(const std::string& path);

/// Whether robot YAML text is of the general form (it has `limbs`) rather than the short form.
[[nodiscard]] bool isGeneralForm(const std::string& text, const std::string& source);

/// The robot in the general form, numbers in their shortest round-trip decimal form
/// (parseRobotDescription reads back the same doubles).
[[nodiscard]] std::string descriptionToYaml(const RobotDescription& robot);

}  // namespace nocdyn::io
