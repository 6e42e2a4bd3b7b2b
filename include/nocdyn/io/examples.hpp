// The example robots shipped in robots/ (compiled in, so that every build has them):
// paper-3prr (the short form), paper-3prr-general, 3-rrr, 3-rpr and 4-rrr.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/description.hpp"

namespace nocdyn::io {

/// Names of the example robots, in the order above.
[[nodiscard]] const std::vector<std::string>& exampleRobotNames();

/// The YAML text of an example robot; throws nocdyn::Error naming the known ones.
[[nodiscard]] const std::string& exampleRobotText(const std::string& name);

/// The example robot, parsed and validated (its source reads "robots/NAME.yaml").
[[nodiscard]] RobotDescription exampleRobot(const std::string& name);

}  // namespace nocdyn::io
