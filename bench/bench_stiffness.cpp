// The platform's stiffness K and its natural frequencies per pose (analysis/stiffness.hpp),
// against one inverse dynamics (the full path) in the same run, on three robots with compliance:
//   BM_Stiffness/<robot>/inverse_dynamics   inverseDynamics at rest
//   BM_Stiffness/<robot>/stiffness          position, velocity and shaping stages, K
//   BM_Stiffness/<robot>/lumped_modes       the same and the lumped modes K v = w^2 M v
//   BM_Stiffness/<robot>/elastodynamic      the elastodynamic modes (allocates)
// over 100 poses about home; read the ratios to inverse_dynamics from one run.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/robot_file.hpp"

namespace nocdyn::bench {
namespace {

RobotDescription withCompliance(const std::string& robot) {
    RobotDescription d = io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml");
    for (LimbDescription& limb : d.limbs) {
        for (JointDescription& joint : limb.joints) {
            if (joint.actuated) joint.stiffness = joint.type == JointType::prismatic ? 2.0e5 : 20.0;
        }
        if (robot == "3-rrr") {
            for (BodyDescription& body : limb.bodies) body.elastic = ElasticBeam{2.8e6, 23.3};
        }
    }
    return d;
}

enum class What { inverse_dynamics, stiffness, lumped_modes, elastodynamic };

void run(benchmark::State& state, const std::string& robot, What what) {
    const Model model(withCompliance(robot));
    const StiffnessModel compliance(model);
    Data data(model);
    StiffnessData K;
    LumpedModes modes;
    ElastodynamicModes elastic;
    std::vector<Pose> poses;
    for (int k = 0; k < 100; ++k) {
        const double s = 0.0628 * k;
        poses.push_back(model.home + Pose(0.02 * std::sin(s), 0.002 * std::cos(s), 0.002 * std::sin(2 * s)));
    }
    for (auto _ : state) {
        for (const Pose& p : poses) {
            Status status;
            switch (what) {
                case What::inverse_dynamics:
                    status = inverseDynamics(model, data, p, Twist::Zero(), Twist::Zero());
                    break;
                case What::stiffness:
                    status = inverseDisplacement(model, data, p);
                    if (status) status = cartesianStiffness(model, compliance, data, K);
                    break;
                case What::lumped_modes:
                    status = stiffnessAndModes(model, compliance, data, p, K, modes);
                    break;
                case What::elastodynamic:
                    status = inverseDisplacement(model, data, p);
                    if (status) status = velocityFromPlatformTwist(model, data, Twist::Zero());
                    if (status) status = elastodynamicModes(model, compliance, data, elastic);
                    break;
            }
            if (!status) {
                state.SkipWithError(("a pose out of reach of " + robot).c_str());
                return;
            }
            benchmark::DoNotOptimize(K.K.data());
            benchmark::DoNotOptimize(modes.frequency.data());
        }
        benchmark::ClobberMemory();
    }
    state.counters["per_pose"] = benchmark::Counter(
        static_cast<double>(poses.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

const bool kRegistered = [] {
    for (const char* robot : {"paper-3prr-general", "3-rpr", "3-rrr"}) {
        for (const auto& [name, what] :
             {std::pair{"inverse_dynamics", What::inverse_dynamics}, std::pair{"stiffness", What::stiffness},
              std::pair{"lumped_modes", What::lumped_modes}, std::pair{"elastodynamic", What::elastodynamic}}) {
            benchmark::RegisterBenchmark(
                (std::string("BM_Stiffness/") + robot + "/" + name).c_str(),
                [robot = std::string(robot), what = what](benchmark::State& s) { run(s, robot, what); });
        }
    }
    return true;
}();

}  // namespace
}  // namespace nocdyn::bench
