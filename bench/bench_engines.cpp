// BM_InverseDynamics/<robot>/{mujoco,simbody}: the independent engines' general models of the
// example robots on the same cycle of samples as BM_InverseDynamics/<robot>/nocdyn
// (bench_robots.cpp). Neither engine has a per-sample inverse-dynamics entry for a closed
// loop: each call covers the cycle, assembling every sample from the previous one, and
// `per_sample` is the time per sample. The two-DOF five-bar and biglide run their own tool
// cycle (fixture.hpp, ToolCycle), as BM_InverseDynamics/<robot>/nocdyn does.
// BM_Simulate/<robot>/simbody: the Simbody plant (SimbodyMechanism::advance, accuracy 1e-10)
// under the forces of BM_Simulate/<robot>/nocdyn (bench_simulate.cpp), held for 1 ms each.
// BM_Simulate/<robot>/mujoco: MuJoCo's plant (MujocoMechanism::advance: mj_step at 0.1 ms,
// soft loop closures) under the same forces. Both report `end_error_um`: the largest
// difference of the final x, y [um] (theta [urad]) from nocdyn's forward dynamics at tight
// tolerances, and MuJoCo `loop_error_um`, its final loop-closure error.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

#include "fixture.hpp"
#include "simulate_fixture.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/validation/mujoco_mechanism.hpp"
#include "nocdyn/validation/mujoco_spatial.hpp"
#include "nocdyn/validation/simbody_spatial.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"
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

/// The engines on a two-DOF robot's tool cycle (ToolCycle), as BM_InverseDynamics/<robot>/nocdyn.
template <typename Engine>
void toolEngine(benchmark::State& state, const std::string& robot) {
    const RobotDescription description =
        io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml");
    const ToolCycle cycle(Model(description).home);
    Engine mechanism(description);
    for (auto _ : state) {
        auto out = mechanism.inverseDynamics(cycle.trajectory, cycle.times);
        benchmark::DoNotOptimize(out.data());
    }
    state.counters["per_sample"] =
        benchmark::Counter(static_cast<double>(cycle.times.size()),
                           benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// nocdyn's final pose under the fixture's held forces, at tolerances far below the engines'.
Pose referenceEndPose(const SimulateFixture& f) {
    const Model model(f.robot);
    SimulatorOptions options;
    options.atol = 1e-14;
    options.rtol = 1e-13;
    Simulator simulator(model, options);
    if (!simulator.reset(f.p0, f.dp0)) throw std::runtime_error("reference simulation: reset failed");
    for (const ActuatorVector& tau : f.tau) {
        if (!simulator.advance(kHoldPeriod, tau)) throw std::runtime_error("reference simulation failed");
    }
    return simulator.pose();
}

/// max(|dx|, |dy|, |dtheta|) of a final pose from the reference, in um (urad).
double endErrorMicro(const Eigen::Vector3d& p, const Pose& reference) {
    return 1e6 * (p - reference).cwiseAbs().maxCoeff();
}

void mujocoPlant(benchmark::State& state, const std::string& name) {
    const SimulateFixture f(name);
    validation::MujocoMechanism plant(f.robot);
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
    state.counters["steps"] = static_cast<double>(steps) / static_cast<double>(std::max<long>(1, state.iterations()));
    state.counters["end_error_um"] = endErrorMicro(plant.pose(), referenceEndPose(f));
    state.counters["loop_error_um"] = 1e6 * plant.loopError();
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
    state.counters["end_error_um"] = endErrorMicro(plant.pose(), referenceEndPose(f));
}

/// A spatial robot's cycle: 1000 samples over one 0.1 s period about home, two harmonics per
/// coordinate (1-2 cm, 0.02-0.04 rad), as ToolCycle for the planar tool robots.
struct SpatialCycle {
    std::vector<Eigen::VectorXd> p, dp, ddp;
    explicit SpatialCycle(const spatial::Model& model) {
        const int d = model.task_dimension;
        for (int k = 0; k < 1000; ++k) {
            const double t = 1e-4 * k;
            Eigen::VectorXd x = model.home, v = Eigen::VectorXd::Zero(d), a = Eigen::VectorXd::Zero(d);
            for (int i = 0; i < d; ++i) {
                const double amplitude = i < 3 ? 0.01 + 0.003 * i : 0.02 + 0.005 * (i - 3);
                for (const double f : {10.0 + i, 20.0 + 2.0 * i}) {
                    const double w = 2.0 * M_PI * f, phase = 0.3 * i;
                    x(i) += amplitude * std::sin(w * t + phase) / (f / 10.0);
                    v(i) += amplitude * w * std::cos(w * t + phase) / (f / 10.0);
                    a(i) -= amplitude * w * w * std::sin(w * t + phase) / (f / 10.0);
                }
            }
            p.push_back(x);
            dp.push_back(v);
            ddp.push_back(a);
        }
    }
};

/// BM_InverseDynamics/<spatial robot>/nocdyn: nocdyn::spatial::inverseDynamics per sample;
/// /simbody and /mujoco: the independent engines' models on the same samples (each call the
/// whole cycle, every sample assembled from the previous one; `per_sample` per sample).
void spatialNocdyn(benchmark::State& state, const std::string& robot) {
    const spatial::Model model(
        io::loadSpatialRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
    const SpatialCycle cycle(model);
    spatial::Data data(model);
    for (auto _ : state) {
        for (std::size_t k = 0; k < cycle.p.size(); ++k) {
            const Status status = spatial::inverseDynamics(model, data, cycle.p[k], cycle.dp[k], cycle.ddp[k]);
            if (!status) {
                state.SkipWithError(("the cycle leaves the workspace of " + robot).c_str());
                return;
            }
            benchmark::DoNotOptimize(data.tau.data());
        }
        benchmark::ClobberMemory();
    }
    state.counters["per_sample"] =
        benchmark::Counter(static_cast<double>(cycle.p.size()),
                           benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// BM_ForwardDynamics/<spatial robot>/nocdyn: nocdyn::spatial::forwardDynamics per sample, from the
/// forces that the inverse dynamics gives on the same cycle (the simulators' right-hand side).
void spatialForwardNocdyn(benchmark::State& state, const std::string& robot) {
    const spatial::Model model(
        io::loadSpatialRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
    const SpatialCycle cycle(model);
    spatial::Data data(model);
    std::vector<spatial::ActuatorVector> tau;
    for (std::size_t k = 0; k < cycle.p.size(); ++k) {
        if (!spatial::inverseDynamics(model, data, cycle.p[k], cycle.dp[k], cycle.ddp[k])) {
            state.SkipWithError(("the cycle leaves the workspace of " + robot).c_str());
            return;
        }
        tau.push_back(data.tau);
    }
    spatial::TaskVector ddp(model.task_dimension);
    for (auto _ : state) {
        for (std::size_t k = 0; k < cycle.p.size(); ++k) {
            if (!spatial::forwardDynamics(model, data, cycle.p[k], cycle.dp[k], tau[k], ddp)) {
                state.SkipWithError(("the forward dynamics failed on " + robot).c_str());
                return;
            }
            benchmark::DoNotOptimize(ddp.data());
        }
        benchmark::ClobberMemory();
    }
    state.counters["per_sample"] =
        benchmark::Counter(static_cast<double>(cycle.p.size()),
                           benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <typename Engine>
void spatialEngine(benchmark::State& state, const std::string& robot) {
    const SpatialRobotDescription description =
        io::loadSpatialRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml");
    const SpatialCycle cycle{spatial::Model(description)};
    Engine mechanism(description);
    for (auto _ : state) {
        try {
            const Eigen::MatrixXd tau = mechanism.actuatorForces(cycle.p, cycle.dp, cycle.ddp);
            benchmark::DoNotOptimize(tau.data());
        } catch (const Error& e) {
            state.SkipWithError(e.what());  // the other benchmarks still run
            return;
        }
    }
    state.counters["per_sample"] =
        benchmark::Counter(static_cast<double>(cycle.p.size()),
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
        benchmark::RegisterBenchmark(("BM_Simulate/" + robot + "/simbody").c_str(), [robot](benchmark::State& s) {
            simbodyPlant(s, robot);
        })->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_Simulate/" + robot + "/mujoco").c_str(), [robot](benchmark::State& s) {
            mujocoPlant(s, robot);
        })->Unit(benchmark::kMillisecond);
    }
    for (const std::string robot : {"delta", "stewart", "hexa-6rus"}) {
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/nocdyn").c_str(),
                                     [robot](benchmark::State& s) { spatialNocdyn(s, robot); });
        benchmark::RegisterBenchmark(("BM_ForwardDynamics/" + robot + "/nocdyn").c_str(),
                                     [robot](benchmark::State& s) { spatialForwardNocdyn(s, robot); });
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/simbody").c_str(), [robot](
                                                                                               benchmark::State& s) {
            spatialEngine<validation::SimbodySpatialMechanism>(s, robot);
        })->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/mujoco").c_str(), [robot](benchmark::State& s) {
            spatialEngine<validation::MujocoSpatialMechanism>(s, robot);
        })->Unit(benchmark::kMillisecond);
    }
    for (const std::string robot : {"five-bar", "biglide"}) {
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/mujoco").c_str(), [robot](benchmark::State& s) {
            toolEngine<validation::MujocoMechanism>(s, robot);
        })->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark(("BM_InverseDynamics/" + robot + "/simbody").c_str(), [robot](
                                                                                               benchmark::State& s) {
            toolEngine<validation::SimbodyMechanism>(s, robot);
        })->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
