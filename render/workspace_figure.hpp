// The workspace map (workspace.hpp) as a figure, with optional paths of C drawn over it.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/analysis/frequency_map.hpp"
#include "nocdyn/analysis/workspace.hpp"
#include "render/plot.hpp"

namespace nocdyn::render {

/// Outline of the feasible region, the two kinds of singularity curves and the home position,
/// in mm, equal axes; `paths` (label, x [m], y [m]) drawn as lines on top.
[[nodiscard]] Figure workspaceFigure(const WorkspaceMap& map, const Model& model, const std::vector<PlotSeries>& paths);

/// The first natural frequency over the map as a heat map (blank where not feasible) with its
/// lowest point and the home position, in mm, equal axes.
[[nodiscard]] Figure firstFrequencyFigure(const WorkspaceMap& map, const FirstFrequencyMap& frequency,
                                          const Model& model);

/// One sentence: the lowest first natural frequency and where (x, y), the highest.
[[nodiscard]] std::string firstFrequencySummary(const FirstFrequencyMap& frequency);

/// One paragraph for a summary: the area, the box, the counts of curve points.
[[nodiscard]] std::string workspaceSummary(const WorkspaceMap& map);

}  // namespace nocdyn::render
