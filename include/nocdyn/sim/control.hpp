// Model-based control of any planar parallel robot (model.hpp) in the platform coordinates,
// and its closed-loop simulation on any plant.
//
// The controller measures the platform pose p = [theta, x_c, y_c] (eq. 1) and its rate
// dp/dt = t_M (eq. 2), as a plant's pose sensor (or a direct kinematics) gives them, and
// tracks a pose trajectory p_d(t):
//
// Computed torque (inverse-dynamics control in the task space):
//   ddp_cmd = ddp_d + K_d (dp_d - dp) + K_p (p_d - p)
//   tau     = inverse dynamics at the measured (p, dp) with d2p/dt2 = ddp_cmd,
// i.e. A_p^T tau = M_p(p) ddp_cmd + h_p(p, dp) (forward_dynamics.hpp), tau the minimum-norm
// solution when the robot is redundantly actuated (n > 3: the actuators share the load and no
// internal force is commanded). With a perfect model and no saturation the pose error
// e = p_d - p obeys e'' + K_d e' + K_p e = 0 per coordinate; taskCriticallyDamped(f_n) gives
// K_p = w^2, K_d = 2 w, w = 2 pi f_n (critically damped).
//
// PD (no dynamic model, for comparison): a task-space PD wrench mapped to the actuators,
//   A_p(p)^T tau = M_p(home) (K_p (p_d - p) + K_d (dp_d - dp)),
// tau minimum-norm again. The constant M_p(home) scales the gains so that the error dynamics
// would match computed torque if the inertia were constant and there were no velocity,
// gravity or friction terms; only the kinematics A_p at the measured pose is used.
//
// Every actuator force is clipped at its joint's effort limit (when finite). compute() is
// allocation-free. A payload the controller does not know is a plant built from another
// description (withPayload); the controller keeps the nominal model.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "nocdyn/choice.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/sim/plant.hpp"
#include "nocdyn/status.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn {

/// Desired motion at one instant: pose, rate and acceleration from the trajectory, and the
/// actuator variables and rates the controller's model gives for them (inverse displacement).
struct PoseReference {
    Pose p = Pose::Zero();
    Twist dp = Twist::Zero();
    Twist ddp = Twist::Zero();
    ActuatorVector u;   ///< u_d [m or rad]
    ActuatorVector du;  ///< du_d [m/s or rad/s]
};

/// Reference at time t on `model` (data: the model's workspace). Fails as inverseDisplacement
/// and velocityFromPlatformTwist do. Allocation-free.
Status poseReference(const Model& model, Data& data, const PoseTrajectory& trajectory, double t,
                     PoseReference& reference);

/// Diagonal task-space gains on [theta, x, y].
struct TaskGains {
    Vector3 kp = Vector3::Zero();  ///< [1/s^2]
    Vector3 kd = Vector3::Zero();  ///< [1/s]
};

/// K_p = (2 pi f_n)^2, K_d = 2 (2 pi f_n): a critically damped pose error, f_n [Hz].
[[nodiscard]] TaskGains taskCriticallyDamped(double natural_frequency);

enum class ControlLaw { computed_torque, pd };

inline constexpr std::array<Choice<ControlLaw>, 2> kControlLaws{
    {{ControlLaw::computed_torque, "computed-torque"}, {ControlLaw::pd, "pd"}}};
[[nodiscard]] constexpr std::span<const Choice<ControlLaw>> choices(ControlLaw) { return kControlLaws; }

/// "computed-torque" or "pd".
[[nodiscard]] inline const char* name(ControlLaw law) { return nameOf(law).data(); }

/// The feedback a user chooses: the law, and the natural frequency f_n of the critically damped
/// pose error (taskCriticallyDamped).
struct FeedbackSettings {
    ControlLaw controller = ControlLaw::computed_torque;  ///< computed-torque or pd
    double natural_frequency = 50.0;                      ///< f_n of the error dynamics [Hz]
};

/// Task-space controller of one robot (see the header comment). Holds a copy of the model.
class PoseController {
public:
    /// Throws nocdyn::Error when the model is singular at home (PD needs M_p there).
    PoseController(const Model& model, ControlLaw law, const TaskGains& gains);

    /// Actuator forces (n values, not yet clipped) from the measured pose and rate and the
    /// reference. Fails as inverseDisplacement / velocityFromPlatformTwist at the measured
    /// pose. Allocation-free.
    Status compute(const Pose& p, const Twist& dp, const PoseReference& reference, ActuatorVector& tau);

    /// Clips tau at each actuator's effort limit; true when some force was clipped.
    bool saturate(ActuatorVector& tau) const;

    [[nodiscard]] ControlLaw law() const { return law_; }
    [[nodiscard]] const Model& model() const { return model_; }
    /// Effort limit of each actuator (+infinity when the file gives none) [N or N m].
    [[nodiscard]] const ActuatorVector& effort() const { return effort_; }

private:
    Model model_;
    Data data_;
    ControlLaw law_;
    TaskGains gains_;
    Matrix3 M_home_ = Matrix3::Identity();
    ActuatorVector effort_;
};

/// A rigid payload fixed on the platform.
struct Payload {
    double mass = 0.0;              ///< [kg]
    double inertia = 0.0;           ///< about its own c.o.m. [kg m^2]
    Vector2 com = Vector2::Zero();  ///< its c.o.m. in the platform frame (origin C) [m]
};

/// The robot with the payload merged into the platform (mass, c.o.m. and inertia about the
/// combined c.o.m. by the parallel-axis theorem). Throws nocdyn::Error for negative or
/// non-finite values.
[[nodiscard]] RobotDescription withPayload(RobotDescription robot, const Payload& payload);

/// A pose sensor's noise: zero-mean Gaussian draws added to each measured pose coordinate and
/// rate, planar (theta; x_c, y_c) or spatial (roll, pitch, yaw; x, y, z).
struct PoseSensorNoise {
    double noise_angle = 0.0;     ///< std. dev. of each measured angle [rad]
    double noise_position = 0.0;  ///< of each measured position coordinate [m]
    double noise_rate = 0.0;      ///< of each component of dp/dt [rad/s, m/s]
    unsigned seed = 1;            ///< noise generator seed
};

/// The sensor a user describes by one sigma for every pose coordinate (`noise_pose`, in m and rad
/// alike, as the command line's --noise-pose) and one for every rate.
[[nodiscard]] constexpr PoseSensorNoise poseSensorNoise(double noise_pose, double noise_rate, unsigned seed) {
    return {noise_pose, noise_pose, noise_rate, seed};
}

/// What every closed loop (planar, shake table, spatial) is run by: the controller's clock, the
/// run's length, the clipping of the forces and a progress callback.
struct LoopClock {
    double rate = 10000.0;   ///< controller ticks per second [Hz]
    double duration = 0.2;   ///< [s]
    bool saturation = true;  ///< clip at each actuator's effort
    /// Called at each tick with its time [s] (e.g. a progress line); none by default.
    std::function<void(double t)> progress = {};
};

struct PoseLoopOptions : LoopClock, PoseSensorNoise {
    /// Measure as a robot without a pose sensor does: its encoders' u (+ noise_u) and their
    /// rates du (+ noise_du), the pose p by the direct-kinematics tracker (PoseTracker, the
    /// working mode from the reference's start) and dp/dt from A_p(p) dp/dt = du (least
    /// squares when redundant). noise_angle, noise_position and noise_rate are then unused.
    bool encoders = false;
    double noise_u = 0.0;   ///< std. dev. of each encoder [m or rad]
    double noise_du = 0.0;  ///< of each encoder rate [m/s or rad/s]
};

/// One closed-loop run, one row per controller tick (state at the tick, before its forces act).
struct PoseLoopResult {
    std::string controller, plant;
    int actuators = 0;
    std::vector<double> t;
    std::vector<Pose> p, p_d;
    std::vector<ActuatorVector> u, u_d, tau;
    /// Encoders (PoseLoopOptions::encoders): u as the encoders read it at each tick, noise_u
    /// included, i.e. what the controller saw; empty otherwise.
    std::vector<ActuatorVector> u_measured;
    Vector3 pose_rms_error = Vector3::Zero();   ///< RMS of p_d - p [rad, m, m]
    Vector3 pose_peak_error = Vector3::Zero();  ///< max |p_d - p|
    /// The same over the second half of the run (after the transients).
    Vector3 pose_late_peak_error = Vector3::Zero();
    std::vector<double> rms_error, peak_error;  ///< of u_d - u per actuator [m or rad]
    std::vector<double> peak_tau;               ///< max |tau| per actuator (after clipping)
    std::size_t saturated_ticks = 0;            ///< ticks where some force was clipped
    /// RMS and max over the ticks of |p_measured - p| (the sensor's error as the controller
    /// saw it) [rad, m, m].
    Vector3 measurement_rms_error = Vector3::Zero();
    Vector3 measurement_peak_error = Vector3::Zero();
    int tracker_max_iterations = 0;  ///< encoders: most Newton steps of a tracker step
};

/// Fills the summaries of a run from its rows: pose_rms_error, pose_peak_error,
/// pose_late_peak_error, rms_error, peak_error and peak_tau (measurement errors untouched).
void summarizeLoop(PoseLoopResult& result);

/// The tracker's options for encoders of noise std. dev. noise_u: on a redundant robot noisy
/// encoders are inconsistent by about noise_u (over the joint scale), so the accepted residual is
/// at least 10 noise_u / joint scale.
[[nodiscard]] TrackerOptions noisyEncoderTrackerOptions(const Model& model, double noise_u);

/// Runs `controller` on `plant` along `trajectory`: the plant starts at (p_d(0), dp_d(0)) (or
/// at `start` when given, to see the error decay); each tick measures (p, dp) (+ noise; or
/// through the encoders and the tracker, options.encoders),
/// computes the forces, clips them, holds them for dt = 1 / rate. The feedforward acceleration
/// is the reference's mean over the hold, (dp_d(t + dt) - dp_d(t)) / dt: the acceleration at t
/// would lag by half a tick, a steady error of about |d3p_d/dt3| dt / (2 K_p) (6 urad for
/// trajectory 1 at 10 kHz and f_n = 50 Hz). Throws nocdyn::Error "t = ... s:
/// reason" when the reference or the controller fails, and before the first tick when the
/// rate is not above twice the trajectory's highest frequency or the reference leaves the
/// workspace (requireReachable). With encoders, a tick where the tracker loses the working mode
/// (or the measured pose is singular) stops the run the same way, naming the limb.
[[nodiscard]] PoseLoopResult runPoseLoop(PoseController& controller, RobotPlant& plant,
                                         const PoseTrajectory& trajectory, const PoseLoopOptions& options,
                                         const Pose* start = nullptr);

}  // namespace nocdyn
