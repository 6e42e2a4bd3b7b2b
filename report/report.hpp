// The report module: everything `nocdyn reproduce` writes (CSV files, gnuplot figures, the
// animation pages and summary.md), the figures and pages other commands draw (plot.hpp,
// workspace_figure.hpp, animation.hpp), the earthquake replay (shake_replay.hpp) and the plants
// the closed loops run on (plants.hpp). It calls the library; the command line and Python call
// it. Nothing here parses arguments.
#pragma once

#include <functional>
#include <string>

namespace nocdyn::report {

struct ReproduceOptions {
    std::string out = "results";           ///< output folder (created if missing)
    double closed_loop_duration = 0.2;     ///< [s] of each closed-loop run on a Simbody plant
    double identification_duration = 5.0;  ///< [s] of data per identification experiment
};

/// How many sections reproduce() runs (8, or 9 with both engines built in).
[[nodiscard]] int reproduceSections();

/// The paper's results for its prototype and the project's checks on them, into options.out:
/// both paper trajectories (CSV, figures like Figs. 5 and 6, with the engines' curves when built
/// in), animations, the forward-dynamics round trip, closed-loop control, the envelope, the
/// workspace, the El Centro replay, the example robots against Simbody and MuJoCo, and the
/// payload identification experiment; then summary.md. `section`, when given, is called with
/// each section's name before it runs (for a progress display). Throws nocdyn::Error.
void reproduce(const ReproduceOptions& options, const std::function<void(const std::string&)>& section = {});

}  // namespace nocdyn::report
