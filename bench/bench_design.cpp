// Design sweeps (design.hpp): the envelope-and-workspace evaluation of one 3-RRR design of
// examples/design_3rrr/family.yaml (parsed from the parametric file, as a sweep does), and
// the throughput of two worker processes against one on the same designs.
//   BM_DesignEvaluation/resolution:<r>/lanes:<4|8>: workspace_area, condition_median,
//     envelope_x, _y and _theta at 50 Hz, the batch on packets of four or eight samples; the
//     goal is <= 20 ms per design on one core.
//   BM_DesignParts/part:<part>/lanes:<4|8>: where that time goes (0 parse and model, 1
//     workspace at resolution 61, 2-4 the envelope along theta, x, y).
//   BM_DesignProcesses: one iteration evaluates 2 x kDesigns designs in one process, then the
//     same designs split over two forked processes; counter `speedup` is the throughput ratio
//     (the goal is >= 1.7 on two cores), read from one run.
//   BM_ParetoFront/<designs>/<metrics>: the Pareto front of random designs, values on a coarse
//     grid so that many tie (metrics workspace_area, moving_mass, peak_force); the goal is under
//     5 s for 1e6 designs of two metrics on one core.
#include <benchmark/benchmark.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "nocdyn/analysis/design.hpp"
#include "nocdyn/batch.hpp"
#include "nocdyn/tables/design.hpp"

namespace nocdyn::bench {
namespace {

constexpr std::size_t kDesigns = 6;

tables::DesignFamily family() {
    tables::DesignFamily f;
    f.text = io::readRobotFileText(std::string(NOCDYN_SOURCE_DIR) + "/examples/design_3rrr/family.yaml");
    f.source = "family.yaml";
    f.ranges = {{"r_b", 0.15, 0.25}, {"l1", 0.09, 0.13}};
    return f;
}

std::vector<DesignMetric> metrics() {
    std::vector<DesignMetric> m;
    for (const char* name :
         {"workspace_area", "condition_median", "envelope_x@50", "envelope_y@50", "envelope_theta@50"})
        m.push_back(parseDesignMetric(name));
    return m;
}

/// The batch's packets for one benchmark (its argument `lanes`: 4, or 8 where the CPU has
/// AVX-512), the default again after it.
struct Lanes {
    explicit Lanes(benchmark::State& state, std::int64_t lanes) {
        state.counters["lanes"] = setBatchPackets(lanes == 4 ? BatchPackets::four : BatchPackets::eight);
    }
    ~Lanes() { setBatchPackets(BatchPackets::automatic); }
    Lanes(const Lanes&) = delete;
    Lanes& operator=(const Lanes&) = delete;
};

void BM_DesignEvaluation(benchmark::State& state) {
    const Lanes lanes(state, state.range(1));
    const tables::DesignFamily f = family();
    const std::vector<DesignMetric> m = metrics();
    DesignOptions options;
    options.workspace.resolution = static_cast<int>(state.range(0));
    const auto points = sweepPoints(f.ranges, SweepKind::random, 16, 1);
    std::size_t k = 0;
    for (auto _ : state) {
        const DesignEvaluation e = tables::evaluateFamilyDesign(f, points[k++ % points.size()], m, options);
        benchmark::DoNotOptimize(e.values.data());
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_DesignEvaluation)
    ->ArgNames({"resolution", "lanes"})
    ->ArgsProduct({{61, 101, 201}, {4, 8}})
    ->Unit(benchmark::kMillisecond);

/// The parts of one evaluation, on the same designs: 0 parses the family and builds the
/// model, 1 the workspace map at resolution 61 (no curves), 2, 3, 4 the envelope along theta,
/// x and y at 50 Hz (maximumAmplitude). Each on packets of four and of eight.
void BM_DesignParts(benchmark::State& state) {
    const Lanes lanes(state, state.range(1));
    const tables::DesignFamily f = family();
    const auto points = sweepPoints(f.ranges, SweepKind::random, 16, 1);
    std::vector<Model> models;
    for (const auto& point : points) models.emplace_back(tables::designRobot(f, point));
    const auto part = state.range(0);
    std::size_t k = 0;
    for (auto _ : state) {
        const std::size_t i = k++ % points.size();
        if (part == 0) {
            const Model model(tables::designRobot(f, points[i]));
            benchmark::DoNotOptimize(&model);
        } else if (part == 1) {
            const WorkspaceMap map = workspaceMap(models[i], {models[i].home(0), 61, false});
            benchmark::DoNotOptimize(map.area);
        } else {
            const EnvelopePoint p = maximumAmplitude(models[i], static_cast<EnvelopeAxis>(part - 2), 50.0);
            benchmark::DoNotOptimize(p.amplitude);
        }
    }
}
BENCHMARK(BM_DesignParts)
    ->ArgNames({"part", "lanes"})
    ->ArgsProduct({{0, 1, 2, 3, 4}, {4, 8}})
    ->Unit(benchmark::kMillisecond);

/// Evaluates designs [first, first + count) of `points`.
void evaluateRange(const tables::DesignFamily& f, const std::vector<std::vector<double>>& points, std::size_t first,
                   std::size_t count, const std::vector<DesignMetric>& m, const DesignOptions& options) {
    for (std::size_t i = first; i < first + count; ++i) {
        const DesignEvaluation e = tables::evaluateFamilyDesign(f, points[i], m, options);
        benchmark::DoNotOptimize(e.values.data());
    }
}

/// Wall time [s] of the designs split over `processes` forked processes.
double wallTime(int processes, const tables::DesignFamily& f, const std::vector<std::vector<double>>& points,
                const std::vector<DesignMetric>& m, const DesignOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t share = points.size() / static_cast<std::size_t>(processes);
    std::vector<pid_t> children;
    for (int p = 0; p < processes; ++p) {
        const pid_t pid = fork();
        if (pid == 0) {
            evaluateRange(f, points, static_cast<std::size_t>(p) * share, share, m, options);
            _exit(0);
        }
        children.push_back(pid);
    }
    for (const pid_t pid : children) waitpid(pid, nullptr, 0);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_DesignProcesses(benchmark::State& state) {
    const tables::DesignFamily f = family();
    const std::vector<DesignMetric> m = metrics();
    DesignOptions options;
    options.workspace.resolution = 101;
    const auto points = sweepPoints(f.ranges, SweepKind::random, 2 * kDesigns, 2);
    double one = 0.0, two = 0.0;
    for (auto _ : state) {
        one += wallTime(1, f, points, m, options);
        two += wallTime(2, f, points, m, options);
    }
    state.counters["one_process_ms_per_design"] = 1e3 * one / static_cast<double>(state.iterations() * points.size());
    state.counters["two_processes_ms_per_design"] = 1e3 * two / static_cast<double>(state.iterations() * points.size());
    state.counters["speedup"] = one / two;
}
BENCHMARK(BM_DesignProcesses)->Iterations(3)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ParetoFront(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const auto m = static_cast<std::size_t>(state.range(1));
    const std::vector<DesignMetric> all = {parseDesignMetric("workspace_area"), parseDesignMetric("moving_mass"),
                                           parseDesignMetric("peak_force")};
    const std::vector<DesignMetric> metrics(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(m));
    std::mt19937_64 engine(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<DesignEvaluation> designs(n);
    for (DesignEvaluation& d : designs) {
        d.feasible = unit(engine) < 0.9;
        for (std::size_t k = 0; k < m; ++k) d.values.push_back(std::round(unit(engine) * 1000.0) / 1000.0);
    }
    std::size_t front = 0;
    for (auto _ : state) {
        front = paretoFront(designs, metrics).size();
        benchmark::DoNotOptimize(front);
    }
    state.counters["front"] = static_cast<double>(front);
}
BENCHMARK(BM_ParetoFront)->Args({40000, 2})->Args({1000000, 2})->Args({100000, 3})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace nocdyn::bench

BENCHMARK_MAIN();
