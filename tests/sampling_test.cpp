// Sampling a trajectory (sampling.hpp) on the general model of the paper's 3-PRR (its short
// form expanded): limits hold on the motion, not only at the output samples; an aliasing rate is refused; nothing
// non-finite comes out; streaming gives the same numbers as the stored series and its memory does not grow with the
// number of samples.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "allocation_counter.hpp"
#include "nocdyn/io/short_form.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/analysis/sampling.hpp"

namespace nocdyn::test {
namespace {

PoseTrajectory harmonicX(double amplitude, double frequency, double phase) {
    PoseTrajectory trajectory;
    trajectory.name = "probe";
    trajectory.x.harmonics.push_back({amplitude, frequency, phase});
    return trajectory;
}

PoseTrajectory harmonicY(double amplitude, double frequency, double phase) {
    PoseTrajectory trajectory;
    trajectory.name = "probe";
    trajectory.y.harmonics.push_back({amplitude, frequency, phase});
    return trajectory;
}

/// The message of the Error thrown by `f`, or "" when none is thrown.
template <typename F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

const io::RobotParameters kPaper{};

LimitSummary stream(const Model& model, const PoseTrajectory& trajectory, double duration, double rate,
                    LimitPolicy policy) {
    return streamInverseDynamics(model, trajectory, sampleGrid(duration, rate), policy,
                                 [](const InverseDynamicsSample&) {});
}

/// Whether every output sample alone is within stroke and peak force (what was checked before).
bool samplesAloneAreWithinLimits(const Model& model, const PoseTrajectory& trajectory, double duration, double rate) {
    Data data(model);
    Pose p, dp, ddp;
    for (const double t : sampleTimes(duration, rate)) {
        trajectory.evaluate(t, p, dp, ddp);
        if (!inverseDynamics(model, data, p, dp, ddp) || !checkJointLimits(model, data) || !checkEffort(model, data)) {
            return false;
        }
    }
    return true;
}

constexpr double kQuarterPi = std::numbers::pi / 4.0;

TEST(Sampling, RateAtOrBelowTwiceTheHighestFrequencyIsRefusedNamingTheRateNeeded) {
    const Model model{io::expand(kPaper)};
    PoseTrajectory trajectory = harmonicX(1e-3, 10.0, 0.0);
    trajectory.theta.harmonics.push_back({1e-3, 1000.0, 0.0});
    for (const double rate : {1000.0, 2000.0}) {
        const std::string message = errorOf([&] { (void)stream(model, trajectory, 0.01, rate, LimitPolicy::record); });
        EXPECT_NE(message.find("above 2000 Hz"), std::string::npos) << rate << ": " << message;
        EXPECT_NE(message.find("alias"), std::string::npos) << message;
    }
    EXPECT_EQ(errorOf([&] { (void)stream(model, trajectory, 0.01, 2001.0, LimitPolicy::record); }), "");
    // The stored series refuses the same sampling.
    EXPECT_THROW((void)sampleInverseDynamics(model, trajectory, sampleTimes(0.01, 1000.0)), Error);
}

TEST(Sampling, ForcePeakBetweenOutputSamplesIsAnError) {
    // 250 Hz sampled at 1 kHz with a 45 degree phase: the samples see 0.71 of the peak only.
    const Model model{io::expand(kPaper)};
    const PoseTrajectory trajectory = harmonicX(4.5e-5, 250.0, kQuarterPi);
    ASSERT_TRUE(samplesAloneAreWithinLimits(model, trajectory, 0.02, 1000.0));
    const std::string message = errorOf([&] { (void)stream(model, trajectory, 0.02, 1000.0, LimitPolicy::error); });
    EXPECT_NE(message.find("effort limit exceeded"), std::string::npos) << message;
    EXPECT_NE(message.find("between output samples"), std::string::npos) << message;
    const LimitSummary recorded = stream(model, trajectory, 0.02, 1000.0, LimitPolicy::record);
    EXPECT_FALSE(recorded.limit_violations.empty());
    EXPECT_GT(*std::max_element(recorded.peak_tau.begin(), recorded.peak_tau.end()), kPaper.peak_force);
    EXPECT_GE(recorded.checks_between_samples, 19u * 9u);  // 10 kHz checks between 1 kHz samples
}

TEST(Sampling, StrokeBetweenOutputSamplesIsAnError) {
    const Model model{io::expand(kPaper)};
    const PoseTrajectory trajectory = harmonicX(0.015, 5.0, kQuarterPi);
    ASSERT_TRUE(samplesAloneAreWithinLimits(model, trajectory, 0.4, 20.0));
    const std::string message = errorOf([&] { (void)stream(model, trajectory, 0.4, 20.0, LimitPolicy::error); });
    EXPECT_NE(message.find("joint range exceeded"), std::string::npos) << message;
    EXPECT_NE(message.find("between output samples"), std::string::npos) << message;
    // A rate that resolves the motion gives the same peak within the grid's 0.3 %.
    const LimitSummary coarse = stream(model, trajectory, 0.4, 20.0, LimitPolicy::record);
    const LimitSummary fine = stream(model, trajectory, 0.4, 100000.0, LimitPolicy::record);
    ASSERT_EQ(coarse.peak_u.size(), 3u);
    for (std::size_t j = 0; j < 3; ++j) EXPECT_NEAR(coarse.peak_u[j], fine.peak_u[j], 3e-3 * fine.peak_u[j]);
}

TEST(Sampling, WorkspaceExitBetweenSamplesIsAnErrorEvenWhenLimitsAreAllowed) {
    const Model model{io::expand(kPaper)};
    const PoseTrajectory trajectory = harmonicY(0.095, 5.0, kQuarterPi);
    Data data(model);
    Pose p, dp, ddp;
    for (const double t : sampleTimes(0.4, 20.0)) {
        trajectory.evaluate(t, p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok()) << "t = " << t;
    }
    // Recording limit violations (the stroke is exceeded first) does not let a workspace exit through.
    EXPECT_NE(errorOf([&] { (void)stream(model, trajectory, 0.4, 20.0, LimitPolicy::error); }), "");
    const std::string message = errorOf([&] { (void)stream(model, trajectory, 0.4, 20.0, LimitPolicy::record); });
    EXPECT_NE(message.find("out of reach"), std::string::npos) << message;
    EXPECT_NE(message.find("between output samples"), std::string::npos) << message;
    EXPECT_THROW(requireReachable(model, trajectory, 0.4), Error);
    EXPECT_NO_THROW(requireReachable(model, harmonicY(0.01, 5.0, kQuarterPi), 0.4));
}

TEST(Sampling, NonFiniteValueIsAnErrorEvenWhenLimitsAreAllowed) {
    // (2 pi f)^2 a overflows: the acceleration, and with it every force, is infinite.
    const Model model{io::expand(kPaper)};
    const PoseTrajectory trajectory = harmonicX(1e-3, 1e160, 0.0);
    const std::string message = errorOf([&] { (void)stream(model, trajectory, 1e-157, 3e160, LimitPolicy::record); });
    EXPECT_NE(message.find("not finite"), std::string::npos) << message;
    EXPECT_NE(message.find("t = 0 s"), std::string::npos) << message;
}

TEST(Sampling, StreamedSamplesEqualTheStoredSeries) {
    const Model model{io::expand(kPaper)};
    const PoseTrajectory trajectory = paperTrajectory1();
    const InverseDynamicsSeries series = sampleInverseDynamics(model, trajectory, sampleTimes(0.05, 2000.0));
    const io::Table table = tables::toTable(series, model.actuators);
    std::size_t k = 0;
    std::vector<double> row;
    const LimitSummary summary = streamInverseDynamics(
        model, trajectory, sampleGrid(0.05, 2000.0), LimitPolicy::error, [&](const InverseDynamicsSample& sample) {
            tables::inverseDynamicsRow(sample, row);
            ASSERT_LT(k, table.rows.size());
            for (std::size_t c = 0; c < row.size(); ++c)
                EXPECT_EQ(row[c], table.rows[k][c]) << "row " << k << " column " << c;
            ++k;
        });
    EXPECT_EQ(k, 100u);
    EXPECT_EQ(table.columns, tables::inverseDynamicsColumns(3));
    EXPECT_EQ(summary.peak_tau, series.summary.peak_tau);
}

TEST(Sampling, StreamingAllocatesTheSameForTenAndTenThousandTimesTheSamples) {
    const Model model{io::expand(kPaper)};
    const PoseTrajectory trajectory = paperTrajectory1();
    auto allocationsFor = [&](double duration) {
        const SampleGrid grid = sampleGrid(duration, 10000.0);
        const long before = allocationCount();
        double sum = 0.0;
        (void)streamInverseDynamics(model, trajectory, grid, LimitPolicy::error,
                                    [&](const InverseDynamicsSample& s) { sum += s.tau(0); });
        EXPECT_TRUE(std::isfinite(sum));
        return allocationCount() - before;
    };
    EXPECT_EQ(allocationsFor(0.001), allocationsFor(1.0));
}

}  // namespace
}  // namespace nocdyn::test
