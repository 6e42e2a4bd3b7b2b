// The workspace map (workspace.hpp) as a figure, with optional paths of C drawn over it.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/analysis/workspace.hpp"
#include "plot.hpp"

namespace nocdyn::report {

/// Outline of the feasible region, the two kinds of singularity curves and the home position,
/// in mm, equal axes; `paths` (label, x [m], y [m]) drawn as lines on top.
[[nodiscard]] Figure workspaceFigure(const WorkspaceMap& map, const Model& model, const std::vector<PlotSeries>& paths);

/// One paragraph for a summary: the area, the box, the counts of curve points.
[[nodiscard]] std::string workspaceSummary(const WorkspaceMap& map);

}  // namespace nocdyn::report
