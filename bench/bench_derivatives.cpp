// Exact derivatives of the dynamics (derivatives.hpp) against the values they differentiate,
// per sample, in one run: BM_Derivatives/<robot>/<what> for the example robots paper-3prr,
// 3-rrr, 3-rpr and 4-rrr (redundant), what in
//   inverse_dynamics_fast    one inverse dynamics, the lean path (inverseDynamicsFast)
//   inverse_dynamics         one inverse dynamics, the full path (inverseDynamics)
//   inverse_derivatives      tau and d tau/d(p, dp, ddp) (inverseDynamicsDerivatives)
//   forward_dynamics         one forward dynamics (forwardDynamics, sim layer)
//   forward_derivatives      ddp and d ddp/d(p, dp, tau) (forwardDynamicsDerivatives)
//   actuator_derivatives     u, du, ddu and their derivatives (actuatorVariableDerivatives)
//   actuator_batch           the same over the cycle as one batch on one thread
//                            (actuatorVariableDerivativesBatch, outputs preallocated)
// over a cycle of 1000 samples of the paper's trajectory 1 plus a second harmonic per axis
// (the fixture of bench_robots.cpp), each reporting `per_sample`. bench/derivative_ratios.py
// prints the ratios of one JSON run: inverse_derivatives / inverse_dynamics(_fast),
// forward_derivatives / forward_dynamics and actuator_derivatives (and _batch) / inverse_dynamics.
#include <benchmark/benchmark.h>

#include <array>
#include <numbers>
#include <string>
#include <vector>

#include "nocdyn/derivatives.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::bench {
namespace {

struct Sample {
    Pose p, dp, ddp;
    ActuatorVector tau;
};

/// One period (0.1 s) of the benchmark trajectory at 10 kHz, and the forces of each sample.
std::vector<Sample> cycle(const Model& model) {
    constexpr double pi = std::numbers::pi;
    PoseTrajectory trajectory = paperTrajectory1();
    trajectory.theta.harmonics.push_back({1.0 * pi / 180.0, 30.0, 0.3});
    trajectory.x.harmonics.push_back({0.0005, 20.0, 1.0});
    trajectory.y.harmonics.push_back({0.0008, 30.0, -0.5});
    std::vector<Sample> samples(1000);
    Data data(model);
    for (std::size_t k = 0; k < samples.size(); ++k) {
        Sample& s = samples[k];
        trajectory.evaluate(static_cast<double>(k) * 1e-4, s.p, s.dp, s.ddp);
        s.p += model.home;  // around the robot's home pose
        if (!inverseDynamics(model, data, s.p, s.dp, s.ddp)) return {};
        s.tau = data.tau;
    }
    return samples;
}

enum class What { inverse_fast, inverse, inverse_derivatives, forward, forward_derivatives, actuator, actuator_batch };

void perSample(benchmark::State& state, std::size_t samples) {
    state.counters["per_sample"] = benchmark::Counter(
        static_cast<double>(samples), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// The cycle as one actuatorVariableDerivativesBatch on the calling thread, N x 3 inputs and
/// the outputs allocated once.
void runActuatorBatch(benchmark::State& state, const Model& model, const std::vector<Sample>& samples) {
    const auto N = static_cast<Eigen::Index>(samples.size());
    const int n = model.actuators;
    Eigen::ArrayXXd p(N, 3), dp(N, 3), ddp(N, 3);
    for (Eigen::Index k = 0; k < N; ++k) {
        p.row(k) = samples[static_cast<std::size_t>(k)].p.transpose();
        dp.row(k) = samples[static_cast<std::size_t>(k)].dp.transpose();
        ddp.row(k) = samples[static_cast<std::size_t>(k)].ddp.transpose();
    }
    std::array<Eigen::ArrayXXd, 3> values;
    std::array<Eigen::ArrayXXd, 6> jacobians;
    for (auto& v : values) v.resize(N, n);
    for (auto& j : jacobians) j.resize(N, 3 * n);
    auto& [u, du, ddu] = values;
    auto& [u_p, du_p, du_dp, ddu_p, ddu_dp, ddu_ddp] = jacobians;
    for (auto _ : state) {
        const BatchResult r = actuatorVariableDerivativesBatch(
            model, p, dp, ddp, {u, du, ddu, u_p, du_p, du_dp, ddu_p, ddu_dp, ddu_ddp}, 1);
        benchmark::DoNotOptimize(r);
        benchmark::DoNotOptimize(ddu_p.data());
        benchmark::ClobberMemory();
    }
    perSample(state, samples.size());
}

void run(benchmark::State& state, const std::string& robot, What what) {
    const Model model(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml"));
    const std::vector<Sample> samples = cycle(model);
    if (samples.empty()) {
        state.SkipWithError(("the benchmark trajectory leaves the workspace of " + robot).c_str());
        return;
    }
    Data data(model);
    InverseDynamicsDerivatives id;
    ForwardDynamicsDerivatives fd;
    ActuatorVariableDerivatives ad;
    if (what == What::actuator_batch) {
        runActuatorBatch(state, model, samples);
        return;
    }
    for (auto _ : state) {
        for (const Sample& s : samples) {
            Status status;
            switch (what) {
                case What::inverse_fast:
                    status = inverseDynamicsFast(model, data, s.p, s.dp, s.ddp);
                    benchmark::DoNotOptimize(data.tau.data());
                    break;
                case What::inverse:
                    status = inverseDynamics(model, data, s.p, s.dp, s.ddp);
                    benchmark::DoNotOptimize(data.tau.data());
                    break;
                case What::inverse_derivatives:
                    status = inverseDynamicsDerivatives(model, data, s.p, s.dp, s.ddp, id);
                    benchmark::DoNotOptimize(id.d_p.data());
                    break;
                case What::forward:
                    status = forwardDynamics(model, data, s.p, s.dp, s.tau);
                    benchmark::DoNotOptimize(data.t_M_dot.data());
                    break;
                case What::forward_derivatives:
                    status = forwardDynamicsDerivatives(model, data, s.p, s.dp, s.tau, fd);
                    benchmark::DoNotOptimize(fd.d_p.data());
                    break;
                case What::actuator:
                    status = actuatorVariableDerivatives(model, data, s.p, s.dp, s.ddp, ad);
                    benchmark::DoNotOptimize(ad.ddu_p.data());
                    break;
                case What::actuator_batch:
                    break;
            }
            benchmark::DoNotOptimize(status);
        }
        benchmark::ClobberMemory();
    }
    perSample(state, samples.size());
}

const bool registered = [] {
    const std::pair<const char*, What> whats[] = {{"inverse_dynamics_fast", What::inverse_fast},
                                                  {"inverse_dynamics", What::inverse},
                                                  {"inverse_derivatives", What::inverse_derivatives},
                                                  {"forward_dynamics", What::forward},
                                                  {"forward_derivatives", What::forward_derivatives},
                                                  {"actuator_derivatives", What::actuator},
                                                  {"actuator_batch", What::actuator_batch}};
    for (const char* robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        for (const auto& [name, what] : whats) {
            const std::string robot_name = robot;
            const What w = what;
            benchmark::RegisterBenchmark(("BM_Derivatives/" + robot_name + "/" + name).c_str(),
                                         [robot_name, w](benchmark::State& state) { run(state, robot_name, w); });
        }
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench

BENCHMARK_MAIN();
