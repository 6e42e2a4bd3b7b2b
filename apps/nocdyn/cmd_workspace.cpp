// nocdyn workspace: the feasible region of C at one orientation with both kinds of
// singularity curves (workspace.hpp), as a figure, a summary line and optionally CSV.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/analysis/workspace.hpp"
#include "progress.hpp"
#include "workspace_figure.hpp"

namespace nocdyn::cli {

namespace {

struct Options {
    std::string robot, output, figure;  ///< no figure unless asked for
    double theta = 0.0;
    bool theta_given = false;
    int resolution = 201;
    bool quiet = false, json = false;
};

/// The summary for a script: the grid, the feasible area and the singularity points (SI units).
nlohmann::json summaryJson(const WorkspaceMap& map, const Model& model) {
    nlohmann::json out;
    out["robot"] = model.description.name;
    out["theta"] = map.theta;
    out["area"] = map.area;
    out["resolution"] = map.n;
    out["step"] = map.step;
    out["x_range"] = {map.x0, map.x0 + (map.n - 1) * map.step};
    out["y_range"] = {map.y0, map.y0 + (map.n - 1) * map.step};
    out["limb_singular_points"] = map.limb_singular.size();
    out["actuation_singular_points"] = map.actuation_singular.size();
    return out;
}

void run(const Options& options) {
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    WorkspaceOptions ws;
    ws.theta = options.theta_given ? options.theta : model.home(0);
    ws.resolution = options.resolution;
    Steps steps("nocdyn workspace", 1, options.quiet);
    ws.progress = [&steps](int done, int total) { steps.count(done, total, "grid column"); };
    const WorkspaceMap map = workspaceMap(model, ws);
    steps.finish();
    if (!options.output.empty()) {
        io::Table table;
        table.columns = io::columnNames(io::TableId::workspace);
        table.categories = {{}, {}, {"feasible", "unreachable", "range", "singular"}};  // WorkspaceCell in order
        for (int i = 0; i < map.n; ++i) {
            for (int k = 0; k < map.n; ++k) {
                table.rows.push_back(
                    {map.x0 + i * map.step, map.y0 + k * map.step, static_cast<double>(map.cell(i, k))});
            }
        }
        writeTable(table, options.output);
    }
    if (!options.figure.empty()) renderFigure(workspaceFigure(map, model, {}), options.figure);
    if (options.json) {
        std::cout << summaryJson(map, model).dump(2) << "\n";
    } else if (!options.quiet) {
        std::printf("%s\n", workspaceSummary(map).c_str());
    }
}

}  // namespace

void addWorkspaceCommand(CLI::App& app) {
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "workspace",
        "Workspace of any robot at one platform orientation: the region of C reachable with every limb on its\n"
        "home branch, within every joint's range and away from singularities (condition numbers within the\n"
        "robot's max_condition), with the limb singularities (type 1: a limb at the edge of its reach) and the\n"
        "actuation singularities (type 2: det A = 0) drawn as curves (--figure STEM: STEM.png, STEM.svg), and its "
        "area.\n"
        "The grid is fitted to the feasible region. CSV: x, y [m] and cell (feasible, unreachable: out of\n"
        "reach, range: a joint out of its range, singular).\n"
        "Example: nocdyn workspace --robot robots/3-rrr.yaml --theta 0.1");
    addRobotOption(*command, options->robot);
    command->add_option("--theta", options->theta, "Platform orientation [rad] [default: the robot's home]")
        ->check(finiteIn(-1e3, 1e3, "rad"))
        ->each([options](const std::string&) { options->theta_given = true; });
    command->add_option("--resolution", options->resolution, "Grid points per side")
        ->check(CLI::Range(11, 2001))
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV of the grid [default: none]")->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Figure stem (STEM.png, STEM.svg) [default: none]");
    command->add_flag("--quiet,-q", options->quiet,
                      "Print nothing (no summary, no progress line); errors still go to stderr");
    command
        ->add_flag(
            "--json", options->json,
            "Print the summary as JSON instead (robot, theta [rad], area [m^2], resolution, step [m], x_range and\n"
            "y_range [m], limb_singular_points, actuation_singular_points)")
        ->excludes("--quiet");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
