// `forward-kinematics` of a spatial robot (space: spatial): every assembly mode found for the
// actuator values (nocdyn/spatial_direct_kinematics.hpp): the Delta's two in closed form (three
// spheres), a hexapod's by many-start continuation.
#pragma once

#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"

namespace nocdyn::app {

struct SpatialForwardKinematicsSolution {
    std::vector<double> pose;    ///< x, y, z (and roll, pitch, yaw) [m, rad]
    bool working = false;        ///< on the home branches, the nearest such mode to home
    bool home_branches = false;  ///< inverse kinematics from home gives back u
    double u_error = 0.0;        ///< max |u(p) - u| over the actuators [m or rad]
    double condition = 0.0;      ///< the largest of the limbs' and the actuation map's
};

struct SpatialForwardKinematicsResult {
    std::string robot;
    std::vector<std::string> coordinates;  ///< x, y, z (and roll, pitch, yaw)
    std::vector<double> u;
    std::vector<bool> revolute;  ///< per actuator: an R joint (rad), else P (m)
    int outside = 0;             ///< 1-based first actuator beyond its joint's range; 0: none
    std::string method;          ///< "three spheres" or "many starts"
    bool complete = false;       ///< every real mode is listed (three spheres)
    int starts = 0;              ///< seeds tried (many starts)
    std::vector<SpatialForwardKinematicsSolution> solutions;  ///< by distance from home
};

/// The assembly modes of u on the spatial robot of `source`. Throws OptionError("u") for the
/// wrong count of values, nocdyn::Error (naming the file) when no mode is found (out of reach);
/// a value beyond its joint's range is reported (outside) and warned of.
[[nodiscard]] SpatialForwardKinematicsResult runSpatialForwardKinematics(const RobotSource& source,
                                                                         const std::vector<double>& u,
                                                                         Observer& observer);

}  // namespace nocdyn::app
