// The forward-kinematics report of a spatial robot apart from cmd_forward_kinematics.cpp: every
// assembly mode found, as text or JSON (poses keyed x, y, z and roll, pitch, yaw).
#pragma once

#include "app/forward_kinematics_spatial.hpp"

namespace nocdyn::cli {

void printSpatialForwardKinematics(const app::SpatialForwardKinematicsResult& r, bool json);

}  // namespace nocdyn::cli
