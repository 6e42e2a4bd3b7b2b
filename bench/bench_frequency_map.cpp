// The first natural frequency over the workspace (analysis/frequency_map.hpp) against the
// workspace map it runs over, in the same run, at 101 and 201 points per side:
//   BM_FrequencyMap/<robot>/<n>/workspace        workspaceMap (no curves), the grid and its cells
//   BM_FrequencyMap/<robot>/<n>/first_frequency  firstFrequencyMap over that map (one core)
// on the compliant paper prototype (robots/paper-3prr-compliant.yaml) and on the 3-RRR with a
// drive stiffness and elastic links (its feasible region fills more of its grid). The counter
// per_point is the time per feasible point.
#include <benchmark/benchmark.h>

#include <string>

#include "nocdyn/analysis/frequency_map.hpp"
#include "nocdyn/analysis/workspace.hpp"
#include "nocdyn/io/robot_file.hpp"

namespace nocdyn::bench {
namespace {

RobotDescription robotFile(const std::string& robot) {
    RobotDescription d = io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml");
    if (robot == "3-rrr") {
        // the compliance of bench_stiffness.cpp: a stiff drive and aluminium links
        for (LimbDescription& limb : d.limbs) {
            for (JointDescription& joint : limb.joints) {
                if (joint.actuated) joint.stiffness = 20.0;
            }
            for (BodyDescription& body : limb.bodies) body.elastic = ElasticBeam{2.8e6, 23.3};
        }
    }
    return d;
}

void run(benchmark::State& state, const std::string& robot, int resolution, bool frequency) {
    const Model model(robotFile(robot));
    WorkspaceOptions options{model.home(0), resolution, false};
    const WorkspaceMap map = workspaceMap(model, options);
    int points = 0;
    for (auto _ : state) {
        if (frequency) {
            const FirstFrequencyMap f = firstFrequencyMap(model, map);
            points = f.points;
            benchmark::DoNotOptimize(f.lowest);
        } else {
            const WorkspaceMap m = workspaceMap(model, options);
            benchmark::DoNotOptimize(m.area);
        }
        benchmark::ClobberMemory();
    }
    if (frequency) {
        state.counters["points"] = points;
        state.counters["per_point"] = benchmark::Counter(
            static_cast<double>(points), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    }
}

const bool kRegistered = [] {
    for (const char* robot : {"paper-3prr-compliant", "3-rrr"}) {
        for (const int n : {101, 201}) {
            for (const bool frequency : {false, true}) {
                benchmark::RegisterBenchmark(
                    (std::string("BM_FrequencyMap/") + robot + "/" + std::to_string(n) + "/" +
                     (frequency ? "first_frequency" : "workspace"))
                        .c_str(),
                    [robot = std::string(robot), n, frequency](benchmark::State& s) { run(s, robot, n, frequency); })
                    ->Unit(benchmark::kMillisecond);
            }
        }
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
