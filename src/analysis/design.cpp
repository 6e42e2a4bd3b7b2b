// Metrics of one design and the sweep machinery (design.hpp): each metric by the same
// library call the single-robot command makes, failures of the design turned into reasons.
#include "nocdyn/analysis/design.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <limits>
#include <mutex>
#include <random>
#include <utility>

#include "nocdyn/analysis/frequency_map.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/parallel.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

namespace {

std::string frequencyText(double f) {
    std::string s = text::format("%f", f);  // "50.000000" -> "50", "12.500000" -> "12.5"
    s.erase(s.find_last_not_of('0') + 1);
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}

constexpr const char* kMetricNames =
    "workspace_area, condition_median, condition_worst, first_frequency_min, envelope_x@F, envelope_y@F, "
    "envelope_theta@F (F in Hz), "
    "moving_mass, peak_force, rms_force, stroke, peak_reaction";

/// Peaks over a trajectory, accumulated sample by sample.
struct TrajectoryPeaks {
    std::vector<double> u_min, u_max, sum_tau2;
    double peak_tau = 0.0, peak_reaction = 0.0;
    std::size_t samples = 0;
};

}  // namespace

std::string DesignMetric::name() const {
    switch (kind) {
        case DesignMetricKind::workspace_area:
            return "workspace_area";
        case DesignMetricKind::condition_median:
            return "condition_median";
        case DesignMetricKind::condition_worst:
            return "condition_worst";
        case DesignMetricKind::first_frequency_min:
            return "first_frequency_min";
        case DesignMetricKind::envelope:
            return std::string("envelope_") + axisName(axis) + "@" + frequencyText(frequency);
        case DesignMetricKind::moving_mass:
            return "moving_mass";
        case DesignMetricKind::peak_force:
            return "peak_force";
        case DesignMetricKind::rms_force:
            return "rms_force";
        case DesignMetricKind::stroke:
            return "stroke";
        case DesignMetricKind::peak_reaction:
            return "peak_reaction";
    }
    return "?";
}

std::string DesignMetric::unit() const {
    switch (kind) {
        case DesignMetricKind::workspace_area:
            return "m^2";
        case DesignMetricKind::condition_median:
        case DesignMetricKind::condition_worst:
            return "-";
        case DesignMetricKind::first_frequency_min:
            return "Hz";
        case DesignMetricKind::envelope:
            return axis == EnvelopeAxis::theta ? "rad" : "m";
        case DesignMetricKind::moving_mass:
            return "kg";
        case DesignMetricKind::peak_force:
        case DesignMetricKind::rms_force:
            return "N or N m";
        case DesignMetricKind::stroke:
            return "m or rad";
        case DesignMetricKind::peak_reaction:
            return "N";
    }
    return "?";
}

bool DesignMetric::larger_is_better() const {
    return kind == DesignMetricKind::workspace_area || kind == DesignMetricKind::first_frequency_min ||
           kind == DesignMetricKind::envelope;
}

bool DesignMetric::along_trajectory() const {
    return kind == DesignMetricKind::peak_force || kind == DesignMetricKind::rms_force ||
           kind == DesignMetricKind::stroke || kind == DesignMetricKind::peak_reaction;
}

DesignMetric parseDesignMetric(const std::string& text) {
    DesignMetric m;
    const std::pair<const char*, DesignMetricKind> plain[] = {
        {"workspace_area", DesignMetricKind::workspace_area},
        {"condition_median", DesignMetricKind::condition_median},
        {"condition_worst", DesignMetricKind::condition_worst},
        {"first_frequency_min", DesignMetricKind::first_frequency_min},
        {"moving_mass", DesignMetricKind::moving_mass},
        {"peak_force", DesignMetricKind::peak_force},
        {"rms_force", DesignMetricKind::rms_force},
        {"stroke", DesignMetricKind::stroke},
        {"peak_reaction", DesignMetricKind::peak_reaction}};
    for (const auto& [name, kind] : plain) {
        if (text == name) {
            m.kind = kind;
            return m;
        }
    }
    const std::string prefix = "envelope_";
    const auto at = text.find('@');
    if (text.rfind(prefix, 0) == 0 && at != std::string::npos) {
        const std::string axis = text.substr(prefix.size(), at - prefix.size());
        const std::string frequency = text.substr(at + 1);
        m.kind = DesignMetricKind::envelope;
        bool known_axis = true;
        if (axis == "x")
            m.axis = EnvelopeAxis::x;
        else if (axis == "y")
            m.axis = EnvelopeAxis::y;
        else if (axis == "theta")
            m.axis = EnvelopeAxis::theta;
        else
            known_axis = false;
        std::size_t used = 0;
        double f = 0.0;
        try {
            f = std::stod(frequency, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (known_axis && used == frequency.size() && !frequency.empty() && f >= kEnvelopeMinFrequency &&
            f <= kEnvelopeMaxFrequency) {
            m.frequency = f;
            return m;
        }
    }
    throw Error("unknown design metric '" + text + "' (expected one of: " + kMetricNames + "; F in [0.001, 10000])");
}

DesignEvaluation evaluateDesign(const RobotDescription& robot, const std::vector<DesignMetric>& metrics,
                                const DesignOptions& options) {
    const bool trajectory =
        std::any_of(metrics.begin(), metrics.end(), [](const DesignMetric& m) { return m.along_trajectory(); });
    if (trajectory && !options.trajectory) throw Error("design: a trajectory metric needs a trajectory");
    DesignEvaluation result;
    result.values.assign(metrics.size(), std::nan(""));
    // A reason for infeasibility is any error the model or a metric reports for this design.
    try {
        const Model model(robot);
        std::optional<WorkspaceMap> map;  // shared by the workspace metrics
        std::optional<Dexterity> dexterity_over_map;
        const auto workspace = [&]() -> const WorkspaceMap& {
            if (!map) {
                WorkspaceOptions ws = options.workspace;
                if (options.workspace_theta_at_home) ws.theta = model.home(0);
                map.emplace(workspaceMap(model, ws));
            }
            return *map;
        };
        std::optional<TrajectoryPeaks> peaks;
        for (std::size_t i = 0; i < metrics.size(); ++i) {
            const DesignMetric& m = metrics[i];
            double& value = result.values[i];
            switch (m.kind) {
                case DesignMetricKind::workspace_area:
                case DesignMetricKind::condition_median:
                case DesignMetricKind::condition_worst:
                    if (!dexterity_over_map) dexterity_over_map = dexterity(workspace());
                    value = m.kind == DesignMetricKind::workspace_area     ? workspace().area
                            : m.kind == DesignMetricKind::condition_median ? dexterity_over_map->median
                                                                           : dexterity_over_map->worst;
                    break;
                case DesignMetricKind::first_frequency_min:
                    // the same function as `nocdyn workspace --first-frequency`, over the same map
                    if (!StiffnessModel(model).any) {
                        throw Error(noComplianceMessage(model, "first_frequency_min"));
                    }
                    value = firstFrequencyMap(model, workspace()).lowest;
                    break;
                case DesignMetricKind::envelope:
                    if (model.task_dimension == 2 && m.axis == EnvelopeAxis::theta) {
                        throw Error(m.name() + ": a two-DOF robot (motion: translation, pose [x, y]) has no theta");
                    }
                    value = maximumAmplitude(model, m.axis, m.frequency, options.envelope).amplitude;
                    break;
                case DesignMetricKind::moving_mass: {
                    double mass = robot.platform.mass;
                    for (const LimbDescription& limb : robot.limbs) {
                        for (const BodyDescription& body : limb.bodies) mass += body.mass;
                    }
                    value = mass;
                    break;
                }
                case DesignMetricKind::peak_force:
                case DesignMetricKind::rms_force:
                case DesignMetricKind::stroke:
                case DesignMetricKind::peak_reaction: {
                    if (!options.trajectory) throw Error("design: a trajectory metric needs a trajectory");
                    if (!peaks) {
                        TrajectoryPeaks& p = peaks.emplace();
                        const auto n = static_cast<std::size_t>(model.actuators);
                        p.u_min.assign(n, INFINITY);
                        p.u_max.assign(n, -INFINITY);
                        p.sum_tau2.assign(n, 0.0);
                        (void)streamInverseDynamicsWithReactions(
                            model, *options.trajectory, sampleGrid(options.duration, options.rate), LimitPolicy::error,
                            [&](const InverseDynamicsSample& s, const Reactions& r) {
                                for (std::size_t a = 0; a < n; ++a) {
                                    const auto k = static_cast<Eigen::Index>(a);
                                    p.u_min[a] = std::min(p.u_min[a], s.u(k));
                                    p.u_max[a] = std::max(p.u_max[a], s.u(k));
                                    p.sum_tau2[a] += s.tau(k) * s.tau(k);
                                    p.peak_tau = std::max(p.peak_tau, std::abs(s.tau(k)));
                                }
                                for (int j = 0; j < model.limbs; ++j) {
                                    for (std::size_t k = 0; k < 3; ++k) {
                                        const Vector3& f = r.joint[static_cast<std::size_t>(j)][k];
                                        p.peak_reaction = std::max(p.peak_reaction, std::hypot(f(0), f(1)));
                                    }
                                }
                                ++p.samples;
                            });
                    }
                    const TrajectoryPeaks& p = peaks.value();
                    if (m.kind == DesignMetricKind::peak_force) {
                        value = p.peak_tau;
                    } else if (m.kind == DesignMetricKind::peak_reaction) {
                        value = p.peak_reaction;
                    } else if (m.kind == DesignMetricKind::rms_force) {
                        value = 0.0;
                        for (const double s2 : p.sum_tau2)
                            value = std::max(value, std::sqrt(s2 / static_cast<double>(p.samples)));
                    } else {
                        value = 0.0;
                        for (std::size_t a = 0; a < p.u_min.size(); ++a)
                            value = std::max(value, p.u_max[a] - p.u_min[a]);
                    }
                    break;
                }
            }
        }
    } catch (const Error& e) {
        result.feasible = false;
        result.reason = e.what();
        std::fill(result.values.begin(), result.values.end(), std::nan(""));
        return result;
    }
    result.feasible = true;
    return result;
}

std::vector<std::vector<double>> sweepPoints(const std::vector<DesignRange>& ranges, SweepKind kind,
                                             std::size_t samples, std::uint64_t seed) {
    if (ranges.empty()) throw Error("design: no parameter is varied");
    for (const DesignRange& r : ranges) {
        if (!std::isfinite(r.lower) || !std::isfinite(r.upper) || !(r.lower <= r.upper)) {
            throw Error("design: the range of '" + r.name + "' must be finite with lower <= upper");
        }
        // every point is lower + s (upper - lower): the width itself must be a finite number
        if (!std::isfinite(r.upper - r.lower)) {
            throw Error("design: the range of '" + r.name + "' is wider than a double holds (upper - lower overflows)");
        }
    }
    if (samples < 1 || samples > kMaxDesigns) {
        throw Error("design: " + std::to_string(samples) + " designs asked; at most " + std::to_string(kMaxDesigns) +
                    " are evaluated in one sweep");
    }
    const std::size_t d = ranges.size();
    std::vector<std::vector<double>> points;
    if (kind == SweepKind::random) {
        std::mt19937_64 engine(seed);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        points.resize(samples, std::vector<double>(d));
        for (auto& p : points) {
            for (std::size_t k = 0; k < d; ++k)
                p[k] = ranges[k].lower + unit(engine) * (ranges[k].upper - ranges[k].lower);
        }
        return points;
    }
    const auto n = std::max<std::size_t>(
        2,
        static_cast<std::size_t>(std::llround(std::pow(static_cast<double>(samples), 1.0 / static_cast<double>(d)))));
    double total = 1.0;
    for (std::size_t k = 0; k < d; ++k) total *= static_cast<double>(n);
    if (total > static_cast<double>(kMaxDesigns)) {
        throw Error("design: a grid of " + std::to_string(n) + " values per parameter holds more than " +
                    std::to_string(kMaxDesigns) + " designs");
    }
    const auto count = static_cast<std::size_t>(total);
    points.resize(count, std::vector<double>(d));
    for (std::size_t i = 0; i < count; ++i) {
        std::size_t rest = i;
        for (std::size_t k = d; k-- > 0;) {
            const std::size_t step = rest % n;
            rest /= n;
            const double s = static_cast<double>(step) / static_cast<double>(n - 1);
            points[i][k] = step + 1 == n ? ranges[k].upper : ranges[k].lower + s * (ranges[k].upper - ranges[k].lower);
        }
    }
    return points;
}

std::size_t evaluateInParallel(std::size_t count, int threads,
                               const std::function<DesignEvaluation(std::size_t)>& evaluate,
                               const std::function<void(std::size_t, DesignEvaluation&&)>& record,
                               const std::function<bool()>& stop) {
    std::mutex mutex;
    std::condition_variable ready_cv;
    std::deque<std::pair<std::size_t, DesignEvaluation>> ready;  // evaluated, not yet recorded
    std::exception_ptr failure;
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stopping{false};
    const unsigned evaluators = static_cast<unsigned>(std::clamp(threads, 1, 256));
    unsigned running = evaluators;
    std::size_t recorded = 0;
    const auto evaluator = [&] {
        while (!stopping.load()) {
            const std::size_t i = next.fetch_add(1);
            if (i >= count) break;
            try {
                DesignEvaluation result = evaluate(i);
                const std::lock_guard<std::mutex> lock(mutex);
                ready.emplace_back(i, std::move(result));
            } catch (...) {
                const std::lock_guard<std::mutex> lock(mutex);
                if (!failure) failure = std::current_exception();
                stopping = true;
                break;
            }
            ready_cv.notify_one();
        }
        const std::lock_guard<std::mutex> lock(mutex);
        --running;
        ready_cv.notify_one();
    };
    // the calling thread (worker 0) records and asks stop(); an exception of its own ends the
    // recording, and runWorkers rethrows it once the designs under way have finished
    const auto recorder = [&] {
        try {
            for (;;) {
                std::deque<std::pair<std::size_t, DesignEvaluation>> batch;
                bool finished = false;
                {
                    std::unique_lock<std::mutex> lock(mutex);
                    ready_cv.wait_for(lock, std::chrono::milliseconds(100),
                                      [&] { return !ready.empty() || running == 0; });
                    batch.swap(ready);
                    finished = running == 0;
                }
                for (auto& [i, result] : batch) {
                    record(i, std::move(result));
                    ++recorded;
                }
                if (finished) return;
                if (stop && !stopping.load() && stop()) stopping = true;
            }
        } catch (...) {
            stopping = true;
            throw;
        }
    };
    runWorkers("design", evaluators + 1, [&](unsigned w) {
        if (w == 0)
            recorder();
        else
            evaluator();
    });
    if (failure) std::rethrow_exception(failure);
    return recorded;
}

namespace {

/// Feasible designs as rows of scores, each metric in its larger-is-better sense: row r is
/// design index[r]. A design with a NaN value compares neither way in that metric, so it
/// neither dominates nor is dominated: it goes straight to `front`, and is not sorted.
struct ScoreTable {
    std::size_t metrics = 0;
    std::vector<std::size_t> index, front;
    std::vector<double> scores;

    template <class Value>
    void add(std::size_t design, const std::vector<bool>& larger_is_better, const Value& value) {
        const std::size_t at = scores.size();
        bool nan = false;
        for (std::size_t m = 0; m < metrics; ++m) {
            const double v = value(m);
            nan = nan || std::isnan(v);
            scores.push_back(larger_is_better[m] ? v : -v);
        }
        if (nan) {
            scores.resize(at);
            front.push_back(design);
        } else {
            index.push_back(design);
        }
    }
};

std::vector<std::size_t> frontOf(ScoreTable table, const std::function<void(std::size_t, std::size_t)>& progress) {
    const std::size_t metrics = table.metrics;
    std::vector<std::size_t>& front = table.front;
    if (metrics == 0) return table.index;  // nothing to compare: no design dominates another
    const auto score = [&](std::size_t r, std::size_t m) { return table.scores[r * metrics + m]; };
    // a >= b in every metric, and > in one
    const auto dominates = [&](std::size_t a, std::size_t b) {
        bool better = false;
        for (std::size_t m = 0; m < metrics; ++m) {
            if (score(a, m) < score(b, m)) return false;
            better = better || score(a, m) > score(b, m);
        }
        return better;
    };
    // In decreasing lexicographic order of the scores a design's dominators all come before it
    // (rows are in design order, so equal rows stay in it).
    std::vector<std::size_t> order(table.index.size());
    for (std::size_t r = 0; r < order.size(); ++r) order[r] = r;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        for (std::size_t m = 0; m < metrics; ++m) {
            if (score(a, m) != score(b, m)) return score(a, m) > score(b, m);
        }
        return a < b;
    });
    if (metrics <= 2) {
        // One pass, O(n log n) with the sort: i is dominated when a design of strictly larger
        // s0 has s1 >= s1(i) (best_before), or one of equal s0 has s1 > s1(i) (the group's
        // first, which has its largest s1). With one metric, s1 is taken as 0 for every design.
        const auto second = [&](std::size_t r) { return metrics == 2 ? score(r, 1) : 0.0; };
        double best_before = -std::numeric_limits<double>::infinity();
        bool any_before = false;
        for (std::size_t g = 0; g < order.size();) {
            std::size_t end = g;
            while (end < order.size() && score(order[end], 0) == score(order[g], 0)) ++end;
            const double group_best = second(order[g]);
            for (std::size_t k = g; k < end; ++k) {
                const double s1 = second(order[k]);
                if ((any_before && best_before >= s1) || group_best > s1) continue;
                front.push_back(table.index[order[k]]);
            }
            best_before = any_before ? std::max(best_before, group_best) : group_best;
            any_before = true;
            if (progress && (end / 65536 != g / 65536 || end == order.size())) progress(end, order.size());
            g = end;
        }
    } else {
        // Three metrics or more: each design compared with the front found so far; one of the
        // front dominates it when any design does (dominance is transitive and the front
        // holds every undominated design before it). O(n |front|).
        std::vector<std::size_t> rows;  // the front's rows
        for (std::size_t k = 0; k < order.size(); ++k) {
            const std::size_t r = order[k];
            bool dominated = false;
            for (std::size_t f = 0; f < rows.size() && !dominated; ++f) dominated = dominates(rows[f], r);
            if (!dominated) {
                rows.push_back(r);
                front.push_back(table.index[r]);
            }
            if (progress && (k + 1) % 4096 == 0) progress(k + 1, order.size());
        }
        if (progress) progress(order.size(), order.size());
    }
    std::sort(front.begin(), front.end());
    return std::move(front);
}

}  // namespace

std::vector<std::size_t> paretoFront(const std::vector<DesignEvaluation>& designs,
                                     const std::vector<DesignMetric>& metrics,
                                     const std::function<void(std::size_t, std::size_t)>& progress) {
    std::vector<bool> larger;
    larger.reserve(metrics.size());
    for (const DesignMetric& m : metrics) larger.push_back(m.larger_is_better());
    return paretoFront(designs, larger, progress);
}

std::vector<std::size_t> paretoFront(const std::vector<DesignEvaluation>& designs,
                                     const std::vector<bool>& larger_is_better,
                                     const std::function<void(std::size_t, std::size_t)>& progress) {
    ScoreTable table;
    table.metrics = larger_is_better.size();
    for (std::size_t i = 0; i < designs.size(); ++i) {
        const DesignEvaluation& d = designs[i];
        if (!d.feasible) continue;
        if (d.values.size() != table.metrics) {
            throw Error("design: design " + std::to_string(i) + " has " + std::to_string(d.values.size()) +
                        " values, not one per metric (" + std::to_string(table.metrics) + ")");
        }
        table.add(i, larger_is_better, [&](std::size_t m) { return d.values[m]; });
    }
    return frontOf(std::move(table), progress);
}

std::vector<std::size_t> paretoFront(std::span<const double> values, std::span<const bool> feasible,
                                     const std::vector<bool>& larger_is_better,
                                     const std::function<void(std::size_t, std::size_t)>& progress) {
    ScoreTable table;
    table.metrics = larger_is_better.size();
    if (values.size() != feasible.size() * table.metrics) {
        throw Error("design: " + std::to_string(values.size()) + " values are not " + std::to_string(table.metrics) +
                    " for each of " + std::to_string(feasible.size()) + " designs");
    }
    for (std::size_t i = 0; i < feasible.size(); ++i) {
        if (feasible[i]) table.add(i, larger_is_better, [&](std::size_t m) { return values[i * table.metrics + m]; });
    }
    return frontOf(std::move(table), progress);
}

}  // namespace nocdyn
