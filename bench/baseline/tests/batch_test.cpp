// The batch path (batch.hpp) equals the per-sample path (dynamics.hpp) sample by sample, on
// one thread and on every core, and reports unreachable samples exactly as the per-sample
// path does.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "nocdyn/prr3/batch.hpp"
#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

using prr3::Status;  // the kernel's own outcomes

/// Relative agreement asked of the batch: error / (|value| + peak of its column), as the
/// golden test reports it (u_j is a difference of lengths near l: its peak sets the scale).
constexpr double kRelativeTolerance = 1e-12;

/// Trajectory 1 plus harmonics, sampled irregularly, with large angles thrown in (to reach
/// every quadrant of the kernel's sin/cos) by offsetting theta by multiples of 2 pi.
prr3::SampleBatch makeBatch(Eigen::Index n) {
    PoseTrajectory traj = paperTrajectory1();
    traj.theta.harmonics.push_back({std::numbers::pi / 180.0, 30.0, 0.3});
    traj.x.harmonics.push_back({0.0005, 20.0, 1.0});
    traj.y.harmonics.push_back({0.0008, 30.0, -0.5});
    prr3::SampleBatch batch(n);
    for (Eigen::Index k = 0; k < n; ++k) {
        Pose p, dp, ddp;
        traj.evaluate(0.000137 * static_cast<double>(k), p, dp, ddp);
        p(0) += 2.0 * std::numbers::pi * static_cast<double>((k % 7) - 3);
        batch.p.row(k) = p.transpose();
        batch.dp.row(k) = dp.transpose();
        batch.ddp.row(k) = ddp.transpose();
    }
    return batch;
}

void expectEqualsPerSample(const prr3::Model& model, const prr3::SampleBatch& batch) {
    prr3::Data data;
    const Eigen::ArrayX3d* got[4] = {&batch.u, &batch.du, &batch.ddu, &batch.tau};
    Eigen::Array<double, 4, 3> peak = Eigen::Array<double, 4, 3>::Zero();
    for (int a = 0; a < 4; ++a) peak.row(a) = got[a]->abs().colwise().maxCoeff();
    for (Eigen::Index k = 0; k < batch.size(); ++k) {
        ASSERT_TRUE(prr3::inverseDynamics(model, data, batch.p.row(k).transpose(), batch.dp.row(k).transpose(),
                                          batch.ddp.row(k).transpose())
                        .ok());
        const prr3::JointVector* want[4] = {&data.u, &data.du, &data.ddu, &data.tau};
        const char* names[4] = {"u", "du", "ddu", "tau"};
        for (int a = 0; a < 4; ++a) {
            for (int j = 0; j < 3; ++j) {
                const double w = (*want[a])(j), g = (*got[a])(k, j);
                const double scale = std::abs(w) + peak(a, j);
                EXPECT_LE(std::abs(g - w), kRelativeTolerance * scale)
                    << names[a] << "_" << j + 1 << " of sample " << k << " at pose " << batch.p.row(k) << ": batch "
                    << g << ", per-sample " << w;
            }
        }
    }
}

TEST(Batch, EqualsPerSamplePathOnOneThread) {
    const prr3::Model model;
    prr3::SampleBatch batch = makeBatch(1001);  // odd: exercises the vector loop's tail
    const prr3::BatchStatus status = prr3::inverseDynamicsBatch(model, batch);
    ASSERT_TRUE(status.ok()) << status.failed << " failed, first " << status.first_failure;
    expectEqualsPerSample(model, batch);
}

TEST(Batch, EqualsPerSamplePathOnEveryCore) {
    const prr3::Model model;
    prr3::SampleBatch batch = makeBatch(4099);
    for (unsigned threads : {0u, 1u, 2u, 3u, 8u}) {
        batch.tau.setZero();
        const prr3::BatchStatus status = prr3::inverseDynamicsBatchParallel(model, batch, threads);
        ASSERT_TRUE(status.ok()) << threads << " threads";
        expectEqualsPerSample(model, batch);
    }
}

TEST(Batch, ReportsTheFirstUnreachableSampleAsThePerSamplePathDoes) {
    const prr3::Model model;
    prr3::SampleBatch batch = makeBatch(64);
    batch.p.row(17) << 0.0, 0.0, -0.2;  // far outside the workspace
    batch.p.row(40) << 0.0, 0.0, -0.2;
    const prr3::BatchStatus status = prr3::inverseDynamicsBatchParallel(model, batch, 2);
    EXPECT_EQ(status.failed, 2);
    EXPECT_EQ(status.first_failure, 17);
    prr3::Data data;
    const Status want = prr3::inverseDisplacement(model, data, Pose(0.0, 0.0, -0.2));
    EXPECT_EQ(status.status.code, want.code);
    EXPECT_EQ(status.status.limb, want.limb);
    EXPECT_DOUBLE_EQ(status.status.value, want.value);
    EXPECT_TRUE(batch.tau.row(17).isNaN().all());
    EXPECT_TRUE(batch.tau.row(16).isFinite().all());
}

TEST(Batch, HugeAnglesTakeThePerSamplePath) {
    const prr3::Model model;
    prr3::SampleBatch batch = makeBatch(8);
    batch.p(3, 0) += 2.0 * std::numbers::pi * 1.0e7;  // beyond the kernel's exact reduction
    ASSERT_TRUE(prr3::inverseDynamicsBatch(model, batch).ok());
    expectEqualsPerSample(model, batch);
}

}  // namespace
}  // namespace nocdyn::test
