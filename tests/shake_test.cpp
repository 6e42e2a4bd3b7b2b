// Recorded motion: the zero-phase high-pass on tones, the Nigam-Jennings spectrum against the
// closed-form response of an oscillator to a harmonic, and the similitude fit of a record to
// the paper's prototype (stroke-limited, then amplitude-limited).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "nocdyn/io/examples.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/shake.hpp"

namespace nocdyn::test {
namespace {

constexpr double kPi = std::numbers::pi;

std::vector<double> tone(double f, double fs, double seconds, double offset = 0.0) {
    std::vector<double> x;
    for (int i = 0; i < static_cast<int>(seconds * fs); ++i) x.push_back(offset + std::sin(2 * kPi * f * i / fs));
    return x;
}

TEST(HighPass, PassesAToneFarAboveTheCutoffUnchangedAndInPhaseAndRemovesAnOffset) {
    const std::vector<double> x = tone(5.0, 100.0, 20.0, 0.7);
    const std::vector<double> y = highPassZeroPhase(x, 0.01, 0.5);
    for (std::size_t i = 500; i < 1500; ++i) EXPECT_NEAR(y[i], x[i] - 0.7, 2e-3) << i;
}

TEST(HighPass, ForwardBackwardButterworthHalvesAToneAtTheCutoff) {
    // |H(f_c)|^2 = 1/2 for a Butterworth with the cutoff prewarped; zero phase
    const std::vector<double> x = tone(1.0, 100.0, 40.0);
    const std::vector<double> y = highPassZeroPhase(x, 0.01, 1.0);
    for (std::size_t i = 1500; i < 2500; ++i) EXPECT_NEAR(y[i], 0.5 * x[i], 2e-3) << i;
}

TEST(HighPass, RefusesACutoffAtOrAboveNyquist) {
    const std::vector<double> x = tone(1.0, 100.0, 1.0);
    EXPECT_ANY_THROW((void)highPassZeroPhase(x, 0.01, 50.0));
    EXPECT_ANY_THROW((void)highPassZeroPhase(x, 0.0, 1.0));
}

/// u'' + 2 z w u' + w^2 u = -sin(W t) from rest, in closed form.
double harmonicResponse(double t, double w, double z, double W) {
    const double k = w * w - W * W, c = 2 * z * w * W;
    const double C = -k / (k * k + c * c), D = c / (k * k + c * c);  // u_p = C sin + D cos
    const double wd = w * std::sqrt(1 - z * z);
    const double E = -D, F = (z * w * E - W * C) / wd;
    return C * std::sin(W * t) + D * std::cos(W * t) +
           std::exp(-z * w * t) * (E * std::cos(wd * t) + F * std::sin(wd * t));
}

TEST(ResponseSpectrum, PeakMatchesTheClosedFormResponseToAHarmonic) {
    const double dt = 0.001, W = 2 * kPi * 3.0, z = 0.05;
    std::vector<double> a;
    for (int i = 0; i <= 4000; ++i) a.push_back(std::sin(W * i * dt));
    for (double T : {0.1, 0.33, 1.0, 2.5}) {
        const double w = 2 * kPi / T;
        double peak = 0.0;
        for (int i = 0; i <= 4000; ++i) peak = std::max(peak, std::abs(harmonicResponse(i * dt, w, z, W)));
        // the recurrence is exact for the piecewise-linear excitation; the sine differs from
        // it by (W dt)^2 / 8 of its amplitude
        EXPECT_NEAR(peakOscillatorDisplacement(a, dt, T, z), peak, 2e-4 * peak) << T;
    }
}

TEST(ResponseSpectrum, IsExactForARampExcitation) {
    // a = t (linear: the recurrence is exact): u = -(t/w^2 - 2 z / w^3) + transient
    const double dt = 0.01, T = 0.5, z = 0.05, w = 2 * kPi / T, wd = w * std::sqrt(1 - z * z);
    std::vector<double> a;
    for (int i = 0; i <= 200; ++i) a.push_back(i * dt);
    double peak = 0.0;
    for (int i = 0; i <= 200; ++i) {
        const double t = i * dt;
        const double E = -2 * z / (w * w * w), F = (z * w * E + 1.0 / (w * w)) / wd;
        const double u =
            -(t / (w * w) - 2 * z / (w * w * w)) + std::exp(-z * w * t) * (E * std::cos(wd * t) + F * std::sin(wd * t));
        peak = std::max(peak, std::abs(u));
    }
    EXPECT_NEAR(peakOscillatorDisplacement(a, dt, T, z), peak, 1e-12);
}

TEST(ScoreShake, IdenticalMotionsScoreZeroAndAScaledOneItsScale) {
    const std::vector<double> a = tone(2.0, 200.0, 3.0);
    std::vector<double> b;
    for (double v : a) b.push_back(1.2 * v);
    const ShakeScore same = scoreShake(a, a, 0.005, 0.05, 2.0);
    EXPECT_EQ(same.rms_error, 0.0);
    EXPECT_EQ(same.share_outside, 0.0);
    const ShakeScore more = scoreShake(a, b, 0.005, 0.05, 2.0);
    EXPECT_NEAR(more.rms_error, 0.2, 1e-12);
    EXPECT_NEAR(more.peak_error, 0.2, 1e-12);
    EXPECT_EQ(more.share_outside, 1.0);  // every S_a 20 % above
}

class FitRecord : public ::testing::Test {
protected:
    Model model{io::exampleRobot("paper-3prr-general")};
    GroundRecord record() const {
        // 2 Hz, 3 m/s^2 along x: displacement 19 mm, beyond the +-12.45 mm stroke
        GroundRecord r;
        r.dt = 0.01;
        for (int i = 0; i < 400; ++i) r.ax.push_back(3.0 * std::sin(2 * kPi * 2.0 * i * r.dt));
        return r;
    }
};

TEST_F(FitRecord, ChoosesTheLeastTimeCompressionThatKeepsEveryActuatorWithinItsLimits) {
    FitOptions options;
    options.highpass = 0.0;
    const FittedRecord fit = fitRecord(model, record(), options);
    EXPECT_GT(fit.time_scale, 1.0);
    EXPECT_DOUBLE_EQ(fit.amplitude_scale, 1.0);
    EXPECT_LE(fit.use.ratio, 1.0);
    EXPECT_GT(fit.use.ratio, 0.99);  // at the limit: a little less compression would not fit
    // similitude: accelerations kept, time compressed by L
    EXPECT_DOUBLE_EQ(fit.dt, 0.01 / fit.time_scale);
    Pose p, dp, ddp;
    for (std::size_t i = 10; i < fit.t.size(); i += 37) {
        fit.trajectory.evaluate(fit.t[i], p, dp, ddp);
        EXPECT_NEAR(ddp(1), 3.0 * std::sin(2 * kPi * 2.0 * i * 0.01), 1e-9);
        EXPECT_NEAR(ddp(2), 0.0, 1e-15);
    }
}

TEST_F(FitRecord, FallsBackToAmplitudeScalingWhenTheTimeScaleIsFixed) {
    FitOptions options;
    options.highpass = 0.0;
    options.time_scale = 1.0;
    const FittedRecord fit = fitRecord(model, record(), options);
    EXPECT_DOUBLE_EQ(fit.time_scale, 1.0);
    EXPECT_LT(fit.amplitude_scale, 1.0);
    EXPECT_GT(fit.use.ratio, 0.99);
    EXPECT_LE(fit.use.ratio, 1.0);
    EXPECT_NEAR(fit.ax[5], fit.amplitude_scale * 3.0 * std::sin(0.2 * kPi), 1e-12);
}

TEST_F(FitRecord, BaselineCorrectionRemovesTheLinearDriftAndKeepsTheAcceleration) {
    // a = 3 sin(w t) over 8 whole periods: integrated from rest, d = 3 t / w - 3 sin(w t) / w^2
    // drifts by 0.95 m; the least stroke is that of -3 sin(w t) / w^2, reached with v0 = -3 / w
    FitOptions options;
    options.highpass = 0.0;
    options.time_scale = 2.0;
    GroundRecord r = record();
    r.ax.resize(401);
    for (int i = 0; i < 401; ++i) r.ax[static_cast<std::size_t>(i)] = 3.0 * std::sin(2 * kPi * 2.0 * i * r.dt);
    const FittedRecord fit = fitRecord(model, r, options);
    ASSERT_DOUBLE_EQ(fit.amplitude_scale, 1.0);
    const double w = 2 * kPi * 2.0 * fit.time_scale;  // in replay time
    Pose p, dp, ddp;
    fit.trajectory.evaluate(0.0, p, dp, ddp);
    EXPECT_NEAR(dp(1), -3.0 / w, 2e-3 * 3.0 / w);
    double lo = 1e9, hi = -1e9;
    for (std::size_t i = 0; i < fit.t.size(); ++i) {
        fit.trajectory.evaluate(fit.t[i], p, dp, ddp);
        lo = std::min(lo, p(1));
        hi = std::max(hi, p(1));
        // the target acceleration is the second derivative of the target displacement
        EXPECT_NEAR(ddp(1), fit.ax[i], 1e-9);
    }
    EXPECT_NEAR(hi - lo, 2.0 * 3.0 / (w * w), 0.01 * 2.0 * 3.0 / (w * w));
    EXPECT_NEAR(0.5 * (hi + lo), model.home(1), 1e-12);
}

TEST_F(FitRecord, BaselineCorrectionAddsNoRateToAMotionThatDoesNotDrift) {
    // a = 3 cos(w t) over whole periods: from rest d = 3 (1 - cos(w t)) / w^2, no drift; any v0
    // would widen the stroke (beyond the samples' round-off of the extremes)
    FitOptions options;
    options.highpass = 0.0;
    options.time_scale = 2.0;
    GroundRecord r = record();
    for (std::size_t i = 0; i < r.ax.size(); ++i)
        r.ax[i] = 3.0 * std::cos(2 * kPi * 2.0 * static_cast<double>(i) * r.dt);
    const FittedRecord fit = fitRecord(model, r, options);
    Pose p, dp, ddp;
    fit.trajectory.evaluate(0.0, p, dp, ddp);
    EXPECT_NEAR(dp(1), 0.0, 1e-5 * 3.0 / (2 * kPi * 2.0 * fit.time_scale));
}

TEST_F(FitRecord, RungeKuttaPlantFollowsTheErrorControlledSimulatorInTheShakeClosedLoop) {
    // the replay's closed loop (computed torque, 10 kHz, unknown payload, noise) for 0.1 s on both
    // plants: one RK4 step per tick against the Simulator at relative tolerance 1e-10
    FitOptions options;
    options.highpass = 0.0;
    const FittedRecord fit = fitRecord(model, record(), options);
    const Model loaded(withPayload(io::exampleRobot("paper-3prr-general"), {0.5, 0.0, Vector2::Zero()}));
    PoseLoopOptions loop;
    loop.duration = 0.1;
    loop.noise_angle = loop.noise_position = 1e-6;
    loop.noise_rate = 1e-5;
    PoseController c1(model, ControlLaw::computed_torque, taskCriticallyDamped(30.0));
    PoseController c2(model, ControlLaw::computed_torque, taskCriticallyDamped(30.0));
    SimulatorRobotPlant reference(loaded);
    RungeKuttaRobotPlant rk4(loaded);
    const PoseLoopResult a = runPoseLoop(c1, reference, fit.trajectory, loop);
    const PoseLoopResult b = runPoseLoop(c2, rk4, fit.trajectory, loop);
    ASSERT_EQ(a.p.size(), b.p.size());
    double peak = 0.0, motion = 0.0;
    for (std::size_t k = 0; k < a.p.size(); ++k) {
        peak = std::max(peak, (a.p[k] - b.p[k]).cwiseAbs().maxCoeff());
        motion = std::max(motion, std::abs(a.p[k](1) - model.home(1)));
        EXPECT_LT((a.u[k] - b.u[k]).cwiseAbs().maxCoeff(), 1e-9);
    }
    EXPECT_GT(motion, 1e-3);  // the platform did move by millimetres
    EXPECT_LT(peak, 1e-11);   // [m, rad]; measured 1e-12
}

}  // namespace
}  // namespace nocdyn::test
