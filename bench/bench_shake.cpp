// Recorded motion: fitting the 31 s El Centro record to the paper's prototype (high-pass,
// integration, choice of the time scale) and the inverse-dynamics feed-forward of the fitted
// motion at 10 kHz.
#include <benchmark/benchmark.h>

#include <string>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/shake.hpp"

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
