// `shake` on a six-DOF table (a spatial robot with motion: full, a hexapod): a record given as
// its components (two horizontals and a vertical), rotated onto the table's x, y, z
// (io::combineComponents), fitted to every leg's stroke, rate and force and replayed in closed
// loop with the rotations held at zero (nocdyn/sim/spatial_shake.hpp).
#pragma once

#include "app/observer.hpp"
#include "app/shake.hpp"

namespace nocdyn::app {

/// The replay's table (t, the target pose x_d, y_d, z_d, the target ax, ay, az, the achieved
/// ax_achieved, ay_achieved, az_achieved, the achieved pose x .. yaw, u1..u6, tau1..tau6 at the
/// record's instants), shake.json (scales, limit use, metrics keyed ax, ay, az, the rotations'
/// parasitic peaks) and the text with one verdict per axis; handed to `files` (when
/// options.out_dir is given) with the figures per axis and shake_animation.html (the achieved motion in 3-D). Several
/// records (a folder) are a suite: the files grouped into three-component records by their shared name prefix, one
/// folder each and summary.md. With identify_payload the specimen is identified first (app/shake_spatial_payload.hpp;
/// one record, not a suite) and the controller's model carries it as identified. Refuses what is planar only (the
/// Simbody plant, drive iteration, theta and y records) with the option's name.
[[nodiscard]] ShakeResult runSpatialShake(const ShakeOptions& options, Observer& observer, FileSink& files);

}  // namespace nocdyn::app
