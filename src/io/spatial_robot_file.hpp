// The reader of spatial robot files (`space: spatial`, ../shared/robot-files-spatial.md), for
// robot_file.cpp.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "nocdyn/spatial_description.hpp"

namespace nocdyn::io::detail::spatial {

/// The spatial robot of a parsed file; `source` names the file in errors. Throws nocdyn::Error
/// "SOURCE:LINE: limbs[i] (name).joints[k].field: reason" for anything the schema refuses.
[[nodiscard]] SpatialRobotDescription parse(const YAML::Node& root, const std::string& source);

}  // namespace nocdyn::io::detail::spatial
