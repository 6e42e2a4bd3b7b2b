// Direct kinematics of the general model for every example robot:
// BM_DirectKinematics/<robot>/all_modes: every assembly mode for the actuator values of one
// sample of the benchmark cycle (fixture.hpp), the cycle's 1000 samples in turn;
// BM_DirectKinematics/<robot>/tracker: one tracker call per sample, from the previous pose
// along the cycle (10 kHz). Both report `per_call`.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "fixture.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/io/robot_file.hpp"

namespace nocdyn::bench {
namespace {

/// u of every sample of the cycle (working mode); false when the cycle leaves the workspace.
bool actuatorCycle(const Model& model, std::vector<ActuatorVector>& u, std::vector<Pose>& p) {
    Data data(model);
    for (const Sample& s : fixture().samples) {
        if (!inverseDisplacement(model, data, s.p)) return false;
        u.push_back(data.u);
        p.push_back(s.p);
    }
    return true;
}

void perCall(benchmark::State& state, std::size_t calls) {
    state.counters["per_call"] = benchmark::Counter(
        static_cast<double>(calls), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <bool kTracker>
void directKinematicsBench(benchmark::State& state, const std::string& robot) {
    const Model model(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
    std::vector<ActuatorVector> u;
    std::vector<Pose> poses;
    if (!actuatorCycle(model, u, poses)) {
        state.SkipWithError(("the benchmark trajectory leaves the workspace of " + robot).c_str());
        return;
    }
    Data data(model);
    AssemblyModes modes;
    Pose p = poses.back();
    long modes_found = 0;
    for (auto _ : state) {
        for (const ActuatorVector& uk : u) {
            if constexpr (kTracker) {
                const Status status = trackPose(model, data, uk, p);
                benchmark::DoNotOptimize(status);
                benchmark::DoNotOptimize(p.data());
            } else {
                const Status status = directKinematics(model, data, uk, modes);
                benchmark::DoNotOptimize(status);
                benchmark::DoNotOptimize(modes.mode.data());
                modes_found += modes.count;
            }
        }
        benchmark::ClobberMemory();
    }
    perCall(state, u.size());
    if (!kTracker && state.iterations() > 0) {
        state.counters["modes"] = static_cast<double>(modes_found) /
                                  (static_cast<double>(state.iterations()) * static_cast<double>(u.size()));
    }
}

[[maybe_unused]] const bool registered = [] {
    for (const std::string robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        benchmark::RegisterBenchmark(("BM_DirectKinematics/" + robot + "/all_modes").c_str(),
                                     [robot](benchmark::State& s) { directKinematicsBench<false>(s, robot); });
        benchmark::RegisterBenchmark(("BM_DirectKinematics/" + robot + "/tracker").c_str(),
                                     [robot](benchmark::State& s) { directKinematicsBench<true>(s, robot); });
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
