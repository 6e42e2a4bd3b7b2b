// The robot in motion: a self-contained HTML page (inline script and canvas, the data as JSON,
// nothing fetched at view time) and static frames drawn by gnuplot, both from the points of
// drawRobot (nocdyn/drawing.hpp).
#pragma once

#include <string>
#include <vector>

#include "nocdyn/io/csv.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/trajectory.hpp"
#include "render/plot.hpp"

namespace nocdyn::render {

/// Samples of a motion: times, poses, actuator variables and forces (n = model.actuators).
struct MotionSamples {
    std::string source;       ///< trajectory name or CSV file, for the page
    std::vector<double> t;    ///< [s], increasing
    std::vector<Pose> p;      ///< [theta, x, y]
    std::vector<double> u;    ///< u_a of sample k at k * n + a [m or rad]
    std::vector<double> tau;  ///< tau_a of sample k at k * n + a [N or N m]
    /// The target pose of sample k when p is what a replay achieved (shake.csv's x_achieved..);
    /// drawn as a ghost behind the robot. Empty otherwise.
    std::vector<Pose> ghost;
    int actuators = 0;
    std::vector<std::string> warnings;  ///< limits exceeded (shown, not refused)
};

/// Most samples an animation holds in memory.
inline constexpr std::size_t kMaxAnimationSamples = 2'000'000;
/// Most frames and plot buckets embedded in a page.
inline constexpr std::size_t kMaxAnimationFrames = 2000;
inline constexpr std::size_t kMaxPlotBuckets = 800;

/// Inverse dynamics along the trajectory at t_k = k / rate over `duration` (limits recorded
/// as warnings). Throws nocdyn::Error "t = ... s: reason" for a pose out of reach.
[[nodiscard]] MotionSamples motionFromTrajectory(const Model& model, const PoseTrajectory& trajectory, double duration,
                                                 double rate);

/// A CSV written by simulate, control or inverse-dynamics: columns t, theta, x, y and
/// tau1..taun; u is recomputed from the pose. A replay's shake.csv (x_achieved, y_achieved,
/// theta_achieved beside the target x, y, theta): the achieved pose is the motion, the target
/// its ghost. Throws nocdyn::Error "FILE:LINE: reason".
[[nodiscard]] MotionSamples motionFromCsv(const Model& model, const std::string& path);

/// The same from a table in memory; `name` stands for the file in messages and on the page.
[[nodiscard]] MotionSamples motionFromTable(const Model& model, const io::Table& table, const std::string& name);

/// Page options: slow-motion factor K (playback lasts K times the motion; 0 = so that the
/// whole motion plays in about 10 s) and the magnification of the displacements about the
/// mean pose.
struct AnimationOptions {
    double slow_motion = 0.0;
    double magnify = 1.0;
};

/// The whole HTML page.
[[nodiscard]] std::string animationPage(const Model& model, const MotionSamples& motion,
                                        const AnimationOptions& options);

/// The robot at the sample nearest to time t, as a gnuplot figure (an equal-axes map).
[[nodiscard]] Figure frameFigure(const Model& model, const MotionSamples& motion, double t);

}  // namespace nocdyn::render
