// `control` of a spatial robot (space: spatial): computed torque or PD in the pose coordinates
// on nocdyn's spatial plant (nocdyn/sim/spatial_control.hpp), with the options and the result
// of the planar job (app/control.hpp).
#pragma once

#include "app/control.hpp"
#include "app/observer.hpp"

namespace nocdyn::app {

/// The closed loop along options.trajectory (a spatial trajectory file) on the nocdyn plant:
/// the table t, the desired and achieved pose (x_d, .., x, ..), u1..un and tau1..taun, and the
/// report (RMS and peak pose errors, peak forces, saturated ticks). Refuses what is planar for
/// now: the Simbody plant (chosen), a payload, encoders and the sensors' log.
[[nodiscard]] ControlResult runSpatialControl(const ControlOptions& options, Observer& observer);

}  // namespace nocdyn::app
