// BM_Simulate/<robot>/nocdyn: forward dynamics of the example robots (forward_dynamics.hpp)
// over 0.1 s under forces held for 1 ms each (simulate_fixture.hpp), at the default
// tolerances (1e-12 absolute, 1e-10 relative); `simulated_per_cpu_s` is the simulated time per
// CPU second. BM_Simulate/<robot>/nocdyn_cubic: the same forces sampled at 10 kHz through the
// cubic spline (the `simulate` command's case). The Simbody plant on the same forces is
// BM_Simulate/<robot>/simbody (bench_engines.cpp).
#include <benchmark/benchmark.h>

#include "nocdyn/sim/simulator.hpp"
#include "simulate_fixture.hpp"

namespace nocdyn::bench {
namespace {

void held(benchmark::State& state, const std::string& name) {
    const SimulateFixture f(name);
    const Model model(f.robot);
    Simulator simulator(model);
    for (auto _ : state) {
        if (!simulator.reset(f.p0, f.dp0)) state.SkipWithError("reset failed");
        for (const ActuatorVector& tau : f.tau) {
            if (!simulator.advance(kHoldPeriod, tau)) state.SkipWithError("simulation failed");
        }
        benchmark::DoNotOptimize(simulator.pose().data());
    }
    state.counters["simulated_per_cpu_s"] =
        benchmark::Counter(kHoldPeriods * kHoldPeriod, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["steps"] = static_cast<double>(simulator.acceptedSteps()) / static_cast<double>(state.iterations());
}

void cubic(benchmark::State& state, const std::string& name) {
    const SimulateFixture f(name);
    const Model model(f.robot);
    Data data(model);
    std::vector<double> times;
    std::vector<ActuatorVector> tau;
    for (std::size_t k = 0; k <= kCycle; ++k) {
        Pose p, dp, ddp;
        times.push_back(static_cast<double>(k) / kRate);
        benchmarkTrajectory().evaluate(times.back(), p, dp, ddp);
        if (!inverseDynamics(model, data, p, dp, ddp)) state.SkipWithError("singular");
        tau.push_back(data.tau);
    }
    Simulator simulator(model);
    for (auto _ : state) {
        state.PauseTiming();
        ForceSignal forces(times, tau, Interpolation::cubic);
        state.ResumeTiming();
        if (!simulator.reset(f.p0, f.dp0)) state.SkipWithError("reset failed");
        simulator.setForces(std::move(forces));
        for (std::size_t k = 0; k < kCycle; ++k) {  // output at 10 kHz
            if (!simulator.advance(1.0 / kRate)) state.SkipWithError("simulation failed");
        }
        benchmark::DoNotOptimize(simulator.pose().data());
    }
    state.counters["simulated_per_cpu_s"] = benchmark::Counter(kPeriod, benchmark::Counter::kIsIterationInvariantRate);
}

[[maybe_unused]] const bool registered = [] {
    for (const std::string robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        benchmark::RegisterBenchmark(("BM_Simulate/" + robot + "/nocdyn").c_str(), [robot](benchmark::State& s) {
            held(s, robot);
        })->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark(("BM_Simulate/" + robot + "/nocdyn_cubic").c_str(), [robot](benchmark::State& s) {
            cubic(s, robot);
        })->Unit(benchmark::kMicrosecond);
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
