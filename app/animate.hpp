// `animate`: the robot moving along a trajectory or a recorded motion as one self-contained HTML
// page (render/animation.hpp), and a static frame as a figure (render/plot.hpp).
#pragma once

#include <optional>
#include <string>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/io/csv.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

inline constexpr Range kSlowMotionRange{1.0, 1e6, ""};
inline constexpr Range kMagnifyRange{0.0, 1e4, ""};
inline constexpr Range kFrameRange{-1e6, 1e6, "s"};

struct AnimateOptions : SamplingOptions {
    RobotSource robot;
    /// A CSV with t,x,y,theta,tau1..taun (simulate, control, inverse-dynamics, shake), instead
    /// of the trajectory. A trajectory CSV with these columns is played so too.
    std::string motion;
    /// The same as a table in memory (Python's Table), named motion_name on the page.
    std::optional<io::Table> motion_table;
    std::string motion_name = "motion";
    double slow_motion = 0.0;     ///< K: 1 s of motion plays in K s; 0: the whole motion in about 10 s
    double magnify = 1.0;         ///< displacements about the mean pose drawn this many times larger
    std::optional<double> frame;  ///< also draw the sample nearest to this time [s] (planar)
};

/// Throws OptionError naming the field of a value out of range or options that do not go together.
void validate(const AnimateOptions& options);

struct AnimateResult {
    std::string html;                     ///< the page
    std::optional<render::Figure> frame;  ///< with options.frame: the robot at that sample
};

/// Samples the motion (warnings through the observer), draws the frame when asked, builds the
/// page. Writes no file: the front ends write the page and render the frame where their caller
/// asks (never over an input file).
AnimateResult runAnimate(const AnimateOptions& options, Observer& observer);

}  // namespace nocdyn::app
