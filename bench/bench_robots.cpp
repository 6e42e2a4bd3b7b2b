// Inverse dynamics per sample of the general model, for every example robot:
// BM_InverseDynamics/<robot>/<engine>, robot in paper-3prr, 3-rrr, 3-rpr, 4-rrr; engine
// nocdyn (the lean path inverseDynamicsFast), nocdyn_full (T_i, I and C stored), and for
// the paper's robot `baseline`, the hand-specialised 3-PRR path the general one must match.
// Each runs the paper's trajectory 1 plus a second harmonic per axis, a cycle of 1000
// samples (fixture.hpp), and reports `per_sample`. The two-DOF five-bar and biglide (nocdyn,
// nocdyn_full, and the batch) run their own cycle of the tool point about home (fixture.hpp, ToolCycle).
// BM_Batch/<robot>/nocdyn: the general batch (batch.hpp, the lean kernel on packets of eight
// samples where the CPU has AVX-512, else four) over the same cycle on one thread,
// BM_Batch/<robot>/nocdyn_4lanes the same on packets of four (AVX2),
// next to prr3's BM_Batch/nocdyn/cycle_1thread; BM_Batch/<robot>/nocdyn_100k: 100 cycles over
// 1 and 2 threads, wall-clock time.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "fixture.hpp"
#include "nocdyn/batch.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/prr3/fast.hpp"

namespace nocdyn::bench {
namespace {

void perSample(benchmark::State& state, std::size_t samples) {
    state.counters["per_sample"] = benchmark::Counter(
        static_cast<double>(samples), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

Model loadExample(const std::string& robot) {
    return Model(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
}

template <bool kLean>
void generalModel(benchmark::State& state, const std::string& robot) {
    const Fixture& f = fixture();
    const Model model = loadExample(robot);
    Data data(model);
    for (const Sample& s : f.samples) {
        if (!inverseDynamics(model, data, s.p, s.dp, s.ddp)) {
            state.SkipWithError(("the benchmark trajectory leaves the workspace of " + robot).c_str());
            return;
        }
    }
    for (auto _ : state) {
        for (const Sample& s : f.samples) {
            const Status status = kLean ? inverseDynamicsFast(model, data, s.p, s.dp, s.ddp)
                                        : inverseDynamics(model, data, s.p, s.dp, s.ddp);
            benchmark::DoNotOptimize(status);
            benchmark::DoNotOptimize(data.tau.data());
        }
        benchmark::ClobberMemory();
    }
    perSample(state, f.samples.size());
}

/// A two-DOF robot (the five-bar, the biglide) per sample on its own tool cycle (ToolCycle):
/// the lean path, or the full one, with the task map E inside.
template <bool kLean>
void toolModel(benchmark::State& state, const std::string& robot) {
    const Model model = loadExample(robot);
    const ToolCycle cycle(model.home);
    Data data(model);
    for (std::size_t k = 0; k < cycle.times.size(); ++k) {
        if (!inverseDynamics(model, data, cycle.p[k], cycle.dp[k], cycle.ddp[k])) {
            state.SkipWithError(("the tool cycle leaves the workspace of " + robot).c_str());
            return;
        }
    }
    for (auto _ : state) {
        for (std::size_t k = 0; k < cycle.times.size(); ++k) {
            const Status status = kLean ? inverseDynamicsFast(model, data, cycle.p[k], cycle.dp[k], cycle.ddp[k])
                                        : inverseDynamics(model, data, cycle.p[k], cycle.dp[k], cycle.ddp[k]);
            benchmark::DoNotOptimize(status);
            benchmark::DoNotOptimize(data.tau.data());
        }
        benchmark::ClobberMemory();
    }
    perSample(state, cycle.times.size());
}

// The hand-specialised 3-PRR lean path, kept frozen as the baseline.
void baseline(benchmark::State& state) {
    const Fixture& f = fixture();
    prr3::FastData data(f.model);
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

/// The batch's packet width for one benchmark's lifetime, back to automatic after it.
struct PacketWidth {
    explicit PacketWidth(BatchPackets p) { setBatchPackets(p); }
    ~PacketWidth() { setBatchPackets(BatchPackets::automatic); }
    PacketWidth(const PacketWidth&) = delete;
    PacketWidth& operator=(const PacketWidth&) = delete;
};

/// The general batch over `cycles` repetitions of the cycle, on `threads` threads.
void generalBatch(benchmark::State& state, const std::string& robot, std::size_t cycles, unsigned threads,
                  BatchPackets packets = BatchPackets::automatic) {
    const PacketWidth width(packets);
    state.counters["lanes"] = batchPacketWidth();
    const Fixture& f = fixture();
    const Model model = loadExample(robot);
    const auto N = static_cast<Eigen::Index>(cycles * f.samples.size());
    Eigen::ArrayX3d p(N, 3), dp(N, 3), ddp(N, 3);
    for (Eigen::Index k = 0; k < N; ++k) {
        const Sample& s = f.samples[static_cast<std::size_t>(k) % f.samples.size()];
        p.row(k) = s.p.transpose();
        dp.row(k) = s.dp.transpose();
        ddp.row(k) = s.ddp.transpose();
    }
    const int n = model.actuators;
    Eigen::ArrayXXd u(N, n), du(N, n), ddu(N, n), tau(N, n);
    if (!inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1).ok()) {
        state.SkipWithError(("the benchmark trajectory leaves the workspace of " + robot).c_str());
        return;
    }
    for (auto _ : state) {
        const BatchResult result = inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, threads);
        benchmark::DoNotOptimize(result);
        benchmark::DoNotOptimize(tau.data());
        benchmark::ClobberMemory();
    }
    perSample(state, static_cast<std::size_t>(N));
}

/// The batch on a two-DOF robot's tool cycle (ToolCycle), one thread, in the packet layout
/// `packets`: the same kernel as the per-sample lean path, as generalBatch.
void toolBatch(benchmark::State& state, const std::string& robot, BatchPackets packets) {
    const PacketWidth width(packets);
    state.counters["lanes"] = batchPacketWidth();
    const Model model = loadExample(robot);
    const ToolCycle cycle(model.home);
    const auto N = static_cast<Eigen::Index>(cycle.times.size());
    Eigen::ArrayX3d p(N, 3), dp(N, 3), ddp(N, 3);
    for (Eigen::Index k = 0; k < N; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        p.row(k) = cycle.p[kk].transpose();
        dp.row(k) = cycle.dp[kk].transpose();
        ddp.row(k) = cycle.ddp[kk].transpose();
    }
    const int n = model.actuators;
    Eigen::ArrayXXd u(N, n), du(N, n), ddu(N, n), tau(N, n);
    if (!inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1).ok()) {
        state.SkipWithError(("the tool cycle leaves the workspace of " + robot).c_str());
        return;
    }
    for (auto _ : state) {
        const BatchResult result = inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1);
        benchmark::DoNotOptimize(result);
        benchmark::DoNotOptimize(tau.data());
        benchmark::ClobberMemory();
    }
    perSample(state, static_cast<std::size_t>(N));
}

/// The one-thread batch of 100 cycles on the paper's robot with the pose columns in `order`
/// (the core's [theta, x, y] or Python's [x, y, theta]: the same gathers, another column
/// index), inputs and outputs column-major (Eigen's) or row-major (NumPy's C order, viewed in
/// place as Python's batch views it).
void poseOrderBatch(benchmark::State& state, PoseColumns order, bool c_order) {
    const Fixture& f = fixture();
    const Model model = loadExample("paper-3prr");
    const auto N = static_cast<Eigen::Index>(100 * f.samples.size());
    const int n = model.actuators;
    using Stride = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;
    // element (k, i) at k * step + i * stride
    const auto strides = [&](Eigen::Index columns) { return c_order ? Stride(1, columns) : Stride(N, 1); };
    std::vector<double> p(static_cast<std::size_t>(3 * N)), dp(p.size()), ddp(p.size());
    std::vector<double> u(static_cast<std::size_t>(n * N)), du(u.size()), ddu(u.size()), tau(u.size());
    using Map = Eigen::Map<Eigen::ArrayXXd, 0, Stride>;
    Map P(p.data(), N, 3, strides(3)), dP(dp.data(), N, 3, strides(3)), ddP(ddp.data(), N, 3, strides(3));
    Map U(u.data(), N, n, strides(n)), dU(du.data(), N, n, strides(n)), ddU(ddu.data(), N, n, strides(n)),
        T(tau.data(), N, n, strides(n));
    for (Eigen::Index k = 0; k < N; ++k) {
        const Sample& s = f.samples[static_cast<std::size_t>(k) % f.samples.size()];
        for (int i = 0; i < 3; ++i) {
            P(k, poseColumn(order, i)) = s.p(i);
            dP(k, poseColumn(order, i)) = s.dp(i);
            ddP(k, poseColumn(order, i)) = s.ddp(i);
        }
    }
    if (!inverseDynamicsBatch(model, P, dP, ddP, U, dU, ddU, T, 1, order).ok()) {
        state.SkipWithError("the benchmark trajectory leaves the workspace");
        return;
    }
    for (auto _ : state) {
        const BatchResult result = inverseDynamicsBatch(model, P, dP, ddP, U, dU, ddU, T, 1, order);
        benchmark::DoNotOptimize(result);
        benchmark::DoNotOptimize(tau.data());
        benchmark::ClobberMemory();
    }
    perSample(state, static_cast<std::size_t>(N));
}

[[maybe_unused]] const bool registered = [] {
    for (const bool c_order : {false, true}) {
        const std::string layout = c_order ? "c_order" : "column_major";
        benchmark::RegisterBenchmark(("BM_PoseOrder/theta_x_y/" + layout).c_str(), [c_order](benchmark::State& s) {
            poseOrderBatch(s, PoseColumns::theta_x_y, c_order);
        })->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_PoseOrder/x_y_theta/" + layout).c_str(), [c_order](benchmark::State& s) {
            poseOrderBatch(s, PoseColumns::x_y_theta, c_order);
        })->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark("BM_InverseDynamics/paper-3prr/baseline", baseline);
    for (const std::string robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/nocdyn").c_str(),
                                     [robot](benchmark::State& s) { generalModel<true>(s, robot); });
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/nocdyn_full").c_str(),
                                     [robot](benchmark::State& s) { generalModel<false>(s, robot); });
    }
    for (const std::string robot : {"five-bar", "biglide"}) {
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/nocdyn").c_str(),
                                     [robot](benchmark::State& s) { toolModel<true>(s, robot); });
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/nocdyn_full").c_str(),
                                     [robot](benchmark::State& s) { toolModel<false>(s, robot); });
        benchmark::RegisterBenchmark(("BM_Batch/" + robot + "/nocdyn").c_str(),
                                     [robot](benchmark::State& s) { toolBatch(s, robot, BatchPackets::automatic); });
        benchmark::RegisterBenchmark(("BM_Batch/" + robot + "/nocdyn_4lanes").c_str(),
                                     [robot](benchmark::State& s) { toolBatch(s, robot, BatchPackets::four); });
    }
    for (const std::string robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        benchmark::RegisterBenchmark(("BM_Batch/" + robot + "/nocdyn").c_str(),
                                     [robot](benchmark::State& s) { generalBatch(s, robot, 1, 1); });
        benchmark::RegisterBenchmark(("BM_Batch/" + robot + "/nocdyn_4lanes").c_str(), [robot](benchmark::State& s) {
            generalBatch(s, robot, 1, 1, BatchPackets::four);
        });
        benchmark::RegisterBenchmark(
            ("BM_Batch/" + robot + "/nocdyn_100k").c_str(),
            [robot](benchmark::State& s) { generalBatch(s, robot, 100, static_cast<unsigned>(s.range(0))); })
            ->ArgName("threads")
            ->Arg(1)
            ->Arg(2)
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
