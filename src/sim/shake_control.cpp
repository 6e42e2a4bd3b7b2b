// Shake-table sensing, estimation and control (see shake_control.hpp).
#include "nocdyn/sim/shake_control.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/analysis/sampling.hpp"

namespace nocdyn {

PoseEstimator::PoseEstimator(double dt, const Vector3& sigma_q, const Vector3& sigma_y) : dt_(dt) {
    if (!(dt > 0.0 && std::isfinite(dt))) throw Error("estimator: the time step must be positive");
    if (!(sigma_q.minCoeff() > 0.0 && sigma_q.allFinite() && sigma_y.minCoeff() >= 0.0 && sigma_y.allFinite())) {
        throw Error("estimator: the pose noise must be positive and the acceleration noise >= 0");
    }
    Eigen::Matrix2d F;
    F << 1.0, dt, 0.0, 1.0;
    const Eigen::Vector2d G(0.5 * dt * dt, dt);
    for (int i = 0; i < 3; ++i) {
        const double r = sigma_q(i) * sigma_q(i);
        // a floor on the process noise keeps the gain finite when the accelerometer is exact
        const double q = std::max(sigma_y(i) * sigma_y(i), 1e-12 * r / (dt * dt * dt * dt));
        const Eigen::Matrix2d Q = q * G * G.transpose();
        Eigen::Matrix2d P = Eigen::Matrix2d::Identity() * r;
        Eigen::Vector2d K = Eigen::Vector2d::Zero();
        // the Riccati recursion to its fixed point (the gain converges geometrically)
        for (int k = 0; k < 1000000; ++k) {
            const Eigen::Matrix2d P_minus = F * P * F.transpose() + Q;
            const Eigen::Vector2d K_next = P_minus.col(0) / (P_minus(0, 0) + r);
            P = P_minus - K_next * P_minus.row(0);
            const bool converged = (K_next - K).cwiseAbs().maxCoeff() <= 1e-13 * K_next.cwiseAbs().maxCoeff();
            K = K_next;
            if (converged && k > 10) break;
        }
        gain_.col(i) = K;
    }
}

void PoseEstimator::reset(const Pose& p, const Twist& dp) {
    p_ = p;
    v_ = dp;
}

void PoseEstimator::update(const Pose& p_measured, const Twist& y) {
    // predict: x = F x + G y
    p_ += dt_ * v_ + 0.5 * dt_ * dt_ * y;
    v_ += dt_ * y;
    // correct: x += K (q_m - q)
    const Vector3 innovation = p_measured - p_;
    p_ += gain_.row(0).transpose().cwiseProduct(innovation);
    v_ += gain_.row(1).transpose().cwiseProduct(innovation);
}

Vector3 encoderPoseNoise(const Model& model, const Pose& p, double sigma_u) {
    Data data(model);
    Status status = inverseDisplacement(model, data, p);
    if (status) status = velocityFromPlatformTwist(model, data, Twist::Zero());
    if (!status) throw Error("encoder pose noise: " + describe(status, model));
    const ActuationMatrix A_p = data.A * platformTwistMap(p.tail<2>());
    const Matrix3 normal = A_p.transpose() * A_p;
    const Matrix3 cov = normal.inverse() * sigma_u * sigma_u;
    return cov.diagonal().cwiseSqrt();
}

Vector3 accelerometerNoise(const TableSensors& sensors) {
    const double s = sensors.accel_noise_density * std::sqrt(0.5 * std::numbers::pi * sensors.accel_bandwidth);
    return {std::sqrt(2.0) * s / sensors.accel_baseline, s, s};
}

PoseLoopResult runShakeLoop(const Model& model, RobotPlant& plant, const PoseTrajectory& trajectory,
                            const ShakeLoopOptions& options, EstimatorReport* report) {
    const TableSensors& sensors = options.sensors;
    if (!(sensors.encoder_noise > 0.0) || !(sensors.accel_noise_density >= 0.0) || !(sensors.accel_bandwidth > 0.0) ||
        !(sensors.accel_baseline > 0.0)) {
        throw Error(
            "shake table: encoder noise, accelerometer bandwidth and baseline must be positive, the noise "
            "density >= 0");
    }
    if (!(options.acceleration_gain >= 0.0 && options.acceleration_gain < 1.0)) {
        throw Error("shake table: the acceleration gain must be in [0, 1)");
    }
    const std::vector<double> times = sampleTimes(options.duration, options.rate);
    requireRateAboveNyquist(trajectory, options.rate);
    requireReachable(model, trajectory, times.back());
    const double dt = 1.0 / options.rate;
    const int n = model.actuators;
    const TaskGains gains = taskCriticallyDamped(options.natural_frequency);
    PoseController controller(model, ControlLaw::computed_torque, gains);
    PoseLoopResult result;
    {
        std::ostringstream name;
        name << "shake table: Kalman estimator of encoders" << (sensors.accelerometer ? " and accelerometers" : "")
             << ", model feed-forward, pose feedback f_n = " << options.natural_frequency << " Hz";
        if (sensors.accelerometer && options.acceleration_gain > 0.0) {
            name << ", acceleration correction g = " << options.acceleration_gain;
        }
        result.controller = name.str();
    }
    result.plant = plant.name();
    result.actuators = n;
    for (auto* v : {&result.p, &result.p_d}) v->reserve(times.size());
    if (options.keep_actuators) {
        for (auto* v : {&result.u, &result.u_d, &result.tau, &result.u_measured}) v->reserve(times.size());
    }
    result.t.reserve(times.size());
    // the actuator summaries, accumulated here when the ticks are not kept
    const auto un = static_cast<std::size_t>(n);
    std::vector<double> sum_sq(un, 0.0), peak(un, 0.0), peak_tau(un, 0.0);

    Data data(model), sensor(model);
    PoseReference reference;
    const auto fail = [&](double t, const Status& status, const char* what) {
        std::ostringstream out;
        out.precision(9);
        out << "t = " << t << " s: " << what << ": " << describe(status, model);
        throw Error(out.str());
    };
    if (const Status status = poseReference(model, data, trajectory, 0.0, reference); !status) {
        fail(0.0, status, "reference");
    }
    plant.reset(reference.p, reference.dp);

    const Vector3 sigma_q = encoderPoseNoise(model, reference.p, sensors.encoder_noise);
    const Vector3 sigma_y = sensors.accelerometer ? accelerometerNoise(sensors) : Vector3::Zero();
    PoseEstimator estimator(dt, sigma_q, sensors.accelerometer ? sigma_y : Vector3::Constant(1e3));
    estimator.reset(reference.p, reference.dp);
    const double g = sensors.accelerometer ? options.acceleration_gain : 0.0;
    const double beta = 1.0 - std::exp(-2.0 * std::numbers::pi * sensors.accel_bandwidth * dt);
    const double white = std::sqrt(0.5 * options.rate);
    const Vector3 density(std::sqrt(2.0) * sensors.accel_noise_density / sensors.accel_baseline,
                          sensors.accel_noise_density, sensors.accel_noise_density);

    std::mt19937 rng(options.seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    PoseTracker tracker(reference.p);
    const TrackerOptions tracker_options = noisyEncoderTrackerOptions(model, sensors.encoder_noise);

    ActuatorVector tau(n), u_measured(n);
    Twist y = Twist::Zero();           // the accelerometers' filtered output
    Twist correction = Twist::Zero();  // c
    Twist commanded = Twist::Zero();   // ddp_cmd - c of the last tick
    Twist rate_before = reference.dp;
    Pose next_p, next_dp, next_ddp;
    Vector3 pose_sq = Vector3::Zero(), rate_sq = Vector3::Zero();
    bool first = true;
    for (const double t : times) {
        if (options.progress) options.progress(t);
        if (const Status status = poseReference(model, data, trajectory, t, reference); !status) {
            fail(t, status, "reference");
        }
        trajectory.evaluate(t + dt, next_p, next_dp, next_ddp);
        const Twist feedforward = (next_dp - reference.dp) / dt;
        const Pose p = plant.pose();
        const Twist dp = plant.poseRate();
        if (!p.allFinite() || !dp.allFinite()) fail(t, {StatusCode::not_finite, -1, 0.0}, "plant state");
        // accelerometers: the mean acceleration of the last tick, noise, the sensor's low-pass
        if (sensors.accelerometer && !first) {
            const Twist a = (dp - rate_before) / dt;
            for (int i = 0; i < 3; ++i) y(i) += beta * (a(i) + density(i) * white * normal(rng) - y(i));
        }
        rate_before = dp;
        // encoders and the tracker
        u_measured = plant.u();
        for (int a = 0; a < n; ++a) u_measured(a) += sensors.encoder_noise * normal(rng);
        if (const Status status = tracker.step(model, sensor, u_measured, tracker_options); !status) {
            fail(t, status, "direct kinematics of the encoders (tracker)");
        }
        if (!first) estimator.update(tracker.pose(), y);
        pose_sq += (estimator.pose() - p).cwiseAbs2();
        rate_sq += (estimator.rate() - dp).cwiseAbs2();
        // the acceleration correction from the last tick's demand
        if (!first) correction += g * (commanded - y);
        first = false;
        const Vector3 servo = gains.kp.cwiseProduct(reference.p - estimator.pose()) +
                              gains.kd.cwiseProduct(reference.dp - estimator.rate());
        commanded = feedforward + servo;
        PoseReference command = reference;
        command.ddp = commanded + correction;
        // the servo is inside ddp: the controller's own gains see p = p_d, dp = dp_d
        command.p = estimator.pose();
        command.dp = estimator.rate();
        if (const Status status = controller.compute(estimator.pose(), estimator.rate(), command, tau); !status) {
            fail(t, status, "controller");
        }
        if (options.saturation && controller.saturate(tau)) ++result.saturated_ticks;
        const ActuatorVector& u_now = plant.u();
        if (options.on_tick) options.on_tick(result.t.size(), t, u_now, tau);
        result.t.push_back(t);
        result.p.push_back(p);
        result.p_d.push_back(reference.p);
        if (options.keep_actuators) {
            result.u.push_back(u_now);
            result.u_d.push_back(reference.u);
            result.tau.push_back(tau);
            result.u_measured.push_back(u_measured);
        } else {
            for (int a = 0; a < n; ++a) {
                const auto ai = static_cast<std::size_t>(a);
                const double e = std::abs(reference.u(a) - u_now(a));
                sum_sq[ai] += e * e;
                peak[ai] = std::max(peak[ai], e);
                peak_tau[ai] = std::max(peak_tau[ai], std::abs(tau(a)));
            }
        }
        plant.setForces(tau);
        plant.advance(dt);
    }

    summarizeLoop(result);
    if (!options.keep_actuators && !result.t.empty()) {
        result.rms_error.resize(un);
        for (std::size_t a = 0; a < un; ++a)
            result.rms_error[a] = std::sqrt(sum_sq[a] / static_cast<double>(result.t.size()));
        result.peak_error = peak;
        result.peak_tau = peak_tau;
    }
    const double count = static_cast<double>(result.t.size());
    if (report != nullptr) {
        report->pose_rms_error = (pose_sq / count).cwiseSqrt();
        report->rate_rms_error = (rate_sq / count).cwiseSqrt();
        report->sigma_q = sigma_q;
        report->sigma_y = sigma_y;
    }
    return result;
}

}  // namespace nocdyn
