// `loads` of a spatial robot (space: spatial): every listed joint's design loads along a pose
// trajectory p(t) (spatial_trajectory.hpp), sampled as `inverse-dynamics` samples it
// (streamSpatialTrajectory), each sample's reactions from spatial::jointReactions: the force
// and the moment about the joint's point that the inboard body passes to the outboard body,
// the joint's efforts taken out (an S passes no moment, a U none about its two axes).
#pragma once

#include <string>
#include <vector>

#include "app/loads.hpp"
#include "app/observer.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_trajectory.hpp"

namespace nocdyn::app {

/// One listed joint's loads along the trajectory.
struct SpatialJointLoad {
    char type = 'R';          ///< R, P, U or S
    double peak_force = 0.0;  ///< largest |f| [N]
    double peak_force_t = 0.0;
    std::vector<double> peak_force_pose;  ///< the pose there (x, y, z and, for motion full, roll, pitch, yaw)
    double peak_moment = 0.0;             ///< largest |m| [N m]
    double peak_moment_t = 0.0;
    double sum_squared_force = 0.0;  ///< sum of |f|^2 over the samples [N^2]
    long samples = 0;
    /// RMS of |f| over the samples [N].
    [[nodiscard]] double rmsForce() const;
};

struct SpatialLoadsResult {
    std::vector<std::vector<SpatialJointLoad>> joint;  ///< [limb][listed joint], file order
    std::vector<std::string> limb_names;
    int worst_limb = 1, worst_joint = 1;  ///< 1-based: the joint of the largest peak force
    std::size_t samples = 0;
    /// The CSV's table: limb, joint (1-based), type (a word: R, P, U or S), peak_force,
    /// peak_force_t, peak_force_<coordinate> per pose coordinate, rms_force, peak_moment,
    /// peak_moment_t.
    io::Table table;
    /// One line per joint, then the largest.
    std::string text;
};

/// The loads of `model` along `trajectory`: every sample's reactions (the peaks are those of
/// the output samples; the motion between them is checked as streamSpatialTrajectory does). A
/// pose out of reach, a singular posture, a limit passed or a non-finite reaction throws
/// nocdyn::Error "t = ... s: <reason naming the limb>".
[[nodiscard]] SpatialLoadsResult runSpatialLoads(const spatial::Model& model, const spatial::Trajectory& trajectory,
                                                 const SamplingOptions& sampling, Observer& observer);

/// The same for options.robot, a spatial robot file (with its overrides), and the trajectory
/// file options.trajectory, as LoadsResult (model null, loads empty: table, text and the worst
/// joint). Throws OptionError("envelope") for the envelope (planar robots only).
[[nodiscard]] LoadsResult runSpatialLoads(const LoadsOptions& options, Observer& observer);

}  // namespace nocdyn::app
