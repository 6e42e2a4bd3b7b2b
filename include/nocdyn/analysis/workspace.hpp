// Workspace of any planar parallel robot at a fixed platform orientation: the region of the
// operation point C reachable on every limb's home branch, within every joint's range and
// away from singularities, on a grid, with the two kinds of singularity curves:
//   limb (serial, type 1): a limb at the edge of its reach, where its J_j (eq. 4a) is
//     singular and its two branches meet;
//   actuation (parallel, type 2): det A = 0, A the map from the platform twist to the
//     actuator rates (eq. 5 generalised), with three actuators; with more, the edge of the
//     region where A's condition number exceeds the model's limit.
// A two-DOF robot (motion: translation) has no orientation: the map is of its tool point C at
// theta = home(0), which moves no body (model.hpp's task map), and its actuation singularity
// with two actuators is det A_t = 0, A_t = A S(c) E the x, y columns of A (the five-bar's
// forearms aligned); with more actuators, the edge where A_t's condition number exceeds the limit.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "nocdyn/model.hpp"

namespace nocdyn {

struct WorkspaceOptions {
    double theta = 0.0;    ///< platform orientation [rad]
    int resolution = 201;  ///< grid points per side, in [11, 2001]
    bool curves = true;    ///< trace the singularity curves (the area and conditions need none)
    /// Called after each grid column with the columns done and their total (a progress line).
    std::function<void(int done, int total)> progress = {};
};

/// What limits each grid point.
enum class WorkspaceCell : std::uint8_t {
    feasible = 0,     ///< reachable, within every joint range, regular
    unreachable = 1,  ///< a limb cannot reach
    range = 2,        ///< a joint outside its range
    singular = 3,     ///< a limb or the actuation beyond the condition-number limit
};

struct WorkspaceMap {
    double theta = 0.0;
    int task_dimension = 3;                   ///< the model's: 2 for a two-DOF robot (no theta)
    double x0 = 0.0, y0 = 0.0;                ///< grid point (0, 0) [m]
    double step = 0.0;                        ///< grid spacing [m]
    int n = 0;                                ///< grid points per side
    std::vector<WorkspaceCell> cells;         ///< row-major: point (i, k) at x0 + i step, y0 + k step
    std::vector<Vector2> limb_singular;       ///< points on type-1 curves [m]
    std::vector<Vector2> actuation_singular;  ///< points on type-2 curves [m]
    double area = 0.0;                        ///< of the feasible points, step^2 each [m^2]
    /// Per grid point (as `cells`): the scaled condition number of A at a feasible point, NaN
    /// elsewhere.
    std::vector<double> condition;
    [[nodiscard]] WorkspaceCell cell(int i, int k) const {
        return cells[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(k)];
    }
};

/// Dexterity over the feasible points of a map: the median and the largest (worst) scaled
/// condition number of A (the upper median for an even count); NaN for a map with none.
struct Dexterity {
    double median = 0.0;
    double worst = 0.0;
};
[[nodiscard]] Dexterity dexterity(const WorkspaceMap& map);

/// The map at options.theta. The grid is fitted to the feasible region in two passes: a coarse
/// one over a box that holds every limb's reach, then `resolution` points per side over the
/// feasible region's bounding box, enlarged by a tenth. Throws nocdyn::Error for options out
/// of range or when no grid point of the coarse pass is feasible.
[[nodiscard]] WorkspaceMap workspaceMap(const Model& model, const WorkspaceOptions& options = {});

}  // namespace nocdyn
