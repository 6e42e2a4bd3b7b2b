// Shake-table control with the sensors a table has: actuator encoders, platform accelerometers,
// a state estimator fusing them, model feed-forward with low-gain pose feedback and an
// acceleration-error correction.
//
// Sensors (TableSensors), read once per controller tick k (dt = 1 / rate):
//   encoders     u_m = u + n_u, n_u ~ N(0, sigma_u^2) per actuator; the pose p_m by the
//                direct-kinematics tracker (PoseTracker) from u_m. Near home the pose noise has
//                the covariance sigma_u^2 (A_p^T A_p)^-1 (A_p = A S(c), du = A_p dp/dt).
//   accelerometers  the platform's mean acceleration over the last tick,
//                a_k = (dp(t_k) - dp(t_k - dt)) / dt, plus white noise of density rho
//                [m/s^2 / sqrt(Hz)] (standard deviation rho sqrt(rate / 2) per sample), both
//                through the sensor's first-order low-pass of corner f_b:
//                y_k = y_(k-1) + beta (a_k + n_k - y_(k-1)), beta = 1 - exp(-2 pi f_b dt).
//                Two accelerometers a baseline b apart give the angular acceleration
//                (difference of their tangential readings over b): its noise density is
//                sqrt(2) rho / b.
// The controller never reads the plant's state: only u_m and y.
//
// Estimator (PoseEstimator): per pose coordinate q, the state x = [q, q'] driven by the measured
// acceleration, x_k = F x_(k-1) + G y_k, F = [1 dt; 0 1], G = [dt^2 / 2; dt], with process noise
// Q = sigma_y^2 G G^T (sigma_y^2 = rho^2 (pi / 2) f_b, the filtered noise's variance) and the
// encoder pose q_m = H x + v, H = [1 0], R = sigma_q^2. The gain is the steady-state Kalman gain
// K = P H^T / (H P H^T + R), P the fixed point of the Riccati recursion
//   P- = F P F^T + Q,  P = (I - K H) P-.
// Each tick: predict with y_k, correct with q_m. Encoder noise is passed below the crossover
// (sigma_q^2 / sigma_y^2)^(-1/4) rad/s and the accelerometer's above it.
//
// Control law (ShakeTableController), the model's inverse dynamics at the estimated state
// (p^, v^):
//   ddp_cmd = ddp_d + K_p (p_d - p^) + K_d (dp_d - v^) + c_k,
//   A_p^T tau = M_p(p^) ddp_cmd + h_p(p^, v^),
// with the acceleration correction c learning what the model misses (an unknown payload's
// inertia) from the accelerometers:
//   c_k = c_(k-1) + g (ddp_cmd,(k-1) - c_(k-1) - y_k),
// an integrator of the acceleration error with bandwidth about g rate / (2 pi) (off by default,
// g = 0). The pose gains (f_n of a few hertz) only hold the table's drift: the pose noise reaches the acceleration as
// K_p sigma_q, (2 pi f_n)^2 times the estimator's pose error.
#pragma once

#include <functional>
#include <vector>

#include "nocdyn/sim/control.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn {

/// Standard gravity [m/s^2] (the accelerometers' datasheets give g).
inline constexpr double kGravity = 9.80665;

/// The sensors of a shake table. Defaults: encoders of 1 um (a linear encoder's resolution);
/// the accelerometer Analog Devices ADXL355 (datasheet rev. A: noise density 22.5 ug/sqrt(Hz) at
/// the +-2 g range, output data rate 4 kHz with its digital low-pass at ODR / 4 = 1 kHz).
struct TableSensors {
    double noise_u = 1e-6;              ///< sigma_u of each actuator encoder [m or rad]
    double accel_noise_density = 22.5;  ///< rho [ug/sqrt(Hz)] (ADXL355)
    double accel_bandwidth = 1000.0;    ///< f_b [Hz]
    double accel_baseline = 0.1;        ///< b of the angular pair [m]
    bool no_accelerometer = false;      ///< encoders only (y = 0, g = 0)
    /// rho in SI [m/s^2 / sqrt(Hz)]
    [[nodiscard]] double rho() const { return accel_noise_density * 1e-6 * kGravity; }
    [[nodiscard]] bool accelerometer() const { return !no_accelerometer; }
};

/// Steady-state Kalman filter of the platform pose from encoder poses and accelerometers
/// (see the header comment). Allocation-free after construction.
class PoseEstimator {
public:
    /// sigma_q: the pose noise per coordinate [rad, m, m]; sigma_y: the measured acceleration's
    /// [rad/s^2, m/s^2, m/s^2]; dt [s]. Throws nocdyn::Error for a non-positive dt or sigma_q.
    PoseEstimator(double dt, const Vector3& sigma_q, const Vector3& sigma_y);
    void reset(const Pose& p, const Twist& dp);
    /// One tick: predict with the measured acceleration y, correct with the measured pose.
    void update(const Pose& p_measured, const Twist& y);
    [[nodiscard]] const Pose& pose() const { return p_; }
    [[nodiscard]] const Twist& rate() const { return v_; }
    /// Steady-state gain of coordinate i: [K_q, K_v].
    [[nodiscard]] Eigen::Vector2d gain(int i) const { return gain_.col(i); }

private:
    double dt_;
    Eigen::Matrix<double, 2, 3> gain_;
    Pose p_ = Pose::Zero();
    Twist v_ = Twist::Zero();
};

/// Pose noise of an encoder pose at `p`: sqrt(diag(sigma_u^2 (A_p^T A_p)^-1)) [rad, m, m]; for a
/// two-DOF robot (task map E) sqrt(diag(sigma_u^2 (E^T A_p^T A_p E)^-1)) over x, y, and 0 for
/// theta (held at home, no coordinate). Throws nocdyn::Error when p is out of reach or singular.
[[nodiscard]] Vector3 encoderPoseNoise(const Model& model, const Pose& p, double sigma_u);

/// Standard deviation of the filtered accelerometer noise per coordinate [rad/s^2, m/s^2, m/s^2]:
/// rho sqrt(pi f_b / 2), the angular one sqrt(2) / b times it (0 for a two-DOF robot,
/// task_dimension 2: no angular pair).
[[nodiscard]] Vector3 accelerometerNoise(const TableSensors& sensors, int task_dimension = 3);

struct ShakeLoopOptions : LoopClock {
    /// f_n of the pose feedback [Hz]; 6 Hz measured best on five real records with a payload the
    /// model does not know, 2 Hz when the model carries it (docs/earthquake-replay.md)
    double natural_frequency = 6.0;
    /// g of the acceleration correction (per tick); 0 by default: on those records the
    /// accelerometer noise it feeds back cost more than the payload error it removes
    double acceleration_gain = 0.0;
    TableSensors sensors;
    unsigned seed = 1;
    /// Keep u, u_d, tau and u_measured of every tick in the result. false: only their summaries
    /// (rms_error, peak_error, peak_tau) are kept, and each tick's u and tau go to on_tick; the
    /// result then holds t, p and p_d only, 56 bytes a tick instead of 664 (a long record's
    /// replay fits in memory).
    bool keep_actuators = true;
    /// Called once per tick with its index, time, u and the applied tau (may be empty).
    std::function<void(std::size_t, double, const ActuatorVector&, const ActuatorVector&)> on_tick;
};

/// What the estimator achieved over a run, against the plant's true state (kept for the report;
/// the controller never reads it).
struct EstimatorReport {
    Vector3 pose_rms_error = Vector3::Zero();  ///< RMS of p^ - p [rad, m, m]
    Vector3 rate_rms_error = Vector3::Zero();  ///< RMS of v^ - dp/dt
    Vector3 sigma_q = Vector3::Zero();         ///< the encoder pose noise assumed
    Vector3 sigma_y = Vector3::Zero();         ///< the accelerometer noise assumed
    /// The encoders' direct kinematics (PoseTracker: Newton on the locked limbs' equations with
    /// their analytic Jacobian): Newton steps per tick, mean and most.
    double tracker_mean_iterations = 0.0;
    int tracker_max_iterations = 0;
};

/// Runs the shake-table controller on `plant` along `trajectory` from (p_d(0), dp_d(0)): each
/// tick reads the encoders and accelerometers, estimates, computes the forces of the control law
/// on `model` (the controller's model: the nominal one or with an identified payload), clips them
/// at the efforts and holds them for one tick. `result.u_measured` holds the encoder readings.
/// Throws nocdyn::Error "t = ... s: reason" as runPoseLoop does.
[[nodiscard]] PoseLoopResult runShakeLoop(const Model& model, RobotPlant& plant, const PoseTrajectory& trajectory,
                                          const ShakeLoopOptions& options, EstimatorReport* report = nullptr);

}  // namespace nocdyn
