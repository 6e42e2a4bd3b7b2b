// Operating envelope of the paper's 3-PRR, on the general model its short form expands to:
// the stroke (the P joints' range) binds at low frequency (amplitude independent of f), the
// peak force (their effort) at high frequency (amplitude ~ 1/f^2, proportional to the peak
// force); at the envelope the binding quantity is exactly reached; the paper's trajectories
// lie inside.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "nocdyn/io/short_form.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

using Axis = EnvelopeAxis;

constexpr Axis kAxes[] = {Axis::theta, Axis::x, Axis::y};
const io::RobotParameters kPaper{};

/// Peak |u| and |tau| over one period of A sin(2 pi f t) along `axis`, sampled very finely.
void peaks(const Model& model, Axis axis, double f, double amplitude, double& stroke, double& force) {
    Data data(model);
    stroke = force = 0.0;
    const double w = 2.0 * std::numbers::pi * f;
    const int index = static_cast<int>(axis);
    for (int k = 0; k < 4096; ++k) {
        const double phase = 2.0 * std::numbers::pi * (k + 0.37) / 4096;  // off the coarse grid
        Pose p = Pose::Zero();
        Twist dp = Twist::Zero(), ddp = Twist::Zero();
        p(index) = amplitude * std::sin(phase);
        dp(index) = amplitude * w * std::cos(phase);
        ddp(index) = -amplitude * w * w * std::sin(phase);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok()) << "phase " << phase;
        stroke = std::max(stroke, data.u.cwiseAbs().maxCoeff());
        force = std::max(force, data.tau.cwiseAbs().maxCoeff());
    }
}

TEST(Envelope, LowFrequencyIsBoundByTheStrokeIndependentlyOfFrequency) {
    const Model model{io::expand(kPaper)};
    for (const Axis axis : kAxes) {
        const auto at1 = maximumAmplitude(model, axis, 1.0);
        const auto at5 = maximumAmplitude(model, axis, 5.0);
        EXPECT_EQ(at1.limit, EnvelopeLimit::range) << axisName(axis);
        EXPECT_EQ(at5.limit, EnvelopeLimit::range) << axisName(axis);
        EXPECT_NEAR(at1.amplitude, at5.amplitude, 1e-5 * at1.amplitude) << axisName(axis);
        EXPECT_NEAR(at1.peak_u, 0.5 * kPaper.stroke, 1e-5 * kPaper.stroke);
        EXPECT_LT(at1.peak_tau, 0.05 * kPaper.peak_force);
    }
}

TEST(Envelope, HighFrequencyIsBoundByForceWithAmplitudeInverseSquareInFrequency) {
    const Model model{io::expand(kPaper)};
    for (const Axis axis : kAxes) {
        const auto at50 = maximumAmplitude(model, axis, 50.0);
        const auto at100 = maximumAmplitude(model, axis, 100.0);
        EXPECT_EQ(at50.limit, EnvelopeLimit::effort) << axisName(axis);
        EXPECT_EQ(at100.limit, EnvelopeLimit::effort) << axisName(axis);
        // inertia forces dominate: A ~ F / (m_eff w^2), so doubling f divides A by four
        EXPECT_NEAR(at50.amplitude / at100.amplitude, 4.0, 0.02) << axisName(axis);
        EXPECT_NEAR(at100.peak_tau, kPaper.peak_force, 1e-4 * kPaper.peak_force);
    }
}

TEST(Envelope, ForceBoundAmplitudeScalesWithThePeakForce) {
    io::RobotParameters strong;
    strong.peak_force = 2.0 * io::RobotParameters{}.peak_force;
    const Model model{io::expand(kPaper)}, stronger(io::expand(strong));
    for (const Axis axis : kAxes) {
        const double a = maximumAmplitude(model, axis, 100.0).amplitude;
        const double b = maximumAmplitude(stronger, axis, 100.0).amplitude;
        EXPECT_NEAR(b / a, 2.0, 0.01) << axisName(axis);
    }
}

TEST(Envelope, AtTheEnvelopeTheBindingLimitIsReachedAndOnePercentMoreExceedsIt) {
    const Model model{io::expand(kPaper)};
    const double half = 0.5 * kPaper.stroke;
    const double peak = kPaper.peak_force;
    for (const Axis axis : kAxes) {
        for (const double f : {2.0, 12.0, 30.0, 80.0}) {
            const auto point = maximumAmplitude(model, axis, f);
            double stroke = 0.0, force = 0.0;
            peaks(model, axis, f, point.amplitude, stroke, force);
            // the coarse grid (256 per period) may miss a peak between samples by ~1e-4
            EXPECT_LE(stroke, half * (1.0 + 1e-4)) << axisName(axis) << " f = " << f;
            EXPECT_LE(force, peak * (1.0 + 1e-4)) << axisName(axis) << " f = " << f;
            const double reached = point.limit == EnvelopeLimit::effort ? force / peak : stroke / half;
            EXPECT_GT(reached, 1.0 - 1e-4) << axisName(axis) << " f = " << f;
            peaks(model, axis, f, 1.01 * point.amplitude, stroke, force);
            EXPECT_TRUE(stroke > half || force > peak) << axisName(axis) << " f = " << f;
        }
    }
}

TEST(Envelope, PaperTrajectoriesLieInsideTheEnvelope) {
    const Model model{io::expand(kPaper)};
    for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
        const AxisMotion* motions[] = {&trajectory.theta, &trajectory.x, &trajectory.y};
        for (const Axis axis : kAxes) {
            for (const Harmonic& h : motions[static_cast<int>(axis)]->harmonics) {
                const auto point = maximumAmplitude(model, axis, h.frequency);
                EXPECT_LT(std::abs(h.amplitude), point.amplitude) << trajectory.name << " " << axisName(axis);
            }
        }
    }
}

TEST(Envelope, SweepIsLogSpacedOverEveryAxis) {
    const Model model{io::expand(kPaper)};
    EnvelopeOptions options;
    options.points = 5;
    const auto points = operatingEnvelope(model, options);
    ASSERT_EQ(points.size(), 15u);
    EXPECT_DOUBLE_EQ(points.front().frequency, 1.0);
    EXPECT_NEAR(points[2].frequency, 10.0, 1e-12);
    EXPECT_NEAR(points[4].frequency, 100.0, 1e-12);
    for (std::size_t k = 1; k < points.size(); ++k) {
        if (points[k].axis == points[k - 1].axis) {
            EXPECT_LE(points[k].amplitude, points[k - 1].amplitude * (1 + 1e-9));
        }
    }
}

TEST(Envelope, FrequenciesAndCountsOutsideTheirRangeAreRefusedNotIterated) {
    // 1e300 Hz used to bisect without end; 10^8 points to run for days.
    const Model model{io::expand(kPaper)};
    EnvelopeOptions options;
    options.max_frequency = 1e300;
    EXPECT_THROW((void)operatingEnvelope(model, options), Error);
    options = {};
    options.points = 100000000;
    EXPECT_THROW((void)operatingEnvelope(model, options), Error);
    options = {};
    options.min_frequency = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW((void)operatingEnvelope(model, options), Error);
    EXPECT_THROW((void)maximumAmplitude(model, Axis::x, 1e300, {}), Error);
    // the top of the accepted range finishes, force-bound
    const EnvelopePoint top = maximumAmplitude(model, Axis::x, kEnvelopeMaxFrequency, {});
    EXPECT_EQ(top.limit, EnvelopeLimit::effort);
    EXPECT_GT(top.amplitude, 0.0);
}

}  // namespace
}  // namespace nocdyn::test
