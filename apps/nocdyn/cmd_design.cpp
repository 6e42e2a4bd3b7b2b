// nocdyn design: a sweep over a family of robots (a parametric robot file with some of its
// parameters varied), every design's metrics (design.hpp) on every core, into DIR/designs.csv
// with the Pareto front (pareto.csv) and figures; a journal lets a stopped sweep resume.
#include <unistd.h>

#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <thread>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/analysis/design.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/tables/design.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/model.hpp"
#include "plot.hpp"
#include "progress.hpp"
#include "workspace_figure.hpp"

namespace nocdyn::cli {

namespace {

struct Options {
    std::string robot, out, sweep = "random", trajectory;
    std::vector<std::string> vary, metrics;
    std::size_t samples = 64;
    std::uint64_t seed = 1;
    int threads = 0;
    double theta = 0.0;
    bool theta_given = false;
    int resolution = 201;
    std::optional<double> duration;
    double rate = 10000.0;
    bool figures = true;
};

/// "NAME=LO:HI" as a range.
DesignRange parseRange(const std::string& text) {
    const auto equals = text.find('=');
    const auto colon = text.find(':', equals == std::string::npos ? 0 : equals);
    DesignRange r;
    if (equals != std::string::npos && colon != std::string::npos) {
        r.name = text.substr(0, equals);
        const io::Parameter lo =
            io::parseParameterAssignment(r.name + "=" + text.substr(equals + 1, colon - equals - 1));
        const io::Parameter hi = io::parseParameterAssignment(r.name + "=" + text.substr(colon + 1));
        r.lower = lo.value;
        r.upper = hi.value;
        if (r.lower <= r.upper) return r;
    }
    throw CLI::ValidationError("--vary", "'" + io::terminalText(text) + "': expected NAME=LOWER:UPPER, LOWER <= UPPER");
}

/// One line on a terminal, rewritten at most once a second.
class DesignProgress {
public:
    explicit DesignProgress(std::size_t total) : total_(total), terminal_(::isatty(STDERR_FILENO) == 1) {}
    ~DesignProgress() { finish(); }
    DesignProgress(const DesignProgress&) = delete;
    DesignProgress& operator=(const DesignProgress&) = delete;
    void update(std::size_t done, std::size_t feasible) {
        if (!terminal_) return;
        const auto now = std::chrono::steady_clock::now();
        if (shown_ && now - last_ < std::chrono::seconds(1)) return;
        last_ = now;
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        const double fraction = static_cast<double>(done) / static_cast<double>(total_);
        const double left =
            done > first_ ? elapsed * static_cast<double>(total_ - done) / static_cast<double>(done - first_) : 0.0;
        std::fprintf(stderr, "\rnocdyn design: %zu of %zu designs (%.0f %%), %zu feasible, about %.0f s left   ", done,
                     total_, 100.0 * fraction, feasible, left);
        std::fflush(stderr);
        shown_ = true;
    }
    void start(std::size_t already) { first_ = already; }
    void finish() {
        if (!shown_) return;
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
        shown_ = false;
    }

private:
    std::size_t total_, first_ = 0;
    bool terminal_, shown_ = false;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
};

/// The shortest decimal that reads back as exactly `value`: two options that differ in any bit
/// differ here (std::to_string keeps six decimals and would take 0.1 and 0.1000001 as one).
std::string exact(double value) {
    char buffer[64];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
    return {buffer, end};
}

/// What a journal is kept for: the content of every input file (the robot file, a trajectory
/// file) and every option that changes a design's numbers, each exactly. Any difference makes
/// the journal another sweep's, which is refused rather than reused.
std::string signature(const Options& options, const io::DesignFamily& family, const std::vector<DesignMetric>& metrics,
                      const DesignOptions& design) {
    std::string s = "robot " + io::fingerprint(family.text);
    for (const io::Parameter& p : family.fixed) s += " set " + p.name + "=" + exact(p.value);
    for (const DesignRange& r : family.ranges) s += " vary " + r.name + "=" + exact(r.lower) + ":" + exact(r.upper);
    s += " " + options.sweep + " " + std::to_string(options.samples) + " seed " + std::to_string(options.seed);
    for (const DesignMetric& m : metrics) s += " " + m.name();
    s += " ws " + std::to_string(design.workspace.resolution) +
         (options.theta_given ? "@" + exact(options.theta) : std::string());
    if (design.trajectory) {
        // a file by its content (an edited file is another sweep), a built-in one by its name
        std::error_code ec;
        std::string content = "builtin";
        if (std::filesystem::is_regular_file(options.trajectory, ec)) {
            std::ifstream in(options.trajectory, std::ios::binary);
            std::ostringstream text;
            text << in.rdbuf();
            content = io::fingerprint(text.str());
        }
        s += " trajectory " + io::fingerprint(options.trajectory) + " " + content + " " + exact(design.duration) + " " +
             exact(design.rate);
    }
    return io::fingerprint(s);
}

void writeFigures(const Options& options, const io::DesignFamily& family, const std::vector<DesignMetric>& metrics,
                  const DesignOptions& design, const std::vector<io::DesignRecord>& records,
                  const std::vector<std::size_t>& front) {
    const std::filesystem::path dir(options.out);
    if (metrics.size() >= 2) {
        PlotSeries all{"feasible designs", {}, {}, "points pt 7 ps 0.5 lc rgb '#999999'"};
        PlotSeries best{"Pareto front (over every metric)", {}, {}, "points pt 7 ps 0.9 lc rgb '#c0392b'"};
        for (const io::DesignRecord& r : records) {
            if (!r.evaluation.feasible) continue;
            all.x.push_back(r.evaluation.values[0]);
            all.y.push_back(r.evaluation.values[1]);
        }
        std::vector<std::size_t> sorted = front;
        std::sort(sorted.begin(), sorted.end(), [&](std::size_t a, std::size_t b) {
            return records[a].evaluation.values[0] < records[b].evaluation.values[0];
        });
        for (const std::size_t i : sorted) {
            best.x.push_back(records[i].evaluation.values[0]);
            best.y.push_back(records[i].evaluation.values[1]);
        }
        Figure f;
        f.title = "Designs of " + literalText(family.source);
        f.panels = {PlotPanel{"Pareto front (the first two metrics)",
                              literalText(metrics[0].name() + " [" + metrics[0].unit() + "]"),
                              literalText(metrics[1].name() + " [" + metrics[1].unit() + "]"),
                              {all, best}}};
        renderFigure(f, (dir / "pareto").string());
    }
    // the best design by the first metric, drawn with its workspace
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < records.size(); ++i) {
        if (!records[i].evaluation.feasible) continue;
        const double v = records[i].evaluation.values[0], b = best ? records[*best].evaluation.values[0] : 0.0;
        if (!best || (metrics[0].larger_is_better() ? v > b : v < b)) best = i;
    }
    if (!best) return;
    const Model model(io::designRobot(family, records[*best].point));
    WorkspaceOptions ws = design.workspace;
    ws.curves = true;
    if (design.workspace_theta_at_home) ws.theta = model.home(0);
    Figure f = workspaceFigure(workspaceMap(model, ws), model, {});
    f.title =
        "Best design by " + literalText(metrics[0].name()) + " (design " + std::to_string(records[*best].index) + ")";
    renderFigure(f, (dir / "best").string());
}

void run(const Options& options) {
    if (options.robot.empty()) throw CLI::ValidationError("--robot", "a parametric robot file is required");
    io::DesignFamily family;
    family.text = io::readRobotFileText(options.robot);
    family.source = options.robot;
    family.fixed = parameterOverrides();
    for (const std::string& v : options.vary) family.ranges.push_back(parseRange(v));
    for (std::size_t a = 0; a < family.ranges.size(); ++a) {
        for (std::size_t b = 0; b < a; ++b) {
            if (family.ranges[a].name == family.ranges[b].name)
                throw CLI::ValidationError("--vary", "'" + family.ranges[a].name + "' is varied twice");
        }
        for (const io::Parameter& p : family.fixed) {
            if (p.name == family.ranges[a].name)
                throw CLI::ValidationError("--vary", "'" + p.name + "' is both varied and fixed by --set");
        }
    }
    io::checkDesignFamily(family);
    std::vector<DesignMetric> metrics;
    for (const std::string& m : options.metrics) {
        try {
            metrics.push_back(parseDesignMetric(m));
        } catch (const Error& e) {
            throw CLI::ValidationError("--metric", io::terminalText(e.what()));
        }
    }
    DesignOptions design;
    design.workspace.resolution = options.resolution;
    design.workspace_theta_at_home = !options.theta_given;
    design.workspace.theta = options.theta;
    const bool needs_trajectory =
        std::any_of(metrics.begin(), metrics.end(), [](const DesignMetric& m) { return m.along_trajectory(); });
    if (needs_trajectory) {
        if (options.trajectory.empty())
            throw CLI::ValidationError("--trajectory",
                                       "is required by peak_force, rms_force, stroke and peak_reaction");
        design.trajectory = io::trajectoryByNameOrFile(options.trajectory);
        design.duration = chooseDuration(options.duration, *design.trajectory);
        design.rate = options.rate;
        requireRateAboveNyquist(*design.trajectory, design.rate);
    }
    const auto points = sweepPoints(family.ranges, options.sweep == "grid" ? SweepKind::grid : SweepKind::random,
                                    options.samples, options.seed);

    std::filesystem::create_directories(options.out);
    const std::filesystem::path dir(options.out);
    const std::vector<std::string> columns = io::designColumns(family.ranges, metrics);
    io::DesignJournal journal((dir / "journal.csv").string(), signature(options, family, metrics, design), columns,
                              family.ranges.size(), metrics.size());
    std::vector<std::optional<io::DesignRecord>> done(points.size());
    std::size_t feasible = 0, count = 0;
    for (const io::DesignRecord& r : journal.previous()) {
        if (r.index < done.size() && !done[r.index]) {
            done[r.index] = r;
            ++count;
            feasible += r.evaluation.feasible ? 1 : 0;
        }
    }
    std::vector<std::size_t> todo;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!done[i]) todo.push_back(i);
    }
    if (count > 0)
        std::fprintf(stderr, "nocdyn design: resuming: %zu of %zu designs already evaluated\n", count, points.size());
    const int threads =
        options.threads > 0 ? options.threads : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
    DesignProgress progress(points.size());
    progress.start(count);
    (void)evaluateInParallel(
        todo.size(), threads,
        [&](std::size_t k) { return io::evaluateFamilyDesign(family, points[todo[k]], metrics, design); },
        [&](std::size_t k, const DesignEvaluation& e) {
            io::DesignRecord r{todo[k], points[todo[k]], e};
            journal.append(r);
            feasible += e.feasible ? 1 : 0;
            done[todo[k]] = std::move(r);
            progress.update(++count, feasible);
        });
    progress.finish();

    std::vector<io::DesignRecord> records;
    std::vector<DesignEvaluation> evaluations;
    for (auto& r : done) {
        records.push_back(*r);
        evaluations.push_back(r->evaluation);
    }
    io::writeDesignTable((dir / "designs.csv").string(), columns, records);
    Steps front_progress("nocdyn design", 1);
    front_progress.next("Pareto front");
    const std::vector<std::size_t> front = paretoFront(evaluations, metrics, [&](std::size_t done, std::size_t total) {
        front_progress.count(static_cast<int>(done), static_cast<int>(total), "design");
    });
    front_progress.finish();
    std::vector<io::DesignRecord> front_records;
    for (const std::size_t i : front) front_records.push_back(records[i]);
    io::writeDesignTable((dir / "pareto.csv").string(), columns, front_records);
    if (options.figures) writeFigures(options, family, metrics, design, records, front);
    std::printf("%zu designs, %zu feasible, %zu on the Pareto front: %s\n", records.size(), feasible, front.size(),
                io::terminalText((dir / "designs.csv").string()).c_str());
}

}  // namespace

void addDesignCommand(CLI::App& app) {
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "design",
        "Sweep a family of robot designs on every core: metrics, Pareto front, figures. The family is a\n"
        "parametric robot file (parameters: NAME: VALUE, numbers as expressions of them) with the parameters\n"
        "given by --vary varied over their ranges, grid or random (seeded); each design's metrics are computed\n"
        "as the single-robot commands compute them:\n"
        "  workspace_area [m^2], condition_median, condition_worst [-] (nocdyn workspace, --theta,\n"
        "  --resolution), envelope_x@F, envelope_y@F [m], envelope_theta@F [rad] (nocdyn envelope at F Hz),\n"
        "  moving_mass [kg], and along --trajectory (limits enforced): peak_force, rms_force [N or N m],\n"
        "  stroke [m or rad], peak_reaction [N].\n"
        "Writes DIR/designs.csv (design, the varied parameters, the metrics, feasible, reason: a design that\n"
        "does not assemble, is singular or meets a limit is a row with the reason), DIR/pareto.csv (the\n"
        "feasible designs no other beats in every metric; workspace and envelope larger, others smaller is\n"
        "better), DIR/pareto.png/.svg (the first two metrics) and DIR/best.png/.svg (the best design by the\n"
        "first metric with its workspace). DIR/journal.csv holds every design as it is evaluated: run the\n"
        "same command again to resume a stopped sweep. Sobol and Latin-hypercube sweeps, optimisation and\n"
        "Dask clusters: the Python package (nocdyn.designs).\n"
        "Example: nocdyn design --robot examples/design_3rrr/family.yaml --vary r_b=0.15:0.25\n"
        "           --vary l=0.09:0.13 --samples 64 --metric workspace_area --metric envelope_x@50 --out-dir runs/a");
    addRobotOption(*command, options->robot);
    command->add_option("--vary", options->vary, "NAME=LOWER:UPPER: a declared parameter and its range; repeatable")
        ->required();
    command->add_option("--metric", options->metrics, "A metric (see above); repeatable, the first ranks 'best'")
        ->required();
    auto* out_dir = command->add_option("--out-dir", options->out, "Output folder (created if missing; required)")
                        ->check(nonEmptyPath());
    auto* old_out = command->add_option("--out", options->out)->group("")->check(nonEmptyPath());  // the old spelling

    command->add_option("--sweep", options->sweep, "grid or random")
        ->check(CLI::IsMember({"grid", "random"}))
        ->capture_default_str();
    command->add_option("--samples", options->samples, "Designs (grid: round(N^(1/d)) values per parameter)")
        ->check(CLI::Range(std::size_t{1}, kMaxDesigns))
        ->capture_default_str();
    command->add_option("--seed", options->seed, "Seed of the random sweep")->capture_default_str();
    command->add_option("--threads", options->threads, "Threads [default: every core]")->check(CLI::Range(1, 256));
    command->add_option("--theta", options->theta, "Workspace orientation [rad] [default: each design's home]")
        ->check(finiteIn(-1e3, 1e3, "rad"))
        ->each([options](const std::string&) { options->theta_given = true; });
    command->add_option("--resolution", options->resolution, "Workspace grid points per side")
        ->check(CLI::Range(11, 2001))
        ->capture_default_str();
    command->add_option("--trajectory", options->trajectory, "Trajectory of the force metrics (as inverse-dynamics)");
    command->add_option("--duration", options->duration, "Seconds of the trajectory [default: its own, else 0.2]")
        ->check(finiteIn(kMinDuration, kMaxDuration, "s"));
    command->add_option("--rate", options->rate, "Samples per second of the trajectory")
        ->check(finiteIn(kMinRate, kMaxRate, "Hz"))
        ->capture_default_str();
    command->add_flag("!--no-figures", options->figures, "Write no figures");
    command->callback([options, out_dir, old_out] {
        if (out_dir->count() + old_out->count() == 0) throw CLI::RequiredError("--out-dir");
        run(*options);
    });
}

}  // namespace nocdyn::cli
