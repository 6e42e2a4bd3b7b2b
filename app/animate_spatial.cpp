// `animate` of a spatial robot (animate_spatial.hpp).
#include "app/animate_spatial.hpp"

#include "app/inverse_dynamics_spatial.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/text.hpp"
#include "render/animation3d.hpp"

namespace nocdyn::app {

AnimateResult runSpatialAnimate(const AnimateOptions& options, Observer& observer) {
    if (!options.motion.empty() || options.motion_table) {
        throw OptionError("motion",
                          "plays a planar robot's recorded CSV (t, x, y, theta, tau1..); a spatial robot "
                          "(space: spatial) is animated along its trajectory: give the poses as --trajectory "
                          "(a YAML file, or a CSV of samples t, x, y, z, ..)");
    }
    if (options.frame) {
        throw OptionError("frame",
                          "draws a planar robot's frame with gnuplot (png, svg); a spatial robot (space: "
                          "spatial) is drawn in 3-D on the page only");
    }
    const spatial::Model model(io::loadSpatialRobotDescription(options.robot.path, options.robot.set));
    const spatial::Trajectory trajectory = spatialTrajectoryOf(options, model.task_dimension);
    const double duration = options.duration ? *options.duration : trajectory.duration.value_or(0.2);
    if (const SampleGrid grid = sampleGrid(duration, options.rate); grid.count > render::kMaxAnimationSamples) {
        throw OptionError("duration", "--duration " + text::precise(duration) + " s at --rate " +
                                          text::precise(options.rate) + " Hz gives " + std::to_string(grid.count) +
                                          " samples; animate holds at most " +
                                          std::to_string(render::kMaxAnimationSamples));
    }
    render::SpatialMotionSamples motion;
    motion.source = trajectory.name.empty() ? "trajectory" : trajectory.name;
    const int n = model.actuators;
    motion.actuators = n;
    // limits are recorded and shown on the page, not refused (as the planar animation)
    const InverseDynamicsResult run = streamSpatialTrajectory(model, trajectory, options, /*allow_limits=*/true,
                                                              observer, {}, [&](const SpatialSample& s) {
                                                                  motion.t.push_back(s.t);
                                                                  motion.p.push_back(s.p);
                                                                  for (int a = 0; a < n; ++a) {
                                                                      motion.u.push_back(s.data.u(a));
                                                                      motion.tau.push_back(s.data.tau(a));
                                                                  }
                                                              });
    motion.warnings = run.summary.limit_violations;  // the observer has warned of them
    AnimateResult out;
    out.html = render::spatialAnimationPage(model, motion, {options.slow_motion, options.magnify});
    return out;
}

}  // namespace nocdyn::app
