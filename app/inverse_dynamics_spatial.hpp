// `inverse-dynamics` of a spatial robot (space: spatial): actuator variables, rates,
// accelerations and forces along a pose trajectory p(t) (spatial_trajectory.hpp), sample by
// sample through spatial::inverseDynamics (the NOC in six dimensions, nocdyn/spatial.hpp).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "app/inverse_dynamics.hpp"
#include "app/observer.hpp"
#include "app/table.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_trajectory.hpp"

namespace nocdyn::app {

/// The table's columns: t, the pose coordinates (x, y, z and, for motion full, roll, pitch,
/// yaw), u1..un, du1..dun, ddu1..ddun, tau1..taun and kinetic (the kinetic energy [J]).
[[nodiscard]] std::vector<std::string> spatialInverseDynamicsColumns(const spatial::Model& model);

/// The trajectory options.trajectory names for a robot of `dimension` pose coordinates (a
/// file: .csv samples or YAML harmonics). Throws nocdyn::Error for a trajectory built in code
/// (planar) and as io::loadSpatialTrajectory.
[[nodiscard]] spatial::Trajectory spatialTrajectoryOf(const SamplingOptions& options, int dimension);

/// One output sample of streamSpatialTrajectory: its time, pose and every per-sample quantity
/// of spatial::inverseDynamics (limbs, u, du, ddu, tau), and the kinetic energy [J].
struct SpatialSample {
    double t = 0.0;
    const spatial::TaskVector& p;
    const spatial::Data& data;
    double kinetic = 0.0;
};

/// The sampling of the spatial jobs (inverse-dynamics, loads): t_k = k / rate, k =
/// 0..round(duration * rate) - 1 (the duration asked for, else the trajectory's, else 0.2 s),
/// each output sample handed to `sink` as computed. A trajectory of another dimension than the
/// robot's, a rate at or below twice the highest harmonic or too long a run are refused
/// (before any sample); between output samples the motion is also checked at 40 points per
/// period of that harmonic. A pose out of reach, a singular posture or a non-finite value
/// throws nocdyn::Error "t = ... s: <reason naming the limb>"; a joint's range or velocity, or
/// an actuator's effort, beyond its limit too, unless allow_limits (then listed in the summary
/// and warned of). `start` is called once the run is accepted, before the first sample.
InverseDynamicsResult streamSpatialTrajectory(const spatial::Model& model, const spatial::Trajectory& trajectory,
                                              const SamplingOptions& sampling, bool allow_limits, Observer& observer,
                                              const std::function<void()>& start,
                                              const std::function<void(const SpatialSample&)>& sink);

/// Samples the trajectory (streamSpatialTrajectory) into `table`, row by row as computed.
InverseDynamicsResult runSpatialInverseDynamics(const spatial::Model& model, const spatial::Trajectory& trajectory,
                                                const SamplingOptions& sampling, bool allow_limits, TableSink& table,
                                                Observer& observer);

/// The same for options.robot, a spatial robot file (with its overrides), and the trajectory
/// file options.trajectory. Refuses `reactions` (planar only).
InverseDynamicsResult runSpatialInverseDynamics(const InverseDynamicsOptions& options, TableSink& table,
                                                Observer& observer);

}  // namespace nocdyn::app
