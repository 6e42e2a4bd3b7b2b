// Shake-table estimation and control: the Kalman filter on known signals (exact without noise,
// and below the encoder noise with it), and the table controller against the pose-sensor
// computed torque on the same excerpt of a real record, the same plant and the same payload.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "nocdyn/error.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/shake.hpp"
#include "nocdyn/sim/shake_control.hpp"

namespace nocdyn::test {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(PoseEstimator, FollowsAMotionExactlyWhenItsSensorsAreExact) {
    const double dt = 1e-4;
    PoseEstimator estimator(dt, Vector3::Constant(1e-6), Vector3::Constant(1e-3));
    // q = sin(2 pi 3 t) on every axis; the accelerometer gives the mean acceleration of each tick
    const auto q = [](double t) { return std::sin(2 * kPi * 3 * t); };
    const auto dq = [](double t) { return 2 * kPi * 3 * std::cos(2 * kPi * 3 * t); };
    estimator.reset(Pose::Constant(q(0)), Twist::Constant(dq(0)));
    double worst_q = 0.0, worst_v = 0.0;
    for (int k = 1; k <= 5000; ++k) {
        const double t = k * dt;
        const Twist y = Twist::Constant((dq(t) - dq(t - dt)) / dt);
        estimator.update(Pose::Constant(q(t)), y);
        worst_q = std::max(worst_q, std::abs(estimator.pose()(1) - q(t)));
        worst_v = std::max(worst_v, std::abs(estimator.rate()(1) - dq(t)));
    }
    // the prediction errs by O(dt^3 d3q/dt3) per tick, which the encoder correction bounds
    // (measured: 9.9e-8 in q and 5.3e-6 in dq/dt of a motion of amplitude 1 and 19 per second)
    EXPECT_LT(worst_q, 2e-7);
    EXPECT_LT(worst_v, 1e-5);
    // a gain between 0 and 1 on the pose, the rate's positive
    EXPECT_GT(estimator.gain(1)(0), 0.0);
    EXPECT_LT(estimator.gain(1)(0), 1.0);
    EXPECT_GT(estimator.gain(1)(1), 0.0);
}

TEST(PoseEstimator, FusesNoisyEncodersAndAccelerometerBelowEitherAlone) {
    const double dt = 1e-4, sigma_q = 1e-6, sigma_y = 5e-3;
    PoseEstimator estimator(dt, Vector3::Constant(sigma_q), Vector3::Constant(sigma_y));
    std::mt19937 rng(3);
    std::normal_distribution<double> normal(0.0, 1.0);
    const auto q = [](double t) { return 1e-3 * std::sin(2 * kPi * 5 * t); };
    const auto dq = [](double t) { return 1e-3 * 2 * kPi * 5 * std::cos(2 * kPi * 5 * t); };
    estimator.reset(Pose::Constant(q(0)), Twist::Constant(dq(0)));
    double sq = 0.0, sv = 0.0, sv_difference = 0.0;
    double q_last = q(0);
    const int n = 40000;
    for (int k = 1; k <= n; ++k) {
        const double t = k * dt;
        const double q_m = q(t) + sigma_q * normal(rng);
        const Twist y = Twist::Constant((dq(t) - dq(t - dt)) / dt + sigma_y * normal(rng));
        estimator.update(Pose::Constant(q_m), y);
        sq += std::pow(estimator.pose()(2) - q(t), 2);
        sv += std::pow(estimator.rate()(2) - dq(t), 2);
        sv_difference += std::pow((q_m - q_last) / dt - dq(t), 2);
        q_last = q_m;
    }
    const double rms_q = std::sqrt(sq / n), rms_v = std::sqrt(sv / n);
    // measured: 0.14 sigma_q and 2.4e-5 m/s (the difference of the encoders: 1.4e-2 m/s)
    EXPECT_LT(rms_q, 0.25 * sigma_q);
    EXPECT_LT(rms_v, 1e-3 * std::sqrt(sv_difference / n));
    EXPECT_LT(rms_v, 5e-5);
}

TEST(PoseEstimator, RefusesANonPositiveStepOrPoseNoise) {
    EXPECT_THROW(PoseEstimator(0.0, Vector3::Constant(1e-6), Vector3::Zero()), Error);
    EXPECT_THROW(PoseEstimator(1e-4, Vector3::Zero(), Vector3::Zero()), Error);
}

TEST(TableSensors, AccelerometerNoiseIsTheDensityOverTheBandwidth) {
    TableSensors s;  // ADXL355: 22.5 ug/sqrt(Hz), 1 kHz
    const Vector3 sigma = accelerometerNoise(s);
    EXPECT_NEAR(sigma(1), 22.5e-6 * 9.80665 * std::sqrt(kPi / 2 * 1000.0), 1e-12);
    EXPECT_NEAR(sigma(0), std::sqrt(2.0) * sigma(1) / 0.1, 1e-12);
}

/// The first 2 s of El Centro along x times `scale`, fitted to the prototype.
FittedRecord elCentroExcerpt(const Model& model, double scale = 1.0) {
    const io::GroundMotionRecord r = io::readAt2File(std::string(NOCDYN_SOURCE_DIR) + "/data/elcentro_1940_ns.AT2");
    GroundRecord record;
    record.dt = r.dt;
    record.ax.assign(r.acceleration.begin(), r.acceleration.begin() + 101);
    for (double& a : record.ax) a *= scale;
    return fitRecord(model, record, {});
}

double rmsError(const Model& model, const FittedRecord& fit, const PoseLoopResult& loop, double rate) {
    const auto achieved = poseAcceleration(loop.p, 1.0 / rate, fit.t, 5);
    const std::size_t n = std::min(fit.t.size(), static_cast<std::size_t>(loop.t.back() / fit.dt) + 1);
    (void)model;
    return scoreShake(std::span(fit.ax).first(n), std::span(achieved[1]).first(n), fit.dt, 0.01, 0.5).rms_error;
}

TEST(ShakeTable, TheEstimatorControllerBeatsTheNoisyPoseSensorOnAWeakRecord) {
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    const Model model(robot);
    // El Centro at 5 %: a peak of 0.014 g, as weak as Hollywood Storage's 0.011 g
    const FittedRecord fit = elCentroExcerpt(model, 0.05);
    const Model plant_model(withPayload(robot, Payload{0.5, 0.0, Vector2::Zero()}));
    const double rate = 10000.0;
    // the table: 1 um encoders, the ADXL355, f_n = 6 Hz, the payload unknown
    RungeKuttaRobotPlant table_plant(plant_model);
    ShakeLoopOptions options;
    options.rate = rate;
    options.duration = fit.t.back();
    EstimatorReport report;
    const PoseLoopResult table = runShakeLoop(model, table_plant, fit.trajectory, options, &report);
    const double table_error = rmsError(model, fit, table, rate);
    // computed torque at f_n = 30 Hz on a pose sensor of 1 um and a rate sensor of 1e-5 m/s
    RungeKuttaRobotPlant pose_plant(plant_model);
    PoseController controller(model, ControlLaw::computed_torque, taskCriticallyDamped(30.0));
    PoseLoopOptions pose_options;
    pose_options.rate = rate;
    pose_options.duration = fit.t.back();
    pose_options.noise_angle = pose_options.noise_position = 1e-6;
    pose_options.noise_rate = 1e-5;
    const PoseLoopResult pose = runPoseLoop(controller, pose_plant, fit.trajectory, pose_options);
    const double pose_error = rmsError(model, fit, pose, rate);
    // measured: 1.45 % against 16.6 %; the estimator's pose error 0.11 um, the encoder pose's 0.72 um
    EXPECT_LT(table_error, 0.5 * pose_error) << table_error << " " << pose_error;
    EXPECT_LT(table_error, 0.05) << table_error;
    // the estimator's pose error is below the encoder pose noise
    EXPECT_LT(report.pose_rms_error(1), report.sigma_q(1)) << report.pose_rms_error(1) << " " << report.sigma_q(1);
    EXPECT_EQ(table.u_measured.size(), table.t.size());
    // the encoders' direct kinematics: Newton with the locked limbs' analytic Jacobian from the
    // cubic prediction takes one step to the pose and a second below 1e-8 that confirms round-off
    // (measured 2.00 per tick, never more, with 1 um encoders; 1.89 with 1 nm)
    EXPECT_GE(report.tracker_mean_iterations, 1.0);
    EXPECT_LE(report.tracker_mean_iterations, 2.0);
    EXPECT_EQ(report.tracker_max_iterations, 2);
}

TEST(ShakeTable, TheAccelerationCorrectionRemovesTheErrorOfAnUnknownPayload) {
    // exact accelerometers and fine encoders: what is left is the payload the model misses
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    const Model model(robot);
    const FittedRecord fit = elCentroExcerpt(model);
    const Model plant_model(withPayload(robot, Payload{0.5, 0.0, Vector2::Zero()}));
    const auto error = [&](double g) {
        RungeKuttaRobotPlant plant(plant_model);
        ShakeLoopOptions options;
        options.duration = fit.t.back();
        options.sensors.noise_u = 1e-9;
        options.sensors.accel_noise_density = 0.0;
        options.acceleration_gain = g;
        return rmsError(model, fit, runShakeLoop(model, plant, fit.trajectory, options), options.rate);
    };
    const double without = error(0.0), with = error(0.05);
    // measured: 2.35 % without, 0.37 % with
    EXPECT_GT(without, 0.015) << without;
    EXPECT_LT(with, 0.25 * without) << with << " " << without;
}

}  // namespace
}  // namespace nocdyn::test
