// Inverse dynamics per sample of the frozen hand-written 3-PRR kernel, and its stages (the
// engines and the general model per robot: bench_engines.cpp, bench_robots.cpp).
//
// BM_InverseDynamics/nocdyn times the lean entry (prr3::inverseDynamicsFast), /nocdyn_full the
// full path (prr3::inverseDynamics). Every BM_InverseDynamics/... runs the same cycle of 1000 samples
// (fixture.hpp) per iteration, in the same order, and reports `per_sample` = time / 1000 (seconds; the console prints
// it with an SI prefix). The BM_Stage/... benchmarks run one stage of one sample per iteration, on Data prepared by the
// earlier stages outside the timed loop.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

#include "fixture.hpp"
#include "nocdyn/noc.hpp"
#include "nocdyn/prr3/fast.hpp"

namespace nocdyn::bench {
namespace {

void perSample(benchmark::State& state, std::size_t samples_per_iteration) {
    state.counters["per_sample"] =
        benchmark::Counter(static_cast<double>(samples_per_iteration),
                           benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// ---- the whole per-sample path, three engines -----------------------------------------

// The lean per-sample entry (fast.hpp): pose-space sample -> u, du, ddu, tau and a Status.
void inverseDynamicsNocdyn(benchmark::State& state) {
    const Fixture& f = fixture();
    prr3::FastData data;
    for (auto _ : state) {
        for (const Sample& s : f.samples) {
            const prr3::Status status = prr3::inverseDynamicsFast(f.model, data, s.p, s.dp, s.ddp);
            benchmark::DoNotOptimize(status);
            benchmark::DoNotOptimize(data.tau);
        }
        benchmark::ClobberMemory();
    }
    perSample(state, f.samples.size());
}

// The full per-sample path (dynamics.hpp): also stores T_i, dT_i, J_j^-1, H^-1, I, C, phi_A, ...
void inverseDynamicsNocdynFull(benchmark::State& state) {
    const Fixture& f = fixture();
    prr3::Data data;
    for (auto _ : state) {
        for (const Sample& s : f.samples) {
            const prr3::Status status = prr3::inverseDynamics(f.model, data, s.p, s.dp, s.ddp);
            benchmark::DoNotOptimize(status);
            benchmark::DoNotOptimize(data.tau);
        }
        benchmark::ClobberMemory();
    }
    perSample(state, f.samples.size());
}

// ---- stages of nocdyn's per-sample path ----------------------------------------------

/// Data after the whole path for every sample of the cycle.
const std::vector<prr3::Data>& prepared() {
    static const std::vector<prr3::Data> all = [] {
        const Fixture& f = fixture();
        std::vector<prr3::Data> out(f.samples.size());
        for (std::size_t k = 0; k < out.size(); ++k) {
            const Sample& s = f.samples[k];
            (void)prr3::inverseDynamics(f.model, out[k], s.p, s.dp, s.ddp);
        }
        return out;
    }();
    return all;
}

template <class Stage>
void stage(benchmark::State& state, Stage&& run) {
    const Fixture& f = fixture();
    std::vector<prr3::Data> data = prepared();
    std::size_t k = 0;
    for (auto _ : state) {
        run(f, f.samples[k], data[k]);
        benchmark::ClobberMemory();
        if (++k == data.size()) k = 0;
    }
    perSample(state, 1);
}

void stageInverseDisplacement(benchmark::State& state) {
    stage(state, [](const Fixture& f, const Sample& s, prr3::Data& d) {
        benchmark::DoNotOptimize(prr3::inverseDisplacement(f.model, d, s.p));
    });
}
void stageVelocity(benchmark::State& state) {
    stage(state, [](const Fixture& f, const Sample& s, prr3::Data& d) {
        benchmark::DoNotOptimize(prr3::velocityFromPlatformTwist(f.model, d, s.dp));
    });
}
void stageTwistShaping(benchmark::State& state) {
    stage(state, [](const Fixture& f, const Sample&, prr3::Data& d) { prr3::twistShaping(f.model, d); });
}
void stageAccelerations(benchmark::State& state) {
    stage(state, [](const Fixture&, const Sample& s, prr3::Data& d) { prr3::actuatorAccelerations(d, s.ddp); });
}
void stageInertia(benchmark::State& state) {
    stage(state, [](const Fixture& f, const Sample&, prr3::Data& d) { noc::inertia(f.model.M, d.T, d.I); });
}
void stageCoriolis(benchmark::State& state) {
    stage(state, [](const Fixture& f, const Sample&, prr3::Data& d) { noc::coriolis(f.model.M, d.T, d.T_dot, d.C); });
}
void stageDynamics(benchmark::State& state) {
    stage(state, [](const Fixture& f, const Sample&, prr3::Data& d) { prr3::jointSpaceDynamics(f.model, d); });
}
void stageForces(benchmark::State& state) {
    stage(state, [](const Fixture&, const Sample&, prr3::Data& d) { prr3::actuatorForces(d); });
}

[[maybe_unused]] const bool registered = [] {
    benchmark::RegisterBenchmark("BM_InverseDynamics/nocdyn", inverseDynamicsNocdyn);
    benchmark::RegisterBenchmark("BM_InverseDynamics/nocdyn_full", inverseDynamicsNocdynFull);
    benchmark::RegisterBenchmark("BM_Stage/inverse_displacement", stageInverseDisplacement);
    benchmark::RegisterBenchmark("BM_Stage/jacobians_velocity", stageVelocity);
    benchmark::RegisterBenchmark("BM_Stage/twist_shaping_T_dT", stageTwistShaping);
    benchmark::RegisterBenchmark("BM_Stage/accelerations", stageAccelerations);
    benchmark::RegisterBenchmark("BM_Stage/inertia_I", stageInertia);
    benchmark::RegisterBenchmark("BM_Stage/coriolis_C", stageCoriolis);
    benchmark::RegisterBenchmark("BM_Stage/dynamics_I_and_C", stageDynamics);
    benchmark::RegisterBenchmark("BM_Stage/forces_tau", stageForces);
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench

BENCHMARK_MAIN();  // one main for both translation units
