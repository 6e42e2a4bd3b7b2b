// The paper's trajectories against the independent golden values in tests/data/golden
// (virtual power with 50-digit finite differences, no NOC).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/trajectory.hpp"
#include "golden.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

class GoldenTrajectory : public ::testing::TestWithParam<GoldenCase> {};

/// The lean path equals the full path to rounding: 1e-12 of (1 + |value|).
constexpr double kLeanEqualsFull = 1e-12;

// The general model of the paper's robot file (either form), on its full and lean paths.
TEST_P(GoldenTrajectory, ReproducesGoldenJointMotionForcesAndEnergyTo1e9RelativeOnBothPaths) {
    const Model model(io::exampleRobot(GetParam().robot));
    Data full(model), lean(model);
    compareWithGolden(GetParam(), [&](const Pose& p, const Twist& dp, const Twist& ddp) {
        solve(model, full, p, dp, ddp);
        const Status fast = inverseDynamicsFast(model, lean, p, dp, ddp);
        EXPECT_TRUE(fast.ok()) << describeCase(model, p) << ": " << describe(fast, model);
        for (int a = 0; a < 3; ++a) {
            SCOPED_TRACE(describeCase(model, p) + ", actuator " + std::to_string(a + 1));
            EXPECT_NEAR(lean.u(a), full.u(a), kLeanEqualsFull * (1.0 + std::abs(full.u(a))));
            EXPECT_NEAR(lean.du(a), full.du(a), kLeanEqualsFull * (1.0 + std::abs(full.du(a))));
            EXPECT_NEAR(lean.ddu(a), full.ddu(a), kLeanEqualsFull * (1.0 + std::abs(full.ddu(a))));
            EXPECT_NEAR(lean.tau(a), full.tau(a), kLeanEqualsFull * (1.0 + std::abs(full.tau(a))));
        }
        return Evaluation{full.u(0),
                          full.u(1),
                          full.u(2),
                          full.du(0),
                          full.du(1),
                          full.du(2),
                          full.ddu(0),
                          full.ddu(1),
                          full.ddu(2),
                          full.tau(0),
                          full.tau(1),
                          full.tau(2),
                          kineticEnergy(model, full)};
    });
}

INSTANTIATE_TEST_SUITE_P(Paper, GoldenTrajectory,
                         ::testing::Values(GoldenCase{"paper_trajectory1.csv", &paperTrajectory1, "paper-3prr"},
                                           GoldenCase{"paper_trajectory2.csv", &paperTrajectory2, "paper-3prr"},
                                           GoldenCase{"paper_trajectory1.csv", &paperTrajectory1, "paper-3prr-general"},
                                           GoldenCase{"paper_trajectory2.csv", &paperTrajectory2,
                                                      "paper-3prr-general"}),
                         [](const auto& info) {
                             std::string name = std::string(info.param.file).substr(0, 17) + "_" + info.param.robot;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace nocdyn::test
