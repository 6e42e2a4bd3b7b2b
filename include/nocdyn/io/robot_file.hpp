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
//
// Parametric files: either form may declare named parameters, and any number in it may be an
// arithmetic expression of them (numbers, the parameters, + - * / ^, parentheses, sin cos tan
// asin acos atan atan2 sqrt abs min max, pi; radians). A parameter may use those above it.
//
//   parameters: {r_b: 0.2, r_p: 0.5 * r_b}
//   ...  - {type: R, point: [r_b * cos(7 * pi / 6), r_b * sin(7 * pi / 6)]}
//
// An expression with a comma (atan2, min, max) inside a YAML flow list is quoted:
// ["atan2(y, x)", 0.0]. An error names the file, line, field and the expression.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/description.hpp"
#include "nocdyn/spatial_description.hpp"

namespace nocdyn::io {

/// A named parameter of a robot file and its value.
struct Parameter {
    std::string name;
    double value = 0.0;
};
/// Parameters in the order they are declared (or given).
using ParameterSet = std::vector<Parameter>;

/// The refusal of a spatial robot file by every command (after the file is read and checked).
inline constexpr const char* kSpatialNotComputed =
    "a spatial robot (space: spatial): this command is planar for now (nocdyn pose and Robot.load take it)";

/// Reads a robot file of either form and validates it (a spatial file is read and checked, then
/// refused with kSpatialNotComputed), each parameter in `overrides`
/// replacing the file's value (a name the file does not declare is an error). Throws
/// nocdyn::Error.
[[nodiscard]] RobotDescription loadRobotDescription(const std::string& path, const ParameterSet& overrides = {});

/// Reads a spatial robot file (`space: spatial`, ../shared/robot-files-spatial.md) and checks
/// it: every error names the file, line, limb, joint or body and field. Throws nocdyn::Error
/// (also for a planar file).
[[nodiscard]] SpatialRobotDescription loadSpatialRobotDescription(const std::string& path,
                                                                  const ParameterSet& overrides = {});
[[nodiscard]] SpatialRobotDescription parseSpatialRobotDescription(const std::string& text, const std::string& source,
                                                                   const ParameterSet& overrides = {});

/// Whether robot YAML text is a spatial robot file (`space: spatial`).
[[nodiscard]] bool isSpatial(const std::string& text, const std::string& source);

/// Parses robot YAML text of either form; `source` names it in messages.
[[nodiscard]] RobotDescription parseRobotDescription(const std::string& text, const std::string& source,
                                                     const ParameterSet& overrides = {});

/// The parameters robot YAML text declares, with their values after `overrides` (empty when it
/// declares none). Throws nocdyn::Error as parseRobotDescription.
[[nodiscard]] ParameterSet robotFileParameters(const std::string& text, const std::string& source,
                                               const ParameterSet& overrides = {});

/// "NAME=VALUE" (the value a finite decimal number) as a parameter; throws nocdyn::Error naming
/// the text otherwise.
[[nodiscard]] Parameter parseParameterAssignment(const std::string& text);

/// The text of a robot file, read as every reader reads (a regular file, size-capped).
[[nodiscard]] std::string readRobotFileText(const std::string& path);

/// Whether robot YAML text is of the general form (it has `limbs`) rather than the short form.
[[nodiscard]] bool isGeneralForm(const std::string& text, const std::string& source);

/// The robot in the general form, numbers in their shortest round-trip decimal form
/// (parseRobotDescription reads back the same doubles).
[[nodiscard]] std::string descriptionToYaml(const RobotDescription& robot);

}  // namespace nocdyn::io
