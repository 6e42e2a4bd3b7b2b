// BM_InverseDynamics/<robot>/{mujoco,simbody}: the independent engines' general models of the
// example robots on the same cycle of samples as BM_InverseDynamics/<robot>/nocdyn
// (bench_general.cpp). Neither engine has a per-sample inverse-dynamics entry for a closed
// loop: each call covers the cycle, assembling every sample from the previous one, and
// `per_sample` is the time per sample.
#include <benchmark/benchmark.h>

#include <string>

#include "fixture.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/validation/mujoco_mechanism.hpp"
#include "nocdyn/validation/simbody_mechanism.hpp"

namespace nocdyn::bench {
namespace {

template <typename Engine>
void engine(benchmark::State& state, const std::string& robot) {
    const Fixture& f = fixture();
    Engine mechanism(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
    for (auto _ : state) {
        auto out = mechanism.inverseDynamics(f.trajectory, f.times);
        benchmark::DoNotOptimize(out.data());
    }
    state.counters["per_sample"] =
        benchmark::Counter(static_cast<double>(f.times.size()),
                           benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

[[maybe_unused]] const bool registered = [] {
    for (const std::string robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/mujoco").c_str(), [robot](benchmark::State& s) {
            engine<validation::MujocoMechanism>(s, robot);
        })->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/simbody").c_str(), [robot](
                                                                                               benchmark::State& s) {
            engine<validation::SimbodyMechanism>(s, robot);
        })->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
