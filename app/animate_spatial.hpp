// `animate` of a spatial robot (space: spatial): the robot moving along a trajectory file as one
// self-contained HTML page drawing it in 3-D (render/animation3d.hpp), with the options and
// the result of the planar job (app/animate.hpp).
#pragma once

#include "app/animate.hpp"
#include "app/observer.hpp"

namespace nocdyn::app {

/// Samples options.trajectory (a YAML file or a CSV of pose samples) by the spatial inverse
/// dynamics at --rate over --duration (limits warned of and listed on the page, not refused)
/// and builds the 3-D page; writes options.output when given. The options that only make
/// sense for a planar robot are refused in one line: motion (a recorded planar CSV), frame,
/// png and svg (gnuplot's planar frame). The caller has validated the options and checked
/// that no output is an input.
AnimateResult runSpatialAnimate(const AnimateOptions& options, Observer& observer);

}  // namespace nocdyn::app
