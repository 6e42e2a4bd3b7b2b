// Writing results: the streaming CSV writer (shortest round-trip numbers, std::to_chars) and
// the whole streaming inverse dynamics of `nocdyn inverse-dynamics` (sample, check, format,
// write), both into /dev/null through io::OutputFile so that no disk time is counted.
#include <benchmark/benchmark.h>

#include <vector>
#include <cstddef>

#include "fixture.hpp"
#include "nocdyn/io/short_form.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/output.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/analysis/sampling.hpp"

namespace nocdyn::bench {
namespace {

/// Rows of 17 numbers (the inverse-dynamics columns) from the fixture's cycle, formatted and
/// written; items/s = rows per second.
void BM_WriteCsv(benchmark::State& state) {
    const Fixture& f = fixture();
    std::vector<std::vector<double>> rows;
    for (const Sample& s : f.samples) {
        InverseDynamicsSample sample;
        sample.t = s.t;
        sample.p = s.p;
        prr3::Data data;
        (void)prr3::inverseDynamics(f.model, data, s.p, s.dp, s.ddp);
        sample.u = data.u;
        sample.du = data.du;
        sample.ddu = data.ddu;
        sample.tau = data.tau;
        sample.kinetic = prr3::kineticEnergy(f.model, data);
        tables::inverseDynamicsRow(sample, rows.emplace_back());
    }
    io::OutputFile out("/dev/null");
    io::CsvWriter csv(out, tables::inverseDynamicsColumns(3));
    for (auto _ : state) {
        for (const auto& row : rows) csv.row(row);
    }
    csv.finish();
    out.commit();
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * rows.size()));
}
BENCHMARK(BM_WriteCsv)->Unit(benchmark::kMillisecond);

/// `nocdyn inverse-dynamics --trajectory paper1 --duration D --rate 1e6 -o /dev/null` without
/// the process, on the general model of the paper's robot as the command runs it: D = samples
/// / 1e6 s; items/s = samples per second. Second argument: 1 = formatting on a second thread
/// (as the command does), 0 = on the calling thread.
void BM_StreamInverseDynamics(benchmark::State& state) {
    const Model model{io::expand(io::RobotParameters{})};
    const PoseTrajectory trajectory = paperTrajectory1();
    const auto samples = static_cast<std::size_t>(state.range(0));
    const SampleGrid grid{1e6, samples};
    std::vector<double> row;
    for (auto _ : state) {
        io::OutputFile out("/dev/null");
        io::CsvWriter csv(out, tables::inverseDynamicsColumns(model.actuators), state.range(1) != 0);
        const auto summary = streamInverseDynamics(model, trajectory, grid, LimitPolicy::error,
                                                   [&](const InverseDynamicsSample& sample) {
                                                       tables::inverseDynamicsRow(sample, row);
                                                       csv.row(row);
                                                   });
        csv.finish();
        out.commit();
        benchmark::DoNotOptimize(summary.peak_tau);
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * samples));
}
BENCHMARK(BM_StreamInverseDynamics)
    ->Args({1000000, 0})
    ->Args({1000000, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace nocdyn::bench
BENCHMARK_MAIN();
