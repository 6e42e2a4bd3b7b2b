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

#include "loop.hpp"

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
    if (model.task_dimension == 2) {
        // the encoders see x, y only (A_t = A_p E); theta is no coordinate and carries no noise
        const Eigen::MatrixXd A_t = A_p * taskMap(model);
        const Eigen::Matrix2d normal = A_t.transpose() * A_t;
        const Eigen::Vector2d variance = (normal.inverse() * sigma_u * sigma_u).diagonal();
        return {0.0, std::sqrt(variance(0)), std::sqrt(variance(1))};
    }
    const Matrix3 normal = A_p.transpose() * A_p;
    const Matrix3 cov = normal.inverse() * sigma_u * sigma_u;
    return cov.diagonal().cwiseSqrt();
}

Vector3 accelerometerNoise(const TableSensors& sensors, int task_dimension) {
    const double s = sensors.rho() * std::sqrt(0.5 * std::numbers::pi * sensors.accel_bandwidth);
    return {task_dimension == 2 ? 0.0 : std::sqrt(2.0) * s / sensors.accel_baseline, s, s};
}

namespace {

/// The estimator's pose noise: a two-DOF robot's theta (no coordinate: it stays at home, its
/// innovation and its measured acceleration are zero) takes sigma_u, any positive value, since
/// the estimator's gain of each coordinate is its own.
Vector3 estimatedPoseNoise(Vector3 sigma_q, double sigma_u) {
    if (sigma_q(0) == 0.0) sigma_q(0) = sigma_u;
    return sigma_q;
}

/// runShakeLoop's sensing: the encoders through the tracker and the accelerometers, fused by the
/// estimator; the controller sees the estimate (p^, v^) and tracks the servo's demand
/// ddp_cmd + c at p = p^, dp = v^ (its own gains then see no error).
class TableSensing final : public detail::LoopSensing {
public:
    TableSensing(const Model& model, const ShakeLoopOptions& options, const PoseReference& start)
        : model_(model),
          sensors_(options.sensors),
          dt_(1.0 / options.rate),
          gains_(taskCriticallyDamped(options.natural_frequency)),
          sigma_q_(encoderPoseNoise(model, start.p, sensors_.noise_u)),
          sigma_y_(sensors_.accelerometer() ? accelerometerNoise(sensors_, model.task_dimension) : Vector3::Zero()),
          estimator_(dt_, estimatedPoseNoise(sigma_q_, sensors_.noise_u),
                     sensors_.accelerometer() ? sigma_y_ : Vector3::Constant(1e3)),
          g_(sensors_.accelerometer() ? options.acceleration_gain : 0.0),
          beta_(1.0 - std::exp(-2.0 * std::numbers::pi * sensors_.accel_bandwidth * dt_)),
          white_(std::sqrt(0.5 * options.rate)),
          density_(model.task_dimension == 2 ? 0.0 : std::sqrt(2.0) * sensors_.rho() / sensors_.accel_baseline,
                   sensors_.rho(), sensors_.rho()),
          rng_(options.seed),
          sensor_(model),
          tracker_(start.p),
          tracker_options_(noisyEncoderTrackerOptions(model, sensors_.noise_u)),
          u_measured_(model.actuators),
          rate_before_(start.dp) {
        estimator_.reset(start.p, start.dp);
    }

    void sense(double t, const RobotPlant& plant, const Pose& p, const Twist& dp, const PoseReference& reference,
               const Twist& ddp_ff, detail::Sensed& out) override {
        // accelerometers: the mean acceleration of the last tick, noise, the sensor's low-pass
        if (sensors_.accelerometer() && !first_) {
            const Twist a = (dp - rate_before_) / dt_;
            for (int i = 0; i < 3; ++i) y_(i) += beta_ * (a(i) + density_(i) * white_ * normal_(rng_) - y_(i));
        }
        rate_before_ = dp;
        // encoders and the tracker
        u_measured_ = plant.u();
        for (int a = 0; a < model_.actuators; ++a) u_measured_(a) += sensors_.noise_u * normal_(rng_);
        TrackerReport tracked;
        if (const Status status = tracker_.step(model_, sensor_, u_measured_, tracker_options_, &tracked); !status) {
            detail::failTick(model_, t, status, "direct kinematics of the encoders (tracker)");
        }
        tracker_steps_ += tracked.iterations;
        tracker_most_ = std::max(tracker_most_, tracked.iterations);
        if (!first_) estimator_.update(tracker_.pose(), y_);
        pose_sq_ += (estimator_.pose() - p).cwiseAbs2();
        rate_sq_ += (estimator_.rate() - dp).cwiseAbs2();
        // the acceleration correction from the last tick's demand
        if (!first_) correction_ += g_ * (commanded_ - y_);
        first_ = false;
        const Vector3 servo = gains_.kp.cwiseProduct(reference.p - estimator_.pose()) +
                              gains_.kd.cwiseProduct(reference.dp - estimator_.rate());
        commanded_ = ddp_ff + servo;
        out.command = reference;
        out.command.ddp = commanded_ + correction_;
        // the servo is inside ddp: the controller's own gains see p = p_d, dp = dp_d
        out.command.p = estimator_.pose();
        out.command.dp = estimator_.rate();
        out.p = estimator_.pose();
        out.dp = estimator_.rate();
        out.u_measured = &u_measured_;
    }
    [[nodiscard]] bool readsEncoders() const override { return true; }

    /// The estimator against the plant's true state over `ticks` ticks.
    void report(double ticks, EstimatorReport& r) const {
        r.pose_rms_error = (pose_sq_ / ticks).cwiseSqrt();
        r.rate_rms_error = (rate_sq_ / ticks).cwiseSqrt();
        r.sigma_q = sigma_q_;
        r.sigma_y = sigma_y_;
        r.tracker_mean_iterations = static_cast<double>(tracker_steps_) / ticks;
        r.tracker_max_iterations = tracker_most_;
    }

private:
    const Model& model_;
    const TableSensors& sensors_;
    double dt_;
    TaskGains gains_;
    Vector3 sigma_q_, sigma_y_;
    PoseEstimator estimator_;
    double g_, beta_, white_;
    Vector3 density_;
    std::mt19937 rng_;
    std::normal_distribution<double> normal_{0.0, 1.0};
    Data sensor_;
    PoseTracker tracker_;
    TrackerOptions tracker_options_;
    ActuatorVector u_measured_;
    Twist y_ = Twist::Zero();           // the accelerometers' filtered output
    Twist correction_ = Twist::Zero();  // c
    Twist commanded_ = Twist::Zero();   // ddp_cmd - c of the last tick
    Twist rate_before_;
    Vector3 pose_sq_ = Vector3::Zero(), rate_sq_ = Vector3::Zero();
    bool first_ = true;
    long long tracker_steps_ = 0;  // Newton steps of the tracker over the run
    int tracker_most_ = 0;
};

}  // namespace

PoseLoopResult runShakeLoop(const Model& model, RobotPlant& plant, const PoseTrajectory& trajectory,
                            const ShakeLoopOptions& options, EstimatorReport* report) {
    const TableSensors& sensors = options.sensors;
    if (!(sensors.noise_u > 0.0) || !(sensors.accel_noise_density >= 0.0) || !(sensors.accel_bandwidth > 0.0) ||
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
    PoseController controller(model, ControlLaw::computed_torque, taskCriticallyDamped(options.natural_frequency));
    PoseLoopResult result;
    {
        std::ostringstream name;
        name << "shake table: Kalman estimator of encoders" << (sensors.accelerometer() ? " and accelerometers" : "")
             << ", model feed-forward, pose feedback f_n = " << options.natural_frequency << " Hz";
        if (sensors.accelerometer() && options.acceleration_gain > 0.0) {
            name << ", acceleration correction g = " << options.acceleration_gain;
        }
        result.controller = name.str();
    }
    result.plant = plant.name();
    result.actuators = model.actuators;

    Data data(model);
    PoseReference reference;
    if (const Status status = poseReference(model, data, trajectory, 0.0, reference); !status) {
        detail::failTick(model, 0.0, status, "reference");
    }
    plant.reset(reference.p, reference.dp);
    TableSensing sensing(model, options, reference);
    detail::runTicks(controller, plant, trajectory, times, data, sensing, options,
                     {options.keep_actuators, &options.on_tick}, result);
    if (report != nullptr) sensing.report(static_cast<double>(result.t.size()), *report);
    return result;
}

}  // namespace nocdyn
