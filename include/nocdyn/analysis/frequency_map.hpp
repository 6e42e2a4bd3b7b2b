// The first natural frequency of the platform over a workspace map: at every feasible grid point
// (theta, x, y) of a WorkspaceMap (workspace.hpp), the lowest frequency f_1 of the lumped model
// K v = w^2 M v (stiffness.hpp), and where over the map f_1 is lowest. Needs the compliance the
// robot file declares (StiffnessModel::any).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "nocdyn/analysis/workspace.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn {

struct FirstFrequencyMap {
    /// Per grid point, as WorkspaceMap::cells (row-major, point (i, k) at x0 + i step,
    /// y0 + k step): f_1 [Hz] at a feasible point, NaN elsewhere.
    std::vector<double> first;
    int points = 0;  ///< feasible points evaluated
    /// Points where the lumped model does not hold, so that f_1 there is the elastodynamic one.
    int elastodynamic_points = 0;
    /// Points where the elastodynamic model was solved to check the lumped one (elastic bodies,
    /// nearLimbSingularity): the only points that allocate.
    int elastodynamic_checks = 0;
    /// The lowest f_1 over the map [Hz], its grid point (the first in row-major order on a tie)
    /// and position [m]; the highest f_1 [Hz].
    double lowest = 0.0;
    int lowest_i = -1, lowest_k = -1;
    double lowest_x = 0.0, lowest_y = 0.0;
    double highest = 0.0;
    /// What the user must know of the map's numbers ("" when nothing): the largest stiffness
    /// contrast when it costs digits (contrastWarning), and with elastic bodies at how many
    /// points the lumped model does not hold, so that f_1 there is the elastodynamic model's
    /// (firstFrequency; lumpedMismatchWarning at the first such point), and whether it holds
    /// at the lowest point when no check reached it.
    std::string warning;
    [[nodiscard]] double at(int i, int k, int n) const {
        return first[static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + static_cast<std::size_t>(k)];
    }
};

/// f_1 at every feasible point of `map` (stiffnessAndModes at (map.theta, x, y)); one Data and
/// one stiffness workspace for the whole map, nothing allocated per point except, with elastic
/// bodies, where nearLimbSingularity: there the elastodynamic model checks the lumped one
/// (firstFrequency) and the lowest point is checked too. `progress(done, total)` is called
/// after each grid column (it may throw to stop). Throws nocdyn::Error when
/// the robot declares no compliance, when the map has no feasible point, or when a feasible
/// point fails (a rigid limb: the message names the limb and the point).
[[nodiscard]] FirstFrequencyMap firstFrequencyMap(const Model& model, const WorkspaceMap& map,
                                                  const std::function<void(int done, int total)>& progress = {});

/// The message for a robot without compliance: "robot 'NAME' declares no compliance (...): WHAT
/// needs a joint stiffness or an elastic body".
[[nodiscard]] std::string noComplianceMessage(const Model& model, const std::string& what);

}  // namespace nocdyn
