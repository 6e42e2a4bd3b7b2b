// What `control`, `envelope` and the dynamics sections of `reproduce` share: the actuators'
// limits of the paper's prototype and the tracking-error figure of closed-loop runs.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/description.hpp"
#include "nocdyn/sim/control.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

/// The actuators' limits of a robot whose actuated joints share them (the paper's prototype):
/// the first actuated joint's range (upper - lower, the total stroke) and effort (the peak force).
struct ActuatorLimits {
    double stroke = 0.0;      ///< [m or rad]
    double peak_force = 0.0;  ///< [N or N m]
};

[[nodiscard]] ActuatorLimits actuatorLimits(const RobotDescription& robot);

/// Tracking errors u_d - u per actuator [um] versus time, one panel per run.
/// `notes`: a few words per run added to its panel's title (e.g. "payload unknown to the
/// controller"), so that runs of the same controller and plant are told apart; may be empty.
[[nodiscard]] render::Figure trackingErrorFigure(const std::string& title, const std::vector<PoseLoopResult>& runs,
                                                 const std::vector<std::string>& notes = {});

}  // namespace nocdyn::app
