// Batch inverse dynamics (batch.hpp), forward dynamics and simulation, and the machine's
// arithmetic peak that the bound in README.md is measured against.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "fixture.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/short_form.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/prr3/batch.hpp"
#include "nocdyn/spatial_batch.hpp"

namespace nocdyn::bench {
namespace {

void perSample(benchmark::State& state, double samples_per_iteration) {
    state.counters["per_sample"] = benchmark::Counter(
        samples_per_iteration, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// The fixture's cycle repeated `cycles` times as a structure-of-arrays batch.
prr3::SampleBatch batchOf(std::size_t cycles) {
    const Fixture& f = fixture();
    prr3::SampleBatch batch(static_cast<Eigen::Index>(cycles * f.samples.size()));
    Eigen::Index row = 0;
    for (std::size_t c = 0; c < cycles; ++c) {
        for (const Sample& s : f.samples) {
            batch.p.row(row) = s.p.transpose();
            batch.dp.row(row) = s.dp.transpose();
            batch.ddp.row(row) = s.ddp.transpose();
            ++row;
        }
    }
    return batch;
}

/// One cycle (1000 samples, 152 kB of inputs and outputs: cache-resident) on one thread.
void batchCycle(benchmark::State& state) {
    const Fixture& f = fixture();
    prr3::SampleBatch batch = batchOf(1);
    for (auto _ : state) {
        const prr3::BatchStatus status = prr3::inverseDynamicsBatch(f.model, batch);
        benchmark::DoNotOptimize(status);
        benchmark::DoNotOptimize(batch.tau.data());
        benchmark::ClobberMemory();
    }
    perSample(state, static_cast<double>(batch.size()));
}

/// 100 cycles (100 000 samples) over state.range(0) threads; wall-clock time.
void batchThreads(benchmark::State& state) {
    const Fixture& f = fixture();
    prr3::SampleBatch batch = batchOf(100);
    const auto threads = static_cast<unsigned>(state.range(0));
    for (auto _ : state) {
        const prr3::BatchStatus status = prr3::inverseDynamicsBatchParallel(f.model, batch, threads);
        benchmark::DoNotOptimize(status);
        benchmark::DoNotOptimize(batch.tau.data());
        benchmark::ClobberMemory();
    }
    perSample(state, static_cast<double>(batch.size()));
}

/// 10 000 samples of the Stewart table (robots/stewart.yaml) about home, two harmonics per
/// coordinate (1-2 cm, 0.02-0.04 rad), by spatial::inverseDynamicsBatch over state.range(0)
/// threads; C-ordered (N, 6) arrays as from NumPy; wall-clock time.
void spatialBatchThreads(benchmark::State& state) {
    using Strided = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;
    using RowMajor = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    static const spatial::Model model(
        io::loadSpatialRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/stewart.yaml"));
    constexpr Eigen::Index kSamples = 10000;
    const int d = model.task_dimension, n = model.actuators;
    RowMajor p(kSamples, d), dp(kSamples, d), ddp(kSamples, d), out(kSamples, 4 * n);
    for (Eigen::Index k = 0; k < kSamples; ++k) {
        const double t = 1e-4 * static_cast<double>(k);
        for (int i = 0; i < d; ++i) {
            const double amplitude = i < 3 ? 0.01 + 0.003 * i : 0.02 + 0.005 * (i - 3);
            p(k, i) = model.home(i), dp(k, i) = 0.0, ddp(k, i) = 0.0;
            for (const double f : {1.0 + i, 2.0 + 2.0 * i}) {
                const double w = 2.0 * M_PI * f, phase = 0.3 * i;
                p(k, i) += amplitude * std::sin(w * t + phase) / f;
                dp(k, i) += amplitude * w * std::cos(w * t + phase) / f;
                ddp(k, i) -= amplitude * w * w * std::sin(w * t + phase) / f;
            }
        }
    }
    const auto in = [&](const RowMajor& a) {
        return Eigen::Map<const Eigen::ArrayXXd, 0, Strided>(a.data(), kSamples, d, Strided(1, d));
    };
    // u, du, ddu, tau side by side in one C-ordered (N, 4n) buffer
    const auto to = [&](int i) {
        return Eigen::Map<Eigen::ArrayXXd, 0, Strided>(out.data() + i * n, kSamples, n, Strided(1, 4 * n));
    };
    spatial::BatchOptions options;
    options.threads = static_cast<unsigned>(state.range(0));
    for (auto _ : state) {
        const BatchResult result =
            spatial::inverseDynamicsBatch(model, in(p), in(dp), in(ddp), to(0), to(1), to(2), to(3), options);
        if (!result.ok()) {
            state.SkipWithError("the motion leaves the Stewart table's workspace");
            return;
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    perSample(state, static_cast<double>(kSamples));
}

/// The paper's robot as the general model (the short form expanded), as the simulator runs it.
const Model& generalModel() {
    static const Model model{io::expand(io::RobotParameters{})};
    return model;
}

/// One evaluation of d2p/dt2 from the state (p, dp/dt) and the forces on the general model:
/// position, velocity and shaping stages, M_p and h_p, and the solve of A_p^T tau = M_p d2p/dt2
/// + h_p (the right-hand side the simulator integrates).
void forwardDynamics(benchmark::State& state) {
    const Fixture& f = fixture();
    const Model& model = generalModel();
    Data data(model);
    std::vector<ActuatorVector> tau;
    for (const Sample& s : f.samples) tau.emplace_back(s.tau);
    std::size_t k = 0;
    for (auto _ : state) {
        const Sample& s = f.samples[k];
        const Status status = nocdyn::forwardDynamics(model, data, s.p, s.dp, tau[k]);
        benchmark::DoNotOptimize(status);
        benchmark::DoNotOptimize(data.t_M_dot);
        if (++k == f.samples.size()) k = 0;
    }
    perSample(state, 1);
}

/// One simulated second of the paper's trajectory 1 on the general model at the simulator's
/// default tolerance, driven by the inverse-dynamics forces at 10 kHz (linear between ticks).
void simulateSecond(benchmark::State& state) {
    const Model& model = generalModel();
    const PoseTrajectory trajectory = paperTrajectory1();
    constexpr int kTicks = 10000;
    std::vector<double> times(kTicks + 1);
    std::vector<ActuatorVector> tau(kTicks + 1);
    Data data(model);
    Pose p0, dp0, ddp;
    for (int i = 0; i <= kTicks; ++i) {
        Pose p, dp;
        times[static_cast<std::size_t>(i)] = i / kRate;
        trajectory.evaluate(i / kRate, p, dp, ddp);
        if (i == 0) p0 = p, dp0 = dp;
        (void)inverseDynamics(model, data, p, dp, ddp);
        tau[static_cast<std::size_t>(i)] = data.tau;
    }
    Simulator simulator(model);
    std::size_t steps = 0;
    for (auto _ : state) {
        (void)simulator.reset(p0, dp0, 0.0);
        simulator.setForces(ForceSignal(times, tau, Interpolation::linear));
        const std::size_t before = simulator.acceptedSteps();
        for (int i = 0; i < kTicks; ++i) {
            const Status status = simulator.advance(1.0 / kRate);
            benchmark::DoNotOptimize(status);
        }
        steps += simulator.acceptedSteps() - before;
        benchmark::DoNotOptimize(simulator.u());
    }
    state.counters["steps"] = static_cast<double>(steps) / static_cast<double>(state.iterations());
}

// ---- the machine's arithmetic peak on one core ------------------------------------------
// 4-lane double vectors (GCC vector extension), AVX2+FMA code. Each benchmark reports
// `per_lane_op`: seconds per scalar (lane) operation at full throughput.
using V4 = double __attribute__((vector_size(32)));

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define NOCDYN_AVX2 __attribute__((target("avx2,fma")))
#else
#define NOCDYN_AVX2
#endif

constexpr int kChains = 12;  // independent dependency chains: covers latency x throughput

NOCDYN_AVX2 void peakAddMul(benchmark::State& state) {
    // half multiplies, half adds, all independent: the mix of the batch kernel
    V4 acc[kChains];
    for (int i = 0; i < kChains; ++i) acc[i] = V4{1.0 + i, 1.0, 1.0, 1.0};
    const V4 m = {0.999999, 0.999999, 0.999999, 0.999999}, a = {1e-9, 1e-9, 1e-9, 1e-9};
    constexpr int kRounds = 1000;
    for (auto _ : state) {
        for (int r = 0; r < kRounds; ++r) {
            for (int i = 0; i < kChains; i += 2) {
                acc[i] = acc[i] * m;
                acc[i + 1] = acc[i + 1] + a;
            }
        }
        benchmark::DoNotOptimize(acc);  // once per iteration: the chains stay in registers
    }
    state.counters["per_lane_op"] = benchmark::Counter(
        4.0 * kRounds * kChains, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <int Op>
NOCDYN_AVX2 void peakDivSqrt(benchmark::State& state) {
    V4 acc[kChains];
    for (int i = 0; i < kChains; ++i) acc[i] = V4{2.0 + i, 2.0, 2.0, 2.0};
    const V4 one = {1.0, 1.0, 1.0, 1.0};
    constexpr int kRounds = 200;
    for (auto _ : state) {
        for (int r = 0; r < kRounds; ++r) {
            for (int i = 0; i < kChains; ++i) {
                if constexpr (Op == 0) {
                    acc[i] = one / acc[i];  // 1 / (1 / x) = x: stays bounded
                } else {
                    acc[i] = __builtin_ia32_sqrtpd256(acc[i]) + one;  // converges to ~2.6
                }
            }
        }
        benchmark::DoNotOptimize(acc);
    }
    state.counters["per_lane_op"] = benchmark::Counter(
        4.0 * kRounds * kChains, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

[[maybe_unused]] const bool registered = [] {
    benchmark::RegisterBenchmark("BM_Batch/nocdyn/cycle_1thread", batchCycle);
    benchmark::RegisterBenchmark("BM_Batch/nocdyn/100k_samples", batchThreads)
        ->ArgName("threads")
        ->Arg(1)
        ->Arg(2)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("BM_SpatialBatch/stewart/10k_samples", spatialBatchThreads)
        ->ArgName("threads")
        ->Arg(1)
        ->Arg(2)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("BM_ForwardDynamics/nocdyn", forwardDynamics);
    benchmark::RegisterBenchmark("BM_SimulateSecond/nocdyn", simulateSecond)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("BM_Peak/add_mul_avx2", peakAddMul);
    benchmark::RegisterBenchmark("BM_Peak/div_avx2", peakDivSqrt<0>);
    benchmark::RegisterBenchmark("BM_Peak/sqrt_avx2", peakDivSqrt<1>);
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
