// Identification of a payload from a 10 kHz log of 5 s: the
// platform motion from the actuator positions (tracker and rates), the stacked regressor and the
// weighted least squares. Two logs: with du, ddu columns (used as given) and without (u and tau
// filtered at zero phase, u differentiated), as a real logger writes it. Reported per run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/spatial_payload.hpp"

namespace {

constexpr double kRate = 1e4;      // [Hz]
constexpr double kDuration = 5.0;  // [s]

/// The loaded robot's exact log along a two-frequency motion about home.
nocdyn::Measurements exactLog(const nocdyn::RobotDescription& robot, bool rates) {
    const nocdyn::Model loaded(nocdyn::withPayload(robot, nocdyn::Payload{0.5, 8e-4, nocdyn::Vector2(0.012, -0.007)}));
    nocdyn::PoseTrajectory trajectory;
    trajectory.theta = {loaded.home(0), {{0.03, 1.0, 0.0}, {0.02, 3.0, 0.4}}};
    trajectory.x = {loaded.home(1), {{0.003, 2.0, 0.3}, {0.001, 5.0, 1.0}}};
    trajectory.y = {loaded.home(2), {{0.003, 1.0, 1.2}, {0.001, 4.0, 0.2}}};
    const auto N = static_cast<Eigen::Index>(kRate * kDuration);
    nocdyn::Measurements m;
    m.u.resize(N, loaded.actuators);
    m.tau.resize(N, loaded.actuators);
    if (rates) {
        m.du.resize(N, loaded.actuators);
        m.ddu.resize(N, loaded.actuators);
    }
    nocdyn::Data data(loaded);
    for (Eigen::Index k = 0; k < N; ++k) {
        nocdyn::Pose p, dp, ddp;
        m.t.push_back(static_cast<double>(k) / kRate);
        trajectory.evaluate(m.t.back(), p, dp, ddp);
        (void)nocdyn::inverseDynamics(loaded, data, p, dp, ddp);
        m.u.row(k) = data.u.transpose();
        m.tau.row(k) = data.tau.transpose();
        if (rates) {
            m.du.row(k) = data.du.transpose();
            m.ddu.row(k) = data.ddu.transpose();
        }
    }
    return m;
}

void BM_Identify(benchmark::State& state) {
    const bool rates = state.range(0) != 0;
    const nocdyn::RobotDescription robot = nocdyn::io::exampleRobot("paper-3prr-general");
    const nocdyn::Model model(robot);
    const nocdyn::Measurements log = exactLog(robot, rates);
    nocdyn::PayloadResult result;
    for (auto _ : state) {
        const nocdyn::Motion motion = nocdyn::reconstructMotion(model, log);
        result = nocdyn::identifyPayload(model, motion);
        benchmark::DoNotOptimize(result.mass);
    }
    state.counters["samples"] = static_cast<double>(log.t.size());
    state.counters["mass_kg"] = result.mass;
    state.counters["inertia_kg_m2"] = result.inertia;
    state.SetLabel(rates ? "paper-3prr, 5 s at 10 kHz, du and ddu given" : "paper-3prr, 5 s at 10 kHz, u filtered");
}
BENCHMARK(BM_Identify)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

nocdyn::SpatialRobotDescription stewart() {
    std::string path = NOCDYN_SOURCE_DIR;
    path.append("/robots/stewart.yaml");
    return nocdyn::io::loadSpatialRobotDescription(path);
}

/// One sample of the hexapod payload's regressor: inverse dynamics of the robot alone and Y (6 x 10).
void BM_SpatialPayloadRegressor(benchmark::State& state) {
    using namespace nocdyn::spatial;
    const Model model(stewart());
    Data data(model);
    PayloadRegressor Y(model.actuators, kPayloadParameters);
    TaskVector p = model.home, dp = TaskVector::Zero(6), ddp = TaskVector::Zero(6);
    p(3) = 0.02;
    dp << 0.1, -0.05, 0.2, 0.3, -0.2, 0.1;
    ddp << 1.0, 2.0, -1.0, 3.0, 1.0, -2.0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(payloadRegressor(model, data, p, dp, ddp, Y));
        benchmark::DoNotOptimize(Y.data());
    }
}
BENCHMARK(BM_SpatialPayloadRegressor);

/// The least squares of a 2 s, 1 kHz log of the shake command's excitation (2000 samples, 12000 rows).
void BM_SpatialPayloadFit(benchmark::State& state) {
    using namespace nocdyn::spatial;
    const nocdyn::SpatialRobotDescription d = stewart();
    SpatialPayload specimen;
    specimen.mass = 0.5;
    const Model alone(d), carrying(withPayload(d, specimen));
    PayloadExcitationOptions o;
    o.loop.simulator.atol = 1e-9;
    o.loop.simulator.rtol = 1e-7;
    o.loop.simulator.floor_step = 5e-5;
    const PayloadLog log = excitePayload(carrying, alone, payloadExcitation(carrying, o), o);
    for (auto _ : state) benchmark::DoNotOptimize(identifySpatialPayload(alone, log));
}
BENCHMARK(BM_SpatialPayloadFit)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
