// First natural frequency over a workspace map (frequency_map.hpp): per feasible grid point the
// position, velocity and shaping stages, K and the lumped modes (stiffnessAndModes), in one
// Data reused from point to point.
#include "nocdyn/analysis/frequency_map.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/printable.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

std::string noComplianceMessage(const Model& model, const std::string& what) {
    const std::string& source = model.description.source;
    return "robot '" + text::printable(model.description.name) + "'" +
           (source.empty() ? "" : " (" + text::printable(source) + ")") +
           " declares no compliance (no joint stiffness, no elastic body): " + what +
           " needs a joint 'stiffness' or a body's 'elastic' (see robots/paper-3prr-compliant.yaml)";
}

FirstFrequencyMap firstFrequencyMap(const Model& model, const WorkspaceMap& map,
                                    const std::function<void(int done, int total)>& progress) {
    const StiffnessModel compliance(model);
    if (!compliance.any) throw Error(noComplianceMessage(model, "the first natural frequency"));
    const std::size_t n = static_cast<std::size_t>(map.n);
    if (map.n < 1 || map.cells.size() != n * n) throw Error("first natural frequency: the workspace map is empty");
    FirstFrequencyMap out;
    out.first.assign(map.cells.size(), std::numeric_limits<double>::quiet_NaN());
    out.lowest = std::numeric_limits<double>::infinity();
    out.highest = -std::numeric_limits<double>::infinity();
    Data data(model);
    StiffnessData stiffness, worst_contrast;
    LumpedModes modes;
    int substituted = 0;  // points where the lumped model does not hold
    std::string first_mismatch;
    for (int i = 0; i < map.n; ++i) {
        const double x = map.x0 + i * map.step;
        for (int k = 0; k < map.n; ++k) {
            if (map.cell(i, k) != WorkspaceCell::feasible) continue;
            const double y = map.y0 + k * map.step;
            // nocdyn::Pose is (theta, x, y)
            if (const Status s = stiffnessAndModes(model, compliance, data, Pose(map.theta, x, y), stiffness, modes);
                !s) {
                std::string where;
                where = text::format(" at (x, y, theta) = (%.6g m, %.6g m, %.6g rad)", x, y, map.theta);
                throw Error("first natural frequency: " + describe(s, model) + where);
            }
            worst_contrast = stiffness.contrast > worst_contrast.contrast ? stiffness : worst_contrast;
            // ascending; with elastic bodies, next to a limb singularity (the only place the
            // lumped model was seen to fail), the elastodynamic f_1 where the lumped one does not hold
            double f1 = modes.frequency(0);
            if (compliance.any_elastic && nearLimbSingularity(model, data)) {
                ++out.elastodynamic_checks;
                std::string mismatch;
                f1 = firstFrequency(model, compliance, data, modes, &mismatch);
                if (!mismatch.empty() && substituted++ == 0) {
                    first_mismatch = text::format("at (x, y) = (%.6g m, %.6g m): ", x, y) + mismatch;
                }
            }
            out.first[static_cast<std::size_t>(i) * n + static_cast<std::size_t>(k)] = f1;
            ++out.points;
            if (f1 < out.lowest) {
                out.lowest = f1;
                out.lowest_i = i;
                out.lowest_k = k;
                out.lowest_x = x;
                out.lowest_y = y;
            }
            if (f1 > out.highest) out.highest = f1;
        }
        if (progress) progress(i + 1, map.n);
    }
    if (out.points == 0) throw Error("first natural frequency: the workspace map has no feasible point");
    out.warning = contrastWarning(worst_contrast);
    out.elastodynamic_points = substituted;
    if (substituted > 0) {
        out.warning += (out.warning.empty() ? "" : "; ") +
                       text::format(
                           "the elastodynamic first frequency is used at %d of %d points, where the "
                           "lumped model does not hold; first ",
                           substituted, out.points) +
                       first_mismatch;
    }
    if (compliance.any_elastic) {
        // the lowest point, when no check reached it: where the lumped model would fail first
        // away from a limb singularity (soft, heavy links), said rather than replaced
        const Pose p(map.theta, out.lowest_x, out.lowest_y);
        if (stiffnessAndModes(model, compliance, data, p, stiffness, modes) && !nearLimbSingularity(model, data)) {
            if (ElastodynamicModes elastic; lumpedFailsAt(model, compliance, data, modes, elastic)) {
                out.warning +=
                    (out.warning.empty() ? "" : "; ") +
                    text::format("at the lowest point (x, y) = (%.6g m, %.6g m): ", out.lowest_x, out.lowest_y) +
                    lumpedMismatchWarning(modes, elastic, false);
            }
        }
    }
    return out;
}

}  // namespace nocdyn
