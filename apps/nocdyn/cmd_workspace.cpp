// nocdyn workspace: binds app::WorkspaceOptions and renders the map as a summary line (or JSON),
// CSV and a figure.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "app/workspace.hpp"
#include "app/outputs.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace workspace_command {

struct Options : app::WorkspaceOptions {
    std::string output, figure;  ///< no figure unless asked for
    std::string frequency_map;   ///< STEM.csv, STEM.png, STEM.svg of the first natural frequency
    bool json = false;
};

/// The summary for a script: the grid, the feasible area and the singularity points (SI units).
nlohmann::json summaryJson(const app::WorkspaceResult& result) {
    const WorkspaceMap& map = result.map;
    nlohmann::json out;
    out["robot"] = result.model->description.name;
    if (map.task_dimension == 3) out["theta"] = map.theta;  // a two-DOF robot has none
    out["area"] = map.area;
    out["resolution"] = map.n;
    out["step"] = map.step;
    out["x_range"] = {map.x0, map.x0 + (map.n - 1) * map.step};
    out["y_range"] = {map.y0, map.y0 + (map.n - 1) * map.step};
    out["limb_singular_points"] = map.limb_singular.size();
    out["actuation_singular_points"] = map.actuation_singular.size();
    if (result.frequency) {
        const FirstFrequencyMap& f = *result.frequency;
        out["first_frequency"] = {{"points", f.points},
                                  {"lowest", f.lowest},
                                  {"lowest_at", {{"x", f.lowest_x}, {"y", f.lowest_y}, {"theta", map.theta}}},
                                  {"highest", f.highest}};
    }
    return out;
}

void run(Options options) {
    if (!options.frequency_map.empty()) options.first_frequency = true;
    TerminalObserver terminal("nocdyn workspace");
    const app::WorkspaceResult result = app::runWorkspace(options, quiet() ? app::silent() : terminal);
    terminal.finish();
    if (!options.output.empty()) writeTable(result.table, options.output);
    if (!options.figure.empty()) app::writeWorkspaceFigure(result, options.figure);
    if (!options.frequency_map.empty()) {
        writeTable(result.frequency_table, options.frequency_map + ".csv");
        app::writeFrequencyFigure(result, options.frequency_map);
    }
    if (options.json) {
        std::cout << summaryJson(result).dump(2) << "\n";
    } else if (!quiet()) {
        std::printf("%s\n", result.summary.c_str());
    }
}

}  // namespace workspace_command

void addWorkspaceCommand(CLI::App& app) {
    auto options = std::make_shared<workspace_command::Options>();
    CLI::App* command = app.add_subcommand(
        "workspace",
        "Workspace of any robot at one platform orientation: the region of C reachable with every limb on its\n"
        "home branch, within every joint's range and away from singularities (condition numbers within the\n"
        "robot's max_condition), with the limb singularities (type 1: a limb at the edge of its reach) and the\n"
        "actuation singularities (type 2: det A = 0) drawn as curves (--figure STEM: STEM.png, STEM.svg), and its "
        "area.\n"
        "The grid is fitted to the feasible region. CSV: x, y [m] and cell (feasible, unreachable: out of\n"
        "reach, range: a joint out of its range, singular).\n"
        "With --first-frequency (robot files that declare compliance: joint stiffness, elastic bodies) also the\n"
        "first natural frequency of the lumped model at every feasible point, its lowest and where;\n"
        "--frequency-map STEM writes it as STEM.csv (x, y [m], first_frequency [Hz]) and a heat map.\n"
        "A two-DOF robot (motion: translation): the region of its tool point, no --theta; the actuation\n"
        "singularity is det A_t = 0 (the five-bar's forearms aligned).\n"
        "Example: nocdyn workspace --robot robots/3-rrr.yaml --theta 0.1");
    addRobotOption(*command, options->robot);
    command->add_option("--theta", options->theta, "Platform orientation [rad] [default: the robot's home]")
        ->check(within(app::kWorkspaceThetaRange));
    command->add_option("--resolution", options->resolution, "Grid points per side")
        ->check(CLI::Range(11, 2001))
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV of the grid [default: none]")->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Figure stem (STEM.png, STEM.svg) [default: none]");
    command->add_flag("--first-frequency", options->first_frequency,
                      "Also the first natural frequency at every feasible point (needs compliance in the robot file)");
    command
        ->add_option("--frequency-map", options->frequency_map,
                     "Stem of the first natural frequency's CSV and heat map (STEM.csv, STEM.png, STEM.svg);\n"
                     "implies --first-frequency [default: none]")
        ->check(nonEmptyPath());
    command->add_flag(
        "--json", options->json,
        "Print the summary as JSON instead (robot, theta [rad] (not for a two-DOF robot), area [m^2], resolution, step "
        "[m], x_range and\n"
        "y_range [m], limb_singular_points, actuation_singular_points; with --first-frequency first_frequency:\n"
        "points, lowest [Hz], lowest_at {x, y [m], theta [rad]}, highest [Hz])");
    command->callback([options] { workspace_command::run(*options); });
}

}  // namespace nocdyn::cli
