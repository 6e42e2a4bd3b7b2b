// nocdyn design: binds app::DesignOptions; the sweep (its thread pool) runs in the application
// layer, its journal, tables and figures go to --out-dir through app::DesignFolder
// (app/design_outputs.hpp); prints the one-line summary.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "app/design.hpp"
#include "app/design_outputs.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/analysis/design.hpp"
#include "nocdyn/io/escape.hpp"
#include "progress.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace design_command {

void run(const app::DesignOptions& options, const CLI::App* command) {
    TerminalObserver observer("nocdyn design");
    app::DesignFolder files(options.out_dir);
    const app::DesignResult result = [&] {
        try {
            return app::runDesign(options, observer, files);
        } catch (const app::OptionError& e) {
            // a bad --vary, --metric or missing --trajectory: a usage error, as CLI11's own
            std::string option = "--" + e.field();
            std::replace(option.begin(), option.end(), '_', '-');
            throw CLI::ValidationError(option, commandLineText(e.message(), command));
        }
    }();
    observer.finish();
    std::printf("%zu designs, %zu feasible, %zu on the Pareto front: %s\n", result.records.size(), result.feasible,
                result.front.size(),
                io::terminalText((std::filesystem::path(options.out_dir) / "designs.csv").string()).c_str());
    std::printf("best by %s\n", result.best ? io::terminalText(result.best_text).c_str()
                                            : "the first metric: none (no design is feasible)");
}

}  // namespace design_command

void addDesignCommand(CLI::App& app) {
    auto options = std::make_shared<app::DesignOptions>();
    CLI::App* command = app.add_subcommand(
        "design",
        "Sweep a family of robot designs on every core: metrics, Pareto front, figures. The family is a\n"
        "parametric robot file (parameters: NAME: VALUE, numbers as expressions of them) with the parameters\n"
        "given by --vary varied over their ranges, grid or random (seeded); each design's metrics are computed\n"
        "as the single-robot commands compute them:\n"
        "  workspace_area [m^2], condition_median, condition_worst [-], first_frequency_min [Hz] (the lowest\n"
        "  first natural frequency over it: robot files with compliance) (nocdyn workspace, --theta,\n"
        "  --resolution), envelope_x@F, envelope_y@F [m], envelope_theta@F [rad] (nocdyn envelope at F Hz),\n"
        "  moving_mass [kg], and along --trajectory (limits enforced): peak_force, rms_force [N or N m],\n"
        "  stroke [m or rad], peak_reaction [N].\n"
        "Writes DIR/designs.csv (design, the varied parameters, the metrics, feasible, reason: a design that\n"
        "does not assemble, is singular or meets a limit is a row with the reason), DIR/pareto.csv (the\n"
        "feasible designs no other beats in every metric; workspace, first frequency and envelope larger, others\n"
        "smaller is better), DIR/pareto.png/.svg (the first two metrics) and DIR/best.png/.svg (the best\n"
        "design by the first metric with its workspace). DIR/journal.csv holds every design as it is\n"
        "evaluated: run the same command again to resume a stopped sweep. Sobol and Latin-hypercube sweeps,\n"
        "optimisation and Dask clusters: the Python package (nocdyn.designs). A two-DOF family (motion:\n"
        "translation: five-bars, biglides) is swept over its tool point's x, y: --theta, envelope_theta@F and a\n"
        "trajectory that moves theta are refused.\n"
        "Example: nocdyn design --robot examples/design_3rrr/family.yaml --vary r_b=0.15:0.25\n"
        "           --vary l=0.09:0.13 --samples 64 --metric workspace_area --metric envelope_x@50 --out-dir runs/a");
    addRobotOption(*command, options->robot);
    command->add_option("--vary", options->vary, "NAME=LOWER:UPPER: a declared parameter and its range; repeatable")
        ->required();
    command->add_option("--metric", options->metric, "A metric (see above); repeatable, the first ranks 'best'")
        ->required();
    auto* out_dir = command->add_option("--out-dir", options->out_dir, "Output folder (created if missing; required)")
                        ->check(nonEmptyPath());
    auto* old_out = addOldSpelling(*command, "--out", out_dir, options->out_dir);

    addChoiceOption(*command, "--sweep", options->sweep, "grid or random");
    command->add_option("--samples", options->samples, "Designs (grid: round(N^(1/d)) values per parameter)")
        ->check(CLI::Range(std::size_t{1}, kMaxDesigns))
        ->capture_default_str();
    command->add_option("--seed", options->seed, "Seed of the random sweep")->capture_default_str();
    command->add_option("--threads", options->threads, "Threads [default: every core]")->check(CLI::Range(1, 256));
    command->add_option("--theta", options->theta, "Workspace orientation [rad] [default: each design's home]")
        ->check(within(app::kDesignThetaRange));
    command->add_option("--resolution", options->resolution, "Workspace grid points per side")
        ->check(CLI::Range(11, 2001))
        ->capture_default_str();
    command->add_option("--trajectory", options->trajectory, "Trajectory of the force metrics (as inverse-dynamics)");
    command->add_option("--duration", options->duration, "Seconds of the trajectory [default: its own, else 0.2]")
        ->check(within(app::kDurationRange));
    command->add_option("--rate", options->rate, "Samples per second of the trajectory")
        ->check(within(app::kRateRange))
        ->capture_default_str();
    command->add_flag("--no-figures", options->no_figures, "Write no figures");
    command->callback([options, out_dir, old_out, command] {
        if (out_dir->count() + old_out->count() == 0) throw CLI::RequiredError("--out-dir");
        if (options->robot.path.empty()) throw CLI::ValidationError("--robot", "a parametric robot file is required");
        design_command::run(*options, command);
    });
}

}  // namespace nocdyn::cli
