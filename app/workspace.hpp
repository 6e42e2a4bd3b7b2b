// `workspace`: the feasible region of C at one platform orientation, with both kinds of
// singularity curves (workspace.hpp).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/analysis/workspace.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::app {

inline constexpr Range kWorkspaceThetaRange{-1e3, 1e3, "rad"};
inline constexpr Range kWorkspaceResolutionRange{11.0, 2001.0, "points"};

struct WorkspaceOptions {
    RobotSource robot;
    /// Platform orientation [rad]; empty: the robot's home orientation.
    std::optional<double> theta;
    int resolution = 201;  ///< grid points per side (kWorkspaceResolutionRange)
};

struct WorkspaceResult {
    std::shared_ptr<const Model> model;
    WorkspaceMap map;
    /// The summary line (area, box, curve points).
    std::string summary;
    /// The grid as the CSV's table (io::TableId::workspace): x, y [m], cell as words.
    io::Table table;
};

/// Throws OptionError for theta or resolution out of range.
void validate(const WorkspaceOptions& options);

/// The map; progress in grid columns, a stop between columns.
[[nodiscard]] WorkspaceResult runWorkspace(const WorkspaceOptions& options, Observer& observer);

/// The map as a figure (feasible region, singularity curves): STEM.png and STEM.svg.
void writeWorkspaceFigure(const WorkspaceResult& result, const std::string& stem);

}  // namespace nocdyn::app
