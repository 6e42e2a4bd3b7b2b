// `workspace`: the feasible region of C at one platform orientation, with both kinds of
// singularity curves (workspace.hpp).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/analysis/frequency_map.hpp"
#include "nocdyn/analysis/workspace.hpp"
#include "nocdyn/io/csv.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

inline constexpr Range kWorkspaceThetaRange{-1e3, 1e3, "rad"};
inline constexpr Range kWorkspaceResolutionRange{11.0, 2001.0, "points"};

struct WorkspaceOptions {
    RobotSource robot;
    /// Platform orientation [rad]; empty: the robot's home orientation.
    std::optional<double> theta;
    int resolution = 201;  ///< grid points per side (kWorkspaceResolutionRange)
    /// Also the first natural frequency of the lumped model at every feasible point
    /// (frequency_map.hpp); the robot file must declare compliance.
    bool first_frequency = false;
};

struct WorkspaceResult {
    std::shared_ptr<const Model> model;
    WorkspaceMap map;
    /// The summary line (area, box, curve points).
    std::string summary;
    /// The grid as the CSV's table (io::TableId::workspace): x, y [m], cell as words.
    io::Table table;
    /// With options.first_frequency: f_1 per grid point [Hz] (NaN where not feasible), its
    /// lowest and where, and the feasible points as a table (io::TableId::first_frequency).
    std::optional<FirstFrequencyMap> frequency;
    io::Table frequency_table;
};

/// Throws OptionError for theta or resolution out of range.
void validate(const WorkspaceOptions& options);

/// The map (and with first_frequency the frequency map: throws nocdyn::Error for a robot that
/// declares no compliance); progress in grid columns, a stop between columns.
[[nodiscard]] WorkspaceResult runWorkspace(const WorkspaceOptions& options, Observer& observer);

/// The map as a figure (feasible region, singularity curves), written by writeWorkspaceFigure
/// (app/outputs.hpp).
[[nodiscard]] render::Figure workspaceResultFigure(const WorkspaceResult& result);

/// The first natural frequency over the map as a heat map with its lowest point, written by
/// writeFrequencyFigure (app/outputs.hpp). Throws nocdyn::Error when the result holds no
/// frequency map.
[[nodiscard]] render::Figure frequencyResultFigure(const WorkspaceResult& result);

}  // namespace nocdyn::app
