// A spatial robot in motion (space: spatial): one self-contained HTML page drawing it in 3-D
// with three.js (Debian's libjs-three, inlined at build time with its OrbitControls; nothing is
// fetched at view time), the data as JSON. Each limb is drawn as its chain of joint points
// (spatial::LimbData::joint_point: base joint, ..., platform joint; a P joint lies on the
// segment it slides along), coloured by its actuator's force; the platform as the polygon of
// its joints; the platform point's path as a trace.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/spatial.hpp"
#include "render/animation.hpp"

namespace nocdyn::render {

/// Samples of a spatial motion: times, poses, actuator variables and forces (n = model.actuators).
struct SpatialMotionSamples {
    std::string source;                  ///< trajectory name, for the page
    std::vector<double> t;               ///< [s], increasing
    std::vector<spatial::TaskVector> p;  ///< [x, y, z (, roll, pitch, yaw)]
    std::vector<double> u;               ///< u_a of sample k at k * n + a [m or rad]
    std::vector<double> tau;             ///< tau_a of sample k at k * n + a [N or N m]
    int actuators = 0;
    std::vector<std::string> warnings;  ///< limits exceeded (shown, not refused)
};

/// The whole HTML page: at most kMaxAnimationFrames frames (evenly spread samples, the first and
/// the last included), each frame's joint points in micrometres and its forces to 17 digits;
/// the plots of u and tau keep every sample's extremes (kMaxPlotBuckets buckets). Throws
/// nocdyn::Error "SOURCE: t = ... s: reason" for a pose the inverse kinematics cannot reach.
[[nodiscard]] std::string spatialAnimationPage(const spatial::Model& model, const SpatialMotionSamples& motion,
                                               const AnimationOptions& options);

}  // namespace nocdyn::render
