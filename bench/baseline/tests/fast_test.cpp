// The lean per-sample entry (fast.hpp) equals the full per-sample path (dynamics.hpp): the
// same u, du, ddu, tau to 1e-12 and exactly the same Status (code, limb, value) in and out of
// the workspace, and it allocates nothing (global operator new is counted in this binary).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/fast.hpp"
#include "nocdyn/prr3/kinematics.hpp"
#include "nocdyn/trajectory.hpp"
#include "allocation_counter.hpp"
#include "baseline_support.hpp"

namespace nocdyn::test {
namespace {

using prr3::Status;  // the kernel's own outcomes
using prr3::StatusCode;

/// error <= 1e-12 (|value| + peak of its column), as batch_test and the golden test measure it.
constexpr double kRelativeTolerance = 1e-12;

struct Input {
    Pose p;
    Twist dp, ddp;
};

struct Output {
    prr3::JointVector u, du, ddu, tau;
};

/// Runs both paths over the inputs; every sample must succeed on both, with equal values.
void expectEqualToFullPath(const prr3::Model& model, const std::vector<Input>& inputs) {
    prr3::Data data;
    prr3::FastData fast;
    std::vector<Output> want(inputs.size()), got(inputs.size());
    for (std::size_t k = 0; k < inputs.size(); ++k) {
        const Input& in = inputs[k];
        const Status full = prr3::inverseDynamics(model, data, in.p, in.dp, in.ddp);
        ASSERT_TRUE(full.ok()) << describePose(in.p);
        const Status lean = prr3::inverseDynamicsFast(model, fast, in.p, in.dp, in.ddp);
        ASSERT_TRUE(lean.ok()) << describePose(in.p) << ": " << describe(lean, model.parameters);
        want[k] = {data.u, data.du, data.ddu, data.tau};
        got[k] = {fast.u, fast.du, fast.ddu, fast.tau};
    }
    auto column = [](const Output& o, int a) -> const prr3::JointVector& {
        const prr3::JointVector* v[4] = {&o.u, &o.du, &o.ddu, &o.tau};
        return *v[a];
    };
    const char* names[4] = {"u", "du", "ddu", "tau"};
    double worst = 0.0;
    for (int a = 0; a < 4; ++a) {
        for (int j = 0; j < 3; ++j) {
            double peak = 0.0;
            for (const Output& o : want) peak = std::max(peak, std::abs(column(o, a)(j)));
            for (std::size_t k = 0; k < inputs.size(); ++k) {
                const double w = column(want[k], a)(j), g = column(got[k], a)(j);
                const double scale = std::abs(w) + peak;
                worst = std::max(worst, std::abs(g - w) / scale);
                EXPECT_LE(std::abs(g - w), kRelativeTolerance * scale)
                    << names[a] << "_" << j + 1 << " of sample " << k << ", " << describePose(inputs[k].p) << ": lean "
                    << g << ", full " << w;
            }
        }
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", worst);
    ::testing::Test::RecordProperty("worst_relative_error", text);
}

void expectSameStatus(const prr3::Model& model, prr3::FastData& fast, const Pose& p, const Twist& dp,
                      const Twist& ddp) {
    prr3::Data data;
    const Status full = prr3::inverseDynamics(model, data, p, dp, ddp);
    const Status lean = prr3::inverseDynamicsFast(model, fast, p, dp, ddp);
    EXPECT_EQ(lean.code, full.code) << describePose(p);
    EXPECT_EQ(lean.limb, full.limb) << describePose(p);
    if (!std::isnan(full.value)) {
        EXPECT_EQ(lean.value, full.value) << describePose(p);
    }
    if (!lean.ok()) {
        EXPECT_TRUE(fast.tau.array().isNaN().all()) << "failed samples' outputs are NaN";
    } else {
        // accepted samples here may be near a singularity, where cos phi_A = sqrt((1 - s)(1 + s))
        // amplifies the rounding of d_j^M (computed as n.M - n.B here, n.(M - B) there) by up
        // to ~1e8 at cond D = 1e4: agreement to 1e-6 (the strict checks are on the workspace)
        EXPECT_NEAR(fast.tau(0), data.tau(0), 1e-6 * (1.0 + std::abs(data.tau(0))));
    }
}

TEST(Fast, EqualsFullPathOverRandomWorkspaceSamples) {
    const prr3::Model model;
    BaselineSampler sampler(model, 7);
    std::uniform_real_distribution<double> alpha(-200.0, 200.0), accel(-30.0, 30.0);
    std::vector<Input> inputs(2000);
    for (Input& in : inputs) {
        in.p = sampler.next();
        in.dp = sampler.twist();
        in.ddp = Twist(alpha(sampler.rng()), accel(sampler.rng()), accel(sampler.rng()));
    }
    expectEqualToFullPath(model, inputs);
}

TEST(Fast, EqualsFullPathAlongThePaperTrajectories) {
    const prr3::Model model;
    for (const PoseTrajectory& traj : {paperTrajectory1(), paperTrajectory2()}) {
        std::vector<Input> inputs;
        for (double t = 0.0; t <= traj.duration; t += 1e-4) {
            Input in;
            traj.evaluate(t, in.p, in.dp, in.ddp);
            inputs.push_back(in);
        }
        SCOPED_TRACE(traj.name);
        expectEqualToFullPath(model, inputs);
    }
}

TEST(Fast, EqualsFullPathAtLargeAnglesAndForAnotherModel) {
    // Whole turns added to theta reach every quadrant of the kernel's sin/cos; beyond 1e6 rad
    // the lean entry takes libm's sin and cos.
    const prr3::Model model;
    BaselineSampler sampler(model, 11);
    std::vector<Input> inputs;
    for (int k = 0; k < 400; ++k) {
        Input in{sampler.next(), sampler.twist(), sampler.twist()};
        const double turns = k < 200 ? (k % 9) - 4 : (k % 2 ? 1 : -1) * 3e5;
        in.p(0) += 2.0 * std::numbers::pi * turns;
        inputs.push_back(in);
    }
    expectEqualToFullPath(model, inputs);

    // One FastData used with another model gives that model's forces.
    io::RobotParameters heavier;
    heavier.platform_mass *= 2.0;
    const prr3::Model other(heavier);
    prr3::FastData fast;
    prr3::Data data;
    const Input& in = inputs.front();
    ASSERT_TRUE(prr3::inverseDynamicsFast(model, fast, in.p, in.dp, in.ddp).ok());
    ASSERT_TRUE(prr3::inverseDynamicsFast(other, fast, in.p, in.dp, in.ddp).ok());
    ASSERT_TRUE(prr3::inverseDynamics(other, data, in.p, in.dp, in.ddp).ok());
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(fast.tau(j), data.tau(j), 1e-12 * (1.0 + data.tau.cwiseAbs().maxCoeff()));
}

TEST(Fast, ModelRebuiltInTheSameStorageGivesItsOwnForces) {
    // A Model destroyed and rebuilt at the same address with a 50 kg platform: the lean entry
    // must see the new constants (at the paper's first sample tau_1 goes from 28.6 N to 234 N).
    std::optional<prr3::Model> model;
    model.emplace();
    const prr3::Model* address = &*model;
    const PoseTrajectory trajectory = paperTrajectory1();
    Pose p, dp, ddp;
    trajectory.evaluate(0.0, p, dp, ddp);
    prr3::FastData fast;
    ASSERT_TRUE(prr3::inverseDynamicsFast(*model, fast, p, dp, ddp).ok());
    const double light_tau_1 = fast.tau(0);

    io::RobotParameters heavy;
    heavy.platform_mass = 50.0;
    model.emplace(heavy);
    ASSERT_EQ(&*model, address) << "the test needs the same storage";
    prr3::Data data;
    ASSERT_TRUE(prr3::inverseDynamicsFast(*model, fast, p, dp, ddp).ok());
    ASSERT_TRUE(prr3::inverseDynamics(*model, data, p, dp, ddp).ok());
    EXPECT_GT(std::abs(data.tau(0) - light_tau_1), 100.0) << "the heavier platform changes tau_1";
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(fast.tau(j), data.tau(j), 1e-12 * (1.0 + data.tau.cwiseAbs().maxCoeff()));

    // The batch path reads the same constants.
    prr3::SampleBatch batch(1);
    batch.p.row(0) = p.transpose();
    batch.dp.row(0) = dp.transpose();
    batch.ddp.row(0) = ddp.transpose();
    ASSERT_TRUE(prr3::inverseDynamicsBatch(*model, batch).ok());
    EXPECT_NEAR(batch.tau(0, 0), data.tau(0), 1e-12 * (1.0 + data.tau.cwiseAbs().maxCoeff()));
}

TEST(Fast, OutsideTheWorkspaceReportsTheFullPathsStatus) {
    const prr3::Model model;
    prr3::FastData fast;
    const Twist dp(0.3, 0.1, -0.2), ddp(5.0, 1.0, 2.0);
    for (const Pose& p : {Pose(0.0, 0.0, -0.2), Pose(0.0, 0.0, 0.08), Pose(0.0, 0.3, 0.0), Pose(0.0, -0.3, 0.0),
                          Pose(1.5, 0.0, 0.0), Pose(std::nan(""), 0.0, 0.0), Pose(0.0, std::nan(""), 0.0)}) {
        expectSameStatus(model, fast, p, dp, ddp);
        EXPECT_EQ(prr3::inverseDynamicsFast(model, fast, p, dp, ddp).code, StatusCode::outside_workspace);
    }
    // A wide box of poses: inside, outside (every limb), and near-singular ones.
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> angle(-3.2, 3.2), position(-0.15, 0.15);
    int failures[4] = {0, 0, 0, 0};
    for (int k = 0; k < 20000; ++k) {
        const Pose p(angle(rng), position(rng), position(rng));
        expectSameStatus(model, fast, p, dp, ddp);
        ++failures[static_cast<int>(prr3::inverseDynamicsFast(model, fast, p, dp, ddp).code)];
    }
    EXPECT_GT(failures[static_cast<int>(StatusCode::ok)], 100);
    EXPECT_GT(failures[static_cast<int>(StatusCode::outside_workspace)], 100);
    std::printf("wide box: %d ok, %d outside, %d singular H, %d singular D\n", failures[0], failures[1], failures[2],
                failures[3]);
}

TEST(Fast, LinkNormalToItsRailIsTheSameSingularity) {
    const prr3::Model model;
    prr3::FastData fast;
    // As kinematics_test: raise C until d_1^M = l (1 - 1e-10), cos phi_A1 ~ 1.4e-5.
    const double y = model.l * (1 - 1e-10) - 0.5 * (model.R - model.r);
    const Pose p(0.0, 0.0, y);
    expectSameStatus(model, fast, p, Twist(0.0, 0.0, 1.0), Twist::Zero());
    const Status status = prr3::inverseDynamicsFast(model, fast, p, Twist(0.0, 0.0, 1.0), Twist::Zero());
    EXPECT_EQ(status.code, StatusCode::singular_inverse_jacobian);
    EXPECT_EQ(status.limb, 0);
    EXPECT_GT(status.value, model.parameters.max_condition);
    // Approaching it: the same verdict as the full path at every step (cond D crosses 1e4).
    for (double eps = 1e-2; eps > 1e-12; eps *= 0.5) {
        expectSameStatus(model, fast, Pose(0.0, 0.0, model.l * (1 - eps) - 0.5 * (model.R - model.r)),
                         Twist(0.0, 0.0, 1.0), Twist::Zero());
    }
}

TEST(Fast, ConcurrentLinkLinesAreTheSameForwardSingularity) {
    // As kinematics_test: the rotation about O where h_j1 = 0 (the link lines meet at C).
    const double lo = baselineConcurrentLinkLinesRotation();
    const prr3::Model model;
    prr3::FastData fast;
    const Status status =
        prr3::inverseDynamicsFast(model, fast, Pose(lo, 0.0, 0.0), Twist(1.0, 0.0, 0.0), Twist::Zero());
    EXPECT_EQ(status.code, StatusCode::singular_forward_jacobian) << "theta = " << lo;
    EXPECT_EQ(status.limb, -1);
    expectSameStatus(model, fast, Pose(lo, 0.0, 0.0), Twist(1.0, 0.0, 0.0), Twist::Zero());
    // Sweeping through it: same verdicts (ok -> singular -> ok) as the full path.
    int singular = 0, accepted = 0;
    for (double d = -0.05; d <= 0.05; d += 1e-4) {
        expectSameStatus(model, fast, Pose(lo + d, 0.0, 0.0), Twist(1.0, 0.0, 0.0), Twist(2.0, 0.1, 0.1));
        const StatusCode code =
            prr3::inverseDynamicsFast(model, fast, Pose(lo + d, 0.0, 0.0), Twist(1.0, 0.0, 0.0), Twist::Zero()).code;
        singular += code == StatusCode::singular_forward_jacobian;
        accepted += code == StatusCode::ok;
    }
    EXPECT_GT(singular, 0);
    EXPECT_GT(accepted, 0);
    ASSERT_TRUE(
        prr3::inverseDynamicsFast(model, fast, Pose(lo + 0.3, 0.0, 0.0), Twist(1.0, 0.0, 0.0), Twist::Zero()).ok());
}

TEST(Fast, AllocatesNothingIncludingFailures) {
    const prr3::Model model;
    prr3::FastData fast;
    const PoseTrajectory trajectory = paperTrajectory1();
    Pose p, dp, ddp;
    const long before = allocationCount();
    double checksum = 0.0;
    for (int k = 0; k < 2000; ++k) {
        trajectory.evaluate(k * 1e-4, p, dp, ddp);
        const Status status = prr3::inverseDynamicsFast(model, fast, p, dp, ddp);
        checksum += status.ok() ? fast.tau.sum() + fast.u.sum() + fast.du.sum() + fast.ddu.sum() : 1e9;
    }
    // Rejected samples take the full path's stages for their Status: no allocation either.
    checksum += prr3::inverseDynamicsFast(model, fast, Pose(0.0, 0.0, -0.2), dp, ddp).ok();
    checksum += prr3::inverseDynamicsFast(model, fast,
                                          Pose(0.0, 0.0, model.l * (1 - 1e-10) - 0.5 * (model.R - model.r)), dp, ddp)
                    .ok();
    // A fresh FastData needs no set-up: no allocation either.
    prr3::FastData fresh;
    checksum += prr3::inverseDynamicsFast(model, fresh, Pose::Zero(), dp, ddp).ok();
    const long after = allocationCount();
    EXPECT_EQ(after - before, 0);
    EXPECT_TRUE(std::isfinite(checksum));
}

TEST(Fast, CountingAllocatorSeesAllocations) {
    // Proves the counter works, so that the test above can fail (volatile: not elided).
    const long before = allocationCount();
    std::vector<double>* volatile v = new std::vector<double>(100);
    (*v)[0] = 1.0;
    delete v;
    EXPECT_GE(allocationCount() - before, 2);
}

}  // namespace
}  // namespace nocdyn::test
