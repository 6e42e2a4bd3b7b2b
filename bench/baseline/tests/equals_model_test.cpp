// The benchmarks' ratio of the model (nocdyn::Model) to the frozen 3-PRR kernel is only honest if both
// compute the same thing: on the paper's robot (either form of its file) they agree sample by
// sample on u, du, ddu, tau, I, C, every T_i and dT_i across the workspace.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "baseline_support.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn::test {
namespace {

/// Agreement asked of the two formulations: rounding, relative to each quantity's scale. The
/// forces (what the benchmarks time) to 1e-12 of the sample's largest |tau_j|; the matrices the
/// two compute differently (T_i, dT_i, I, C) to 1e-10.
constexpr double kForceRoundOff = 1e-12;
constexpr double kRoundOff = 1e-10;
constexpr int kPoses = 300;

class EqualsTheModel : public ::testing::TestWithParam<std::string> {};

TEST_P(EqualsTheModel, AtRandomWorkspacePosesUpToRounding) {
    const prr3::Model special;
    const Model model(io::exampleRobot(GetParam()));
    ASSERT_EQ(model.bodies, prr3::kBodies);
    prr3::Data a;
    Data b(model);
    BaselineSampler sampler(special, 11);
    double worst_tau = 0.0;
    int checked = 0;
    for (int n = 0; n < kPoses; ++n) {
        const Pose p = sampler.next();
        const Twist dp = sampler.twist(), ddp = 100.0 * sampler.twist();
        SCOPED_TRACE(GetParam() + ", " + describePose(p));
        ASSERT_TRUE(prr3::inverseDynamics(special, a, p, dp, ddp).ok());
        const Status status = inverseDynamics(model, b, p, dp, ddp);
        ASSERT_TRUE(status.ok()) << describe(status, model);
        const double tau_scale = a.tau.cwiseAbs().maxCoeff();
        for (int j = 0; j < 3; ++j) {
            SCOPED_TRACE("limb " + std::to_string(j + 1));
            EXPECT_NEAR(b.u(j), a.u(j), 1e-15);
            EXPECT_NEAR(b.du(j), a.du(j), kForceRoundOff * (1.0 + std::abs(a.du(j))));
            EXPECT_NEAR(b.ddu(j), a.ddu(j), kForceRoundOff * (1.0 + std::abs(a.ddu(j))));
            EXPECT_NEAR(b.tau(j), a.tau(j), kForceRoundOff * tau_scale);
            worst_tau = std::max(worst_tau, std::abs(b.tau(j) - a.tau(j)) / tau_scale);
        }
        EXPECT_LT((b.I - a.I).cwiseAbs().maxCoeff(), kRoundOff * a.I.cwiseAbs().maxCoeff());
        EXPECT_LT((b.C - a.C).cwiseAbs().maxCoeff(), kRoundOff * (1.0 + a.C.cwiseAbs().maxCoeff()));
        for (int i = 0; i < prr3::kBodies; ++i) {
            const auto ii = static_cast<std::size_t>(i);
            EXPECT_LT((b.T[ii] - a.T[ii]).cwiseAbs().maxCoeff(), kRoundOff * (1.0 + a.T[ii].cwiseAbs().maxCoeff()))
                << "T_" << i + 1;
            EXPECT_LT((b.T_dot[ii] - a.T_dot[ii]).cwiseAbs().maxCoeff(),
                      kRoundOff * (1.0 + a.T_dot[ii].cwiseAbs().maxCoeff()))
                << "dT_" << i + 1;
        }
        ++checked;
    }
    EXPECT_EQ(checked, kPoses);
    RecordProperty("worst_tau_relative", std::to_string(worst_tau));
}

INSTANTIATE_TEST_SUITE_P(PaperRobot, EqualsTheModel, ::testing::Values("paper-3prr", "paper-3prr-general"),
                         [](const auto& info) {
                             std::string name = info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace nocdyn::test
