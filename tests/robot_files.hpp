// The repository's example robot files (robots/<name>.yaml), read as the tests of stiffness and
// frequencies use them.
#pragma once

#include <string>

#include "nocdyn/io/robot_file.hpp"

namespace nocdyn {

/// The description of robots/<robot>.yaml in the source tree.
inline RobotDescription robotDescription(const std::string& robot) {
    // appended, not a chain of +: GCC 12 warns (-Warray-bounds, a false positive) on the chain here
    std::string path = NOCDYN_SOURCE_DIR;
    path.append("/robots/").append(robot).append(".yaml");
    return io::loadRobotDescription(path);
}

}  // namespace nocdyn
