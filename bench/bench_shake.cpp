// Recorded motion: fitting the 31 s El Centro record to the paper's prototype (high-pass,
// integration, choice of the time scale) and the inverse-dynamics feed-forward of the fitted
// motion at 10 kHz.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/sim/shake.hpp"
#include "nocdyn/sim/shake_control.hpp"
#ifdef NOCDYN_HAS_ENGINES
#include "nocdyn/validation/simbody_plant.hpp"
#endif

namespace {

nocdyn::GroundRecord elCentro() {
    const nocdyn::io::GroundMotionRecord r =
        nocdyn::io::readAt2File(std::string(NOCDYN_SOURCE_DIR) + "/data/elcentro_1940_ns.AT2");
    nocdyn::GroundRecord g;
    g.dt = r.dt;
    g.ax = r.acceleration;
    return g;
}

void BM_ShakeFitAndFeedForward(benchmark::State& state) {
    const nocdyn::Model model(nocdyn::io::exampleRobot("paper-3prr-general"));
    const nocdyn::GroundRecord record = elCentro();
    nocdyn::Data data(model);
    for (auto _ : state) {
        const nocdyn::FittedRecord fit = nocdyn::fitRecord(model, record, nocdyn::FitOptions{});
        // feed-forward: tau along the fitted motion at 10 kHz
        nocdyn::Pose p, dp, ddp;
        double sum = 0.0;
        const auto ticks = static_cast<long>(fit.t.back() * 1e4);
        for (long k = 0; k <= ticks; ++k) {
            fit.trajectory.evaluate(static_cast<double>(k) * 1e-4, p, dp, ddp);
            (void)nocdyn::inverseDynamicsFast(model, data, p, dp, ddp);
            sum += data.tau(0);
        }
        benchmark::DoNotOptimize(sum);
        state.counters["time_scale"] = fit.time_scale;
        state.counters["ticks"] = static_cast<double>(ticks + 1);
    }
}
BENCHMARK(BM_ShakeFitAndFeedForward)->Unit(benchmark::kMillisecond);

}  // namespace

// The closed loop of `nocdyn shake` (computed torque at 10 kHz, f_n = 30 Hz, 0.5 kg payload on
// the plant only, pose noise 1 um, rate noise 10 um/s) over the first 20 ms of the fitted El
// Centro replay, on nocdyn's plant and on the Simbody plant (accuracy 1e-10).
// simulated_per_cpu_s: seconds of motion per CPU second (the goal is 10, i.e. 10x real time).
namespace {

constexpr double kLoopSeconds = 0.02;

/// The plant `which` ("simbody", "nocdyn_rk4", else "nocdyn") of the prototype carrying 0.5 kg.
std::unique_ptr<nocdyn::RobotPlant> loadedPlant(const nocdyn::RobotDescription& robot, const std::string& which) {
    const nocdyn::RobotDescription loaded = nocdyn::withPayload(robot, {0.5, 0.0, nocdyn::Vector2::Zero()});
#ifdef NOCDYN_HAS_ENGINES
    if (which == "simbody") return std::make_unique<nocdyn::validation::SimbodyPlant>(loaded);
#endif
    if (which == "nocdyn_rk4") return std::make_unique<nocdyn::RungeKuttaRobotPlant>(nocdyn::Model(loaded));
    return std::make_unique<nocdyn::SimulatorRobotPlant>(nocdyn::Model(loaded));
}

void BM_ShakeClosedLoop(benchmark::State& state, const std::string& which) {
    const nocdyn::RobotDescription robot = nocdyn::io::exampleRobot("paper-3prr-general");
    const nocdyn::Model model(robot);
    const nocdyn::FittedRecord fit = nocdyn::fitRecord(model, elCentro(), nocdyn::FitOptions{});
    const std::unique_ptr<nocdyn::RobotPlant> plant = loadedPlant(robot, which);
    nocdyn::PoseController controller(model, nocdyn::ControlLaw::computed_torque, nocdyn::taskCriticallyDamped(30.0));
    nocdyn::PoseLoopOptions options;
    options.rate = 1e4;
    options.duration = kLoopSeconds;
    options.noise_angle = options.noise_position = 1e-6;
    options.noise_rate = 1e-5;
    for (auto _ : state) {
        const nocdyn::PoseLoopResult result = nocdyn::runPoseLoop(controller, *plant, fit.trajectory, options);
        benchmark::DoNotOptimize(result.p.back());
    }
    state.counters["simulated_per_cpu_s"] =
        benchmark::Counter(kLoopSeconds, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK_CAPTURE(BM_ShakeClosedLoop, nocdyn, std::string("nocdyn"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ShakeClosedLoop, nocdyn_rk4, std::string("nocdyn_rk4"))->Unit(benchmark::kMillisecond);
#ifdef NOCDYN_HAS_ENGINES
BENCHMARK_CAPTURE(BM_ShakeClosedLoop, simbody, std::string("simbody"))->Unit(benchmark::kMillisecond);
#endif

// The shake-table controller of `nocdyn shake` (the default --controller table: 1 um encoders
// through the direct-kinematics tracker, ADXL355 accelerometers, the Kalman estimator, f_n = 6
// Hz, no acceleration correction) at 10 kHz over the same 20 ms, 0.5 kg payload on the
// plant only. simulated_per_cpu_s: seconds of motion per CPU second (goal: 10).
namespace {

void BM_ShakeTableLoop(benchmark::State& state, const std::string& which) {
    const nocdyn::RobotDescription robot = nocdyn::io::exampleRobot("paper-3prr-general");
    const nocdyn::Model model(robot);
    const nocdyn::FittedRecord fit = nocdyn::fitRecord(model, elCentro(), nocdyn::FitOptions{});
    const std::unique_ptr<nocdyn::RobotPlant> plant = loadedPlant(robot, which);
    nocdyn::ShakeLoopOptions options;
    options.rate = 1e4;
    options.duration = kLoopSeconds;
    for (auto _ : state) {
        const nocdyn::PoseLoopResult result = nocdyn::runShakeLoop(model, *plant, fit.trajectory, options);
        benchmark::DoNotOptimize(result.p.back());
    }
    state.counters["simulated_per_cpu_s"] =
        benchmark::Counter(kLoopSeconds, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK_CAPTURE(BM_ShakeTableLoop, nocdyn, std::string("nocdyn"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ShakeTableLoop, nocdyn_rk4, std::string("nocdyn_rk4"))->Unit(benchmark::kMillisecond);
#ifdef NOCDYN_HAS_ENGINES
BENCHMARK_CAPTURE(BM_ShakeTableLoop, simbody, std::string("simbody"))->Unit(benchmark::kMillisecond);
#endif
