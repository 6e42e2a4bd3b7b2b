// The joints' limits of a spatial robot (robot-files-spatial.md: an R or P joint's range and
// velocity, an actuator's effort; U and S joints take none), checked after the inverse dynamics.
#pragma once

#include <string>

#include "nocdyn/spatial.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn::spatial {

/// The first limit passed at the sample data holds (after inverseDynamics), limb by limb and
/// freedom by freedom: joint_limit_exceeded (value q), velocity_exceeded (value q') or
/// effort_exceeded (value tau), with limb and joint the 0-based limb and listed joint; ok when
/// every one holds. Allocation-free.
[[nodiscard]] Status checkLimits(const Model& model, const Data& data);

/// One line for a status of checkLimits: "joint range exceeded: limb 1 (leg1), joint 2: q = ...,
/// range [lower, upper]", and the same for a velocity and an effort.
[[nodiscard]] std::string describeLimit(const Status& status, const Model& model);

}  // namespace nocdyn::spatial
