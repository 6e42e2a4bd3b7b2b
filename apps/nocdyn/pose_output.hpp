// The pose reports' blocks apart from cmd_pose.cpp: a compliant robot's stiffness and natural
// frequencies, and the whole report of a spatial robot, as text or JSON.
#pragma once

#include <nlohmann/json.hpp>

#include "app/pose.hpp"
#include "app/pose_spatial.hpp"

namespace nocdyn::cli {

[[nodiscard]] nlohmann::json poseComplianceJson(const app::PoseCompliance& c);
void printPoseCompliance(const app::PoseCompliance& c);
void printSpatialPose(const app::SpatialPoseResult& r, bool json);

}  // namespace nocdyn::cli
