// The frozen 3-PRR kernel on the paper's trajectories against the independent golden values in
// ../shared/golden (virtual power with 50-digit finite differences, no NOC), as the general
// model is checked by tests/golden_test.cpp.
#include <gtest/gtest.h>

#include <string>

#include "baseline_support.hpp"
#include "golden.hpp"

namespace nocdyn::test {
namespace {

class BaselineGolden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(BaselineGolden, ReproducesGoldenJointMotionForcesAndEnergyTo1e9Relative) {
    const prr3::Model model;
    prr3::Data data;
    compareWithGolden(GetParam(), [&](const Pose& p, const Twist& dp, const Twist& ddp) {
        solve(model, data, p, dp, ddp);
        return Evaluation{data.u(0),
                          data.u(1),
                          data.u(2),
                          data.du(0),
                          data.du(1),
                          data.du(2),
                          data.ddu(0),
                          data.ddu(1),
                          data.ddu(2),
                          data.tau(0),
                          data.tau(1),
                          data.tau(2),
                          prr3::kineticEnergy(model, data)};
    });
}

INSTANTIATE_TEST_SUITE_P(Paper, BaselineGolden,
                         ::testing::Values(GoldenCase{"paper_trajectory1.csv", &paperTrajectory1, "baseline"},
                                           GoldenCase{"paper_trajectory2.csv", &paperTrajectory2, "baseline"}),
                         [](const auto& info) { return std::string(info.param.file).substr(0, 17); });

}  // namespace
}  // namespace nocdyn::test
