// The workspace figure: the feasible region's outline (grid edges where feasibility changes)
// and the singularity curves as dots, so that the SVG stays small at any resolution.
#include "render/workspace_figure.hpp"

#include <cstdio>
#include <numbers>
#include "nocdyn/text.hpp"

namespace nocdyn::render {

Figure workspaceFigure(const WorkspaceMap& map, const Model& model, const std::vector<PlotSeries>& paths) {
    PlotSeries outline{"feasible region (outline)", {}, {}, "points pt 7 ps 0.25 lc rgb '#1f77b4'"};
    for (int i = 0; i < map.n; ++i) {
        for (int k = 0; k < map.n; ++k) {
            const bool in = map.cell(i, k) == WorkspaceCell::feasible;
            const bool right = i + 1 < map.n && (map.cell(i + 1, k) == WorkspaceCell::feasible) != in;
            const bool up = k + 1 < map.n && (map.cell(i, k + 1) == WorkspaceCell::feasible) != in;
            if (right) {
                outline.x.push_back((map.x0 + (i + 0.5) * map.step) * 1e3);
                outline.y.push_back((map.y0 + k * map.step) * 1e3);
            }
            if (up) {
                outline.x.push_back((map.x0 + i * map.step) * 1e3);
                outline.y.push_back((map.y0 + (k + 0.5) * map.step) * 1e3);
            }
        }
    }
    PlotSeries limb{"limb singularity (type 1: edge of a limb's reach)", {}, {}, "points pt 7 ps 0.3 lc rgb '#d62728'"};
    for (const Vector2& c : map.limb_singular) {
        limb.x.push_back(c.x() * 1e3);
        limb.y.push_back(c.y() * 1e3);
    }
    PlotSeries actuation{"actuation singularity (type 2)", {}, {}, "points pt 7 ps 0.3 lc rgb '#ff7f0e'"};
    for (const Vector2& c : map.actuation_singular) {
        actuation.x.push_back(c.x() * 1e3);
        actuation.y.push_back(c.y() * 1e3);
    }
    PlotSeries home{
        "home position of C", {model.home(1) * 1e3}, {model.home(2) * 1e3}, "points pt 2 ps 2 lc rgb 'black'"};
    std::string theta;
    theta = text::format("%.4g deg", map.theta * 180.0 / std::numbers::pi);
    const std::string where = map.task_dimension == 2 ? std::string("tool point C") : "C at theta = " + theta;
    PlotPanel panel{where + " (grid " + std::to_string(map.n) + " x " + std::to_string(map.n) + ")",
                    "x [mm]",
                    "y [mm]",
                    {},
                    false,
                    false};
    panel.equal_axes = true;
    for (PlotSeries* s : {&outline, &limb, &actuation, &home}) {
        if (!s->x.empty()) panel.series.push_back(std::move(*s));  // gnuplot refuses an empty block
    }
    for (PlotSeries s : paths) {
        for (double& v : s.x) v *= 1e3;
        for (double& v : s.y) v *= 1e3;
        if (!s.x.empty()) panel.series.push_back(std::move(s));
    }
    Figure figure;
    figure.title = "Workspace of " + literalText(model.description.name);
    figure.panels = {panel};
    figure.width = 820;
    figure.height = 900;
    return figure;
}

Figure firstFrequencyFigure(const WorkspaceMap& map, const FirstFrequencyMap& frequency, const Model& model) {
    // one pixel per grid point ("with image" needs the whole grid; NaN is drawn blank)
    PlotSeries heat{"first natural frequency f_1 [Hz] (colour; blank: not feasible)", {}, {}, "image", {{}}};
    const auto cells = static_cast<std::size_t>(map.n) * static_cast<std::size_t>(map.n);
    heat.x.reserve(cells);
    heat.y.reserve(cells);
    heat.extra[0].reserve(cells);
    for (int i = 0; i < map.n; ++i) {
        for (int k = 0; k < map.n; ++k) {
            heat.x.push_back((map.x0 + i * map.step) * 1e3);
            heat.y.push_back((map.y0 + k * map.step) * 1e3);
            heat.extra[0].push_back(frequency.at(i, k, map.n));
        }
    }
    std::string lowest_label;
    lowest_label = text::format("lowest f_1: %.4g Hz", frequency.lowest);
    PlotSeries lowest{lowest_label,
                      {frequency.lowest_x * 1e3},
                      {frequency.lowest_y * 1e3},
                      "points pt 6 ps 2.5 lw 2 lc rgb '#00a0ff'"};
    PlotSeries home{
        "home position of C", {model.home(1) * 1e3}, {model.home(2) * 1e3}, "points pt 2 ps 2 lc rgb 'black'"};
    std::string theta;
    theta = text::format("%.4g deg", map.theta * 180.0 / std::numbers::pi);
    PlotPanel panel{"First natural frequency f_1 [Hz] of the lumped model, C at theta = " + std::string(theta) +
                        " (grid " + std::to_string(map.n) + " x " + std::to_string(map.n) + ")",
                    "x [mm]",
                    "y [mm]",
                    {},
                    false,
                    false};
    panel.equal_axes = true;
    panel.series = {std::move(heat), std::move(lowest), std::move(home)};
    Figure figure;
    figure.title = "First natural frequency over the workspace of " + literalText(model.description.name);
    figure.panels = {panel};
    figure.width = 900;
    figure.height = 900;
    return figure;
}

std::string firstFrequencySummary(const FirstFrequencyMap& frequency) {
    // where the lumped model does not hold, f_1 is the elastodynamic model's (firstFrequency)
    const std::string models =
        frequency.elastodynamic_points > 0
            ? text::format("lumped model; elastodynamic at %d point%s, where the lumped one does not hold",
                           frequency.elastodynamic_points, frequency.elastodynamic_points == 1 ? "" : "s")
            : std::string("lumped model");
    std::string text;
    text = text::format(
        "First natural frequency (%s) over its %d feasible points: lowest %.6g Hz at (x, y) = "
        "(%.6g, %.6g) mm, highest %.6g Hz.",
        models.c_str(), frequency.points, frequency.lowest, frequency.lowest_x * 1e3, frequency.lowest_y * 1e3,
        frequency.highest);
    return text;
}

std::string workspaceSummary(const WorkspaceMap& map) {
    std::string text;
    const Dexterity d = dexterity(map);
    // a two-DOF robot has no orientation: the region of its tool point
    const std::string at = map.task_dimension == 2
                               ? std::string("The feasible region of the tool point C")
                               : text::format("At theta = %.6g rad the feasible region of C", map.theta);
    text = text::format(
        "%s (reachable on the home branches, within every "
        "joint range, regular) has an area of %.6g mm^2 (%d x %d grid, step %.4g mm, over x in "
        "[%.4g, %.4g] mm and y in [%.4g, %.4g] mm); %zu points on limb-singularity curves and %zu on "
        "actuation-singularity curves. Scaled condition number of A over it: median %.6g, worst %.6g.",
        at.c_str(), map.area * 1e6, map.n, map.n, map.step * 1e3, map.x0 * 1e3, (map.x0 + (map.n - 1) * map.step) * 1e3,
        map.y0 * 1e3, (map.y0 + (map.n - 1) * map.step) * 1e3, map.limb_singular.size(), map.actuation_singular.size(),
        d.median, d.worst);
    return text;
}

}  // namespace nocdyn::render
