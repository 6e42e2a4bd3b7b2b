// Joint reactions (reactions.hpp) against the inverse dynamics alone, per sample, on every
// example robot along the paper's trajectory 1 about its home: BM_Reactions/<robot>/lean
// (inverseDynamicsFast), /full (inverseDynamics) and /with_reactions
// (inverseDynamicsWithReactions). The goal is with_reactions <= 2x lean, read from one run.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::bench {
namespace {

struct Motion {
    std::vector<Pose> p, dp, ddp;
};

/// 1000 samples of trajectory 1 (eq. 33) over one period, about the robot's home.
Motion motionOf(const Model& model) {
    const PoseTrajectory trajectory = paperTrajectory1();
    Motion m;
    for (int k = 0; k < 1000; ++k) {
        Pose p, dp, ddp;
        trajectory.evaluate(1e-4 * k, p, dp, ddp);
        m.p.push_back(p + model.home);
        m.dp.push_back(dp);
        m.ddp.push_back(ddp);
    }
    return m;
}

enum class Path { lean, full, with_reactions };

void run(benchmark::State& state, const std::string& robot, Path path) {
    const Model model(io::exampleRobot(robot));
    const Motion m = motionOf(model);
    Data data(model);
    Reactions reactions;
    for (std::size_t k = 0; k < m.p.size(); ++k) {
        if (!inverseDynamics(model, data, m.p[k], m.dp[k], m.ddp[k])) {
            state.SkipWithError(("trajectory 1 leaves the workspace of " + robot).c_str());
            return;
        }
    }
    for (auto _ : state) {
        for (std::size_t k = 0; k < m.p.size(); ++k) {
            Status status;
            switch (path) {
                case Path::lean:
                    status = inverseDynamicsFast(model, data, m.p[k], m.dp[k], m.ddp[k]);
                    break;
                case Path::full:
                    status = inverseDynamics(model, data, m.p[k], m.dp[k], m.ddp[k]);
                    break;
                case Path::with_reactions:
                    status = inverseDynamicsWithReactions(model, data, m.p[k], m.dp[k], m.ddp[k], reactions);
                    benchmark::DoNotOptimize(reactions.joint.data());
                    break;
            }
            benchmark::DoNotOptimize(status);
            benchmark::DoNotOptimize(data.tau.data());
        }
        benchmark::ClobberMemory();
    }
    state.counters["per_sample"] = benchmark::Counter(
        static_cast<double>(m.p.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

const bool kRegistered = [] {
    for (const char* robot : {"paper-3prr-general", "3-rrr", "3-rpr", "4-rrr"}) {
        for (const auto& [name, path] : {std::pair{"lean", Path::lean}, std::pair{"full", Path::full},
                                         std::pair{"with_reactions", Path::with_reactions}}) {
            benchmark::RegisterBenchmark(
                (std::string("BM_Reactions/") + robot + "/" + name).c_str(),
                [robot = std::string(robot), path = path](benchmark::State& s) { run(s, robot, path); });
        }
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
