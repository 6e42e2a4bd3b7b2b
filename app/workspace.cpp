#include "app/workspace.hpp"

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/layouts.hpp"
#include "render/workspace_figure.hpp"

namespace nocdyn::app {

void validate(const WorkspaceOptions& options) {
    if (options.theta) requireIn(*options.theta, kWorkspaceThetaRange, "theta");
    requireIn(options.resolution, kWorkspaceResolutionRange, "resolution");
}

WorkspaceResult runWorkspace(const WorkspaceOptions& options, Observer& observer) {
    validate(options);
    WorkspaceResult out;
    // a two-DOF robot too: the region of its tool point, theta no coordinate of it
    out.model = std::make_shared<const Model>(loadRobot(options.robot));
    const Model& model = *out.model;
    if (model.task_dimension == 2) {
        if (options.theta && *options.theta != model.home(0))
            throw OptionError("theta", "a two-DOF robot (motion: translation) has no theta: leave it out");
        if (options.first_frequency) {
            throw Error(where(model.description, 0) +
                        "the first natural frequency map of a two-DOF robot (motion: translation) is not "
                        "available yet");
        }
    }
    nocdyn::WorkspaceOptions ws;
    ws.theta = options.theta ? *options.theta : model.home(0);
    ws.resolution = options.resolution;
    // called after each grid column, from this thread
    ws.progress = [&observer](int done, int total) {
        observer.progress(done, total, "grid columns");
        stopIfRequested(observer);
    };
    if (options.first_frequency && !StiffnessModel(model).any) {
        throw Error(noComplianceMessage(model, "the first natural frequency map"));
    }
    out.map = workspaceMap(model, ws);
    out.summary = render::workspaceSummary(out.map);
    const WorkspaceMap& map = out.map;
    if (options.first_frequency) {
        out.frequency = firstFrequencyMap(model, map, [&observer](int done, int total) {
            observer.progress(done, total, "grid columns (natural frequencies)");
            stopIfRequested(observer);
        });
        if (!out.frequency->warning.empty()) observer.warning("first natural frequency: " + out.frequency->warning);
        out.summary += ' ';
        out.summary += render::firstFrequencySummary(*out.frequency);
        out.frequency_table.columns = io::columnNames(io::TableId::first_frequency);
        for (int i = 0; i < map.n; ++i) {
            for (int k = 0; k < map.n; ++k) {
                if (map.cell(i, k) != WorkspaceCell::feasible) continue;
                out.frequency_table.rows.push_back(
                    {map.x0 + i * map.step, map.y0 + k * map.step, out.frequency->at(i, k, map.n)});
            }
        }
    }
    out.table.columns = io::columnNames(io::TableId::workspace);
    out.table.categories = {{}, {}, {"feasible", "unreachable", "range", "singular"}};  // WorkspaceCell in order
    for (int i = 0; i < map.n; ++i) {
        for (int k = 0; k < map.n; ++k) {
            out.table.rows.push_back(
                {map.x0 + i * map.step, map.y0 + k * map.step, static_cast<double>(map.cell(i, k))});
        }
    }
    return out;
}

render::Figure workspaceResultFigure(const WorkspaceResult& result) {
    return render::workspaceFigure(result.map, *result.model, {});
}

render::Figure frequencyResultFigure(const WorkspaceResult& result) {
    if (!result.frequency) throw Error("the figure of the first natural frequency needs first_frequency");
    return render::firstFrequencyFigure(result.map, *result.frequency, *result.model);
}

}  // namespace nocdyn::app
