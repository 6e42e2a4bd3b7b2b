// Direct kinematics of the general model for every example robot:
// BM_DirectKinematics/<robot>/all_modes: every assembly mode for the actuator values of one
// sample of the benchmark cycle (fixture.hpp), the cycle's 1000 samples in turn;
// BM_DirectKinematics/<robot>/tracker: one PoseTracker step per sample along the cycle
// (10 kHz), Newton from the poses extrapolated along the motion;
// BM_DirectKinematics/<robot>/tracker_from_previous: one trackPose call per sample, Newton from
// the previous pose. All report `per_call`.
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

enum class Solver { all_modes, tracker, tracker_from_previous };

template <Solver kSolver>
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
    // the cycle wraps around continuously: the tracker enters it from its last samples
    PoseTracker tracker(poses[poses.size() - 4]);
    for (std::size_t k = poses.size() - 3; k < poses.size(); ++k) (void)tracker.step(model, data, u[k]);
    long modes_found = 0;
    for (auto _ : state) {
        for (const ActuatorVector& uk : u) {
            if constexpr (kSolver == Solver::tracker) {
                const Status status = tracker.step(model, data, uk);
                benchmark::DoNotOptimize(status);
                benchmark::DoNotOptimize(tracker.pose().data());
            } else if constexpr (kSolver == Solver::tracker_from_previous) {
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
    if (kSolver == Solver::all_modes && state.iterations() > 0) {
        state.counters["modes"] = static_cast<double>(modes_found) /
                                  (static_cast<double>(state.iterations()) * static_cast<double>(u.size()));
    }
}

[[maybe_unused]] const bool registered = [] {
    for (const std::string robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        benchmark::RegisterBenchmark(
            ("BM_DirectKinematics/" + robot + "/all_modes").c_str(),
            [robot](benchmark::State& s) { directKinematicsBench<Solver::all_modes>(s, robot); });
        benchmark::RegisterBenchmark(
            ("BM_DirectKinematics/" + robot + "/tracker").c_str(),
            [robot](benchmark::State& s) { directKinematicsBench<Solver::tracker>(s, robot); });
        benchmark::RegisterBenchmark(
            ("BM_DirectKinematics/" + robot + "/tracker_from_previous").c_str(),
            [robot](benchmark::State& s) { directKinematicsBench<Solver::tracker_from_previous>(s, robot); });
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
