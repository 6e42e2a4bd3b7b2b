// BM_InverseDynamics/<robot>/{mujoco,simbody}: the independent engines' general models of the
// example robots on the same cycle of samples as BM_InverseDynamics/<robot>/nocdyn
// (bench_general.cpp). Neither engine has a per-sample inverse-dynamics entry for a closed
// loop: each call covers the cycle, assembling every sample from the previous one, and
// `per_sample` is the time per sample.
// BM_Simulate/<robot>/simbody: the Simbody plant (SimbodyMechanism::advance, accuracy 1e-10)
// under the forces of BM_Simulate/<robot>/nocdyn (bench_simulate.cpp), held for 1 ms each.
#include <benchmark/benchmark.h>

#include <string>

#include "fixture.hpp"
#include "simulate_fixture.hpp"
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

void simbodyPlant(benchmark::State& state, const std::string& name) {
    const SimulateFixture f(name);
    validation::SimbodyMechanism plant(f.robot);
    long steps = 0;
    for (auto _ : state) {
        plant.resetPlant(f.p0, f.dp0);
        for (const ActuatorVector& tau : f.tau) {
            plant.setActuatorForces(Eigen::VectorXd(tau));
            plant.advance(kHoldPeriod);
        }
        steps += plant.plantSteps();
        benchmark::DoNotOptimize(plant.time());
    }
    state.counters["simulated_per_cpu_s"] =
        benchmark::Counter(kHoldPeriods * kHoldPeriod, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["steps"] = static_cast<double>(steps) / static_cast<double>(state.iterations());
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
        benchmark::RegisterBenchmark(("BM_Simulate/" + robot + "/simbody").c_str(), [robot](benchmark::State& s) {
            simbodyPlant(s, robot);
        })->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
