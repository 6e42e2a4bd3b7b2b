#include "app/design.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "app/outputs.hpp"
#include "nocdyn/analysis/design.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/parallel.hpp"
#include "nocdyn/text.hpp"
#include "render/plot.hpp"
#include "render/workspace_figure.hpp"

namespace nocdyn::app {

namespace {

/// Whether a robot declares any compliance: a joint's stiffness or an elastic body.
bool declaresCompliance(const RobotDescription& robot) {
    return std::any_of(robot.limbs.begin(), robot.limbs.end(), [](const LimbDescription& limb) {
        return std::any_of(limb.joints.begin(), limb.joints.end(),
                           [](const JointDescription& j) { return j.stiffness.has_value(); }) ||
               std::any_of(limb.bodies.begin(), limb.bodies.end(),
                           [](const BodyDescription& b) { return b.elastic.has_value(); });
    });
}

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
    throw OptionError("vary", "'" + io::terminalText(text) + "': expected NAME=LOWER:UPPER, LOWER <= UPPER");
}

/// The shortest decimal that reads back as exactly `value`: two options that differ in any bit
/// differ here (std::to_string keeps six decimals and would take 0.1 and 0.1000001 as one).

/// What a journal is kept for: the content of every input file (the robot file, a trajectory
/// file) and every option that changes a design's numbers, each exactly. Any difference makes
/// the journal another sweep's, which is refused rather than reused.
std::string signature(const DesignOptions& options, const tables::DesignFamily& family,
                      const std::vector<DesignMetric>& metrics, const nocdyn::DesignOptions& design) {
    std::string s = "robot " + tables::fingerprint(family.text);
    for (const io::Parameter& p : family.fixed) s += " set " + p.name + "=" + text::shortest(p.value);
    for (const DesignRange& r : family.ranges)
        s += " vary " + r.name + "=" + text::shortest(r.lower) + ":" + text::shortest(r.upper);
    s.append(" ").append(nameOf(options.sweep));
    s += " " + std::to_string(options.samples) + " seed " + std::to_string(options.seed);
    for (const DesignMetric& m : metrics) {
        s += ' ';
        s += m.name();
    }
    s += " ws " + std::to_string(design.workspace.resolution);
    if (options.theta) {
        s += '@';
        s += text::shortest(*options.theta);
    }
    if (design.trajectory) {
        // a file by its content (an edited file is another sweep), a built-in one by its name
        std::error_code ec;
        std::string content = "builtin";
        if (std::filesystem::is_regular_file(options.trajectory, ec)) {
            std::ifstream in(options.trajectory, std::ios::binary);
            std::ostringstream text;
            text << in.rdbuf();
            content = tables::fingerprint(text.str());
        }
        s += " trajectory " + tables::fingerprint(options.trajectory) + " " + content + " " +
             text::shortest(design.duration) + " " + text::shortest(design.rate);
    }
    return tables::fingerprint(s);
}

/// The best feasible design by the first metric (larger or smaller is better, as the metric says).
std::optional<std::size_t> bestDesign(const std::vector<tables::DesignRecord>& records,
                                      const std::vector<DesignMetric>& metrics) {
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < records.size(); ++i) {
        if (!records[i].evaluation.feasible) continue;
        const double v = records[i].evaluation.values[0], b = best ? records[*best].evaluation.values[0] : 0.0;
        if (!best || (metrics[0].larger_is_better() ? v > b : v < b)) best = i;
    }
    return best;
}

/// "metric: design 30 (a = 0.1, b = 0.2), metric = 5.3", designs numbered from 1.
std::string bestText(const tables::DesignFamily& family, const std::vector<DesignMetric>& metrics,
                     const tables::DesignRecord& record) {
    std::string text = metrics[0].name() + ": design " + std::to_string(record.index + 1) + " (";
    for (std::size_t p = 0; p < family.ranges.size() && p < record.point.size(); ++p) {
        text += (p == 0 ? "" : ", ") + family.ranges[p].name + " = " + text::format("%.6g", record.point[p]);
    }
    return text + "), " + metrics[0].name() + " = " + text::format("%.6g", record.evaluation.values[0]);
}

/// pareto (the first two metrics) and best (the best design with its workspace), handed to `files`.
void designFigureFiles(DesignSink& files, const tables::DesignFamily& family, const std::vector<DesignMetric>& metrics,
                       const nocdyn::DesignOptions& design, const std::vector<tables::DesignRecord>& records,
                       const std::vector<std::size_t>& front) {
    using render::literalText;
    // no feasible design: nothing to draw (gnuplot refuses an empty data block)
    if (std::none_of(records.begin(), records.end(),
                     [](const tables::DesignRecord& r) { return r.evaluation.feasible; })) {
        return;
    }
    if (metrics.size() >= 2) {
        render::PlotSeries all{"feasible designs", {}, {}, "points pt 7 ps 0.5 lc rgb '#999999'"};
        render::PlotSeries best{"Pareto front (over every metric)", {}, {}, "points pt 7 ps 0.9 lc rgb '#c0392b'"};
        for (const tables::DesignRecord& r : records) {
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
        render::Figure f;
        f.title = "Designs of " + literalText(family.source);
        f.panels = {render::PlotPanel{"Pareto front (the first two metrics)",
                                      literalText(metrics[0].name() + " [" + metrics[0].unit() + "]"),
                                      literalText(metrics[1].name() + " [" + metrics[1].unit() + "]"),
                                      {all, best}}};
        files.figure("pareto", f);
    }
    // the best design by the first metric, drawn with its workspace
    const std::optional<std::size_t> best = bestDesign(records, metrics);
    if (!best) return;
    const Model model(tables::designRobot(family, records[*best].point));
    nocdyn::WorkspaceOptions ws = design.workspace;
    ws.curves = true;
    if (design.workspace_theta_at_home) ws.theta = model.home(0);
    render::Figure f = render::workspaceFigure(workspaceMap(model, ws), model, {});
    f.title = "Best by " + literalText(bestText(family, metrics, records[*best]));
    files.figure("best", f);
}

/// What refers to theta has no meaning for a two-DOF family (motion: translation, pose [x, y]):
/// its workspace is the tool point's region in x, y and its envelope has no theta axis.
void refuseThetaOfTwoDof(const DesignOptions& options, const std::vector<DesignMetric>& metrics) {
    if (options.theta) {
        throw OptionError("theta",
                          "a two-DOF family (motion: translation, pose [x, y]) has no theta: its workspace is over "
                          "x, y; leave it out");
    }
    for (const DesignMetric& m : metrics) {
        if (m.kind == DesignMetricKind::envelope && m.axis == EnvelopeAxis::theta) {
            throw OptionError("metric", "'" + m.name() +
                                            "': a two-DOF family (motion: translation, pose [x, y]) has no theta: "
                                            "envelope_x@F or envelope_y@F");
        }
    }
}

/// A trajectory of a two-DOF family holds theta at home (0): x, y only.
void refuseThetaMotion(const PoseTrajectory& trajectory, const std::string& source) {
    bool sampled = false;  // a sampled theta of zeros holds it at home too
    if (trajectory.sampled && trajectory.sampled->theta) {
        for (const auto& piece : trajectory.sampled->theta->pieces) {
            sampled = sampled || std::any_of(piece.begin(), piece.end(), [](double c) { return c != 0.0; });
        }
    }
    if (trajectory.theta.offset != 0.0 || !trajectory.theta.harmonics.empty() || sampled) {
        throw OptionError("trajectory", "'" + io::terminalText(source) +
                                            "' moves theta, and a two-DOF family (motion: translation, pose "
                                            "[x, y]) has none: give a trajectory of x, y");
    }
}

/// A robot file inside the output folder would be overwritten by the tables it writes.
void refuseRobotInside(const std::string& robot, const std::string& out_dir) {
    std::error_code ec;
    const auto file = std::filesystem::weakly_canonical(robot, ec);
    const auto dir = std::filesystem::weakly_canonical(out_dir, ec);
    if (ec || dir.empty()) return;
    const auto [end, _] = std::mismatch(dir.begin(), dir.end(), file.begin(), file.end());
    if (end == dir.end()) {
        throw OptionError("robot", "'" + io::terminalText(robot) + "' is inside the output folder out_dir");
    }
}

}  // namespace

void validate(const DesignOptions& options) {
    if (options.robot.description) {
        throw OptionError("robot", "a parametric robot file is required (a robot built in code has no parameters)");
    }
    if (options.robot.path.empty()) throw OptionError("robot", "a parametric robot file is required");
    if (options.vary.empty()) throw OptionError("vary", "at least one NAME=LOWER:UPPER is required");
    if (options.metric.empty()) throw OptionError("metric", "at least one metric is required");
    if (options.samples < 1 || options.samples > kMaxDesigns) {
        throw OptionError("samples", std::to_string(options.samples) + " is outside [1, " +
                                         std::to_string(kMaxDesigns) + "] designs");
    }
    requireIn(options.threads, kDesignThreadsRange, "threads");
    if (options.theta) requireIn(*options.theta, kDesignThetaRange, "theta");
    requireIn(options.resolution, kDesignResolutionRange, "resolution");
    if (options.duration) requireIn(*options.duration, kDurationRange, "duration");
    requireIn(options.rate, kRateRange, "rate");
}

DesignResult runDesign(const DesignOptions& options, Observer& observer, DesignSink& files) {
    validate(options);
    tables::DesignFamily family;
    family.text = io::readRobotFileText(options.robot.path);
    family.source = options.robot.path;
    family.fixed = options.robot.set;
    for (const std::string& v : options.vary) family.ranges.push_back(parseRange(v));
    for (std::size_t a = 0; a < family.ranges.size(); ++a) {
        for (std::size_t b = 0; b < a; ++b) {
            if (family.ranges[a].name == family.ranges[b].name)
                throw OptionError("vary", "'" + family.ranges[a].name + "' is varied twice");
        }
        for (const io::Parameter& p : family.fixed) {
            if (p.name == family.ranges[a].name)
                throw OptionError("vary", "'" + p.name + "' is both varied and fixed by set");
        }
    }
    tables::checkDesignFamily(family);
    std::vector<DesignMetric> metrics;
    for (const std::string& m : options.metric) {
        try {
            metrics.push_back(parseDesignMetric(m));
        } catch (const Error& e) {
            throw OptionError("metric", io::terminalText(e.what()));
        }
    }
    for (std::size_t a = 0; a < metrics.size(); ++a) {
        for (std::size_t b = 0; b < a; ++b) {
            if (metrics[a].name() == metrics[b].name())
                throw OptionError("metric", "'" + io::terminalText(metrics[a].name()) + "' is asked twice");
        }
    }
    const auto points = sweepPoints(family.ranges, options.sweep, options.samples, options.seed);
    // What the whole family shares is checked on its first design (one that fails, the sweep
    // reports): whether it is two-DOF (motion: translation), whose metrics are over x, y, and
    // whether it declares compliance (a field present, not its value), without which
    // first_frequency_min is refused before the first design.
    std::optional<RobotDescription> first;
    if (!points.empty()) {
        try {
            first = tables::designRobot(family, points.front());
        } catch (const Error&) {  // NOLINT(bugprone-empty-catch): a design the sweep itself will report
        }
    }
    const bool two_dof = first && first->motion == PlatformMotion::translation;
    if (two_dof) refuseThetaOfTwoDof(options, metrics);
    if (std::any_of(metrics.begin(), metrics.end(),
                    [](const DesignMetric& m) { return m.kind == DesignMetricKind::first_frequency_min; })) {
        if (first && !declaresCompliance(*first)) {
            throw OptionError("metric", "first_frequency_min: the family '" + io::terminalText(first->name) +
                                            "' declares no compliance (no joint 'stiffness', no body 'elastic'), so "
                                            "no design has a natural frequency");
        }
    }
    nocdyn::DesignOptions design;
    design.workspace.resolution = options.resolution;
    design.workspace_theta_at_home = !options.theta;
    design.workspace.theta = options.theta.value_or(0.0);
    if (std::any_of(metrics.begin(), metrics.end(), [](const DesignMetric& m) { return m.along_trajectory(); })) {
        if (options.trajectory.empty())
            throw OptionError("trajectory", "is required by peak_force, rms_force, stroke and peak_reaction");
        design.trajectory = io::trajectoryByNameOrFile(options.trajectory);
        if (two_dof) refuseThetaMotion(*design.trajectory, options.trajectory);
        design.duration = chooseDuration(options.duration, *design.trajectory);
        design.rate = options.rate;
        requireRateAboveNyquist(*design.trajectory, design.rate);
    }

    DesignResult out;
    for (const DesignRange& r : family.ranges) out.names.push_back(r.name);
    for (const DesignMetric& m : metrics) out.metrics.push_back(m.name());
    out.columns = tables::designColumns(family.ranges, metrics);
    const bool journal = !options.out_dir.empty();  // the files handed over (and a sweep resumed)
    std::vector<tables::DesignRecord> previous;
    if (journal) {
        refuseRobotInside(options.robot.path, options.out_dir);
        previous =
            files.open(signature(options, family, metrics, design), out.columns, family.ranges.size(), metrics.size());
    }
    std::vector<std::optional<tables::DesignRecord>> done(points.size());
    std::size_t count = 0;
    for (const tables::DesignRecord& r : previous) {
        if (r.index < done.size() && !done[r.index]) {
            done[r.index] = r;
            ++count;
            out.feasible += r.evaluation.feasible ? 1 : 0;
        }
    }
    out.resumed = count;
    std::vector<std::size_t> todo;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!done[i]) todo.push_back(i);
    }
    if (count > 0) {
        observer.warning("resuming: " + std::to_string(count) + " of " + std::to_string(points.size()) +
                         " designs already evaluated (" + io::terminalText(files.journal()) + ")");
    }
    const int threads = options.threads > 0 ? options.threads : static_cast<int>(hardwareThreads());
    const auto total = static_cast<double>(points.size());
    observer.progress(static_cast<double>(count), total, "designs");
    // the library's work queue; this thread records each design and polls the observer
    (void)evaluateInParallel(
        todo.size(), threads,
        [&](std::size_t k) { return tables::evaluateFamilyDesign(family, points[todo[k]], metrics, design); },
        [&](std::size_t k, DesignEvaluation&& e) {
            tables::DesignRecord r{todo[k], points[todo[k]], std::move(e)};
            if (journal) files.append(r);
            out.feasible += r.evaluation.feasible ? 1 : 0;
            done[todo[k]] = std::move(r);
            observer.progress(static_cast<double>(++count), total, "designs");
        },
        [&] {
            stopIfRequested(observer);
            return false;
        });

    std::vector<DesignEvaluation> evaluations;
    evaluations.reserve(done.size());
    out.records.reserve(done.size());
    for (auto& r : done) {
        if (!r) throw Error("design: a design was left unevaluated");  // every index not done was in todo
        out.records.push_back(std::move(*r));
        evaluations.push_back(out.records.back().evaluation);
    }
    if (journal) files.designs("designs.csv", out.columns, out.records);
    observer.step("Pareto front", 1, 1);
    out.front = paretoFront(evaluations, metrics, [&](std::size_t k, std::size_t n) {
        if ((k & 1023U) != 0 && k != n) return;  // the observer at a price that does not show
        observer.progress(static_cast<double>(k), static_cast<double>(n), "designs");
        stopIfRequested(observer);
    });
    out.best = bestDesign(out.records, metrics);
    if (out.best) out.best_text = bestText(family, metrics, out.records[*out.best]);
    if (journal) {
        std::vector<tables::DesignRecord> front_records;
        front_records.reserve(out.front.size());
        for (const std::size_t i : out.front) front_records.push_back(out.records[i]);
        files.designs("pareto.csv", out.columns, front_records);
        if (!options.no_figures) designFigureFiles(files, family, metrics, design, out.records, out.front);
    }
    return out;
}

}  // namespace nocdyn::app
