// Model-based control in actuator space of any robot with three actuators (model.hpp), and
// closed-loop simulation. (Task-space control of any robot, redundant ones included:
// general_control.hpp.)
//
// Computed torque (inverse-dynamics control) on the NOC model of eq. 20:
//   tau = I(u) (ddu_d + K_d (du_d - du) + K_p (u_d - u)) + C(u, du) du
// With a perfect model the error e = u_d - u obeys e'' + K_d e' + K_p e = 0 (per actuator);
// criticallyDamped(f_n) chooses K_p = w^2, K_d = 2 w, w = 2 pi f_n.
// PD control for comparison:  tau = K_p (u_d - u) + K_d (du_d - du)   [N/m, N s/m].
// The desired (u_d, du_d, ddu_d) come from the pose trajectory through the controller's own
// model: inverse displacement, eq. 5 and its time derivative. The controller runs at a fixed
// rate; its forces are held between ticks (zero-order hold). compute() is allocation-free.
//
// With three actuators the NOC's independent coordinates are the actuator rates (v = du,
// dynamics.hpp), so I and C are the 3 x 3 actuator-space matrices of eq. 20.
//
// The plant is any Plant: our own forward dynamics (SimulatorPlant) or an independent engine
// (the Simbody model, adapted in apps/nocdyn/simbody_plant.hpp). runClosedLoop adds actuator
// saturation at the peak force and optional Gaussian sensor noise; a model mismatch is a
// plant built from another robot than the controller's model.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "nocdyn/forward_dynamics.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/robot.hpp"
#include "nocdyn/status.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::control {

/// Actuator-space vector of a robot with three actuators [m or rad, N or N m].
using JointVector = Vector3;

/// Desired motion at one instant, in pose and actuator space.
struct Reference {
    Pose p = Pose::Zero();
    Twist dp = Twist::Zero();
    Twist ddp = Twist::Zero();
    JointVector u = JointVector::Zero();    ///< u_d [m]
    JointVector du = JointVector::Zero();   ///< du_d [m/s]
    JointVector ddu = JointVector::Zero();  ///< ddu_d [m/s^2]
};

/// Reference at time t: p, dp, ddp from the trajectory, then u_d, du_d, ddu_d by inverse
/// displacement, eq. 5 and its derivative on `model` (three actuators). Allocation-free.
Status desiredMotion(const Model& model, Data& data, const PoseTrajectory& trajectory, double t, Reference& reference);

/// Diagonal gains, one entry per actuator.
struct Gains {
    JointVector kp = JointVector::Zero();
    JointVector kd = JointVector::Zero();
};

/// Computed-torque gains for a critically damped error, natural frequency f_n [Hz]:
/// K_p = (2 pi f_n)^2 [1/s^2], K_d = 2 (2 pi f_n) [1/s].
[[nodiscard]] Gains criticallyDamped(double natural_frequency);

/// PD gains with the same error dynamics as `computed_torque` would have if the inertia were
/// constant, diagonal and equal to diag(I) at the reference posture (home): K = diag(I_ref) K_ct
/// [N/m, N s/m].
[[nodiscard]] Gains equivalentPdGains(const Model& model, const Gains& computed_torque);

/// A controller ticking at a fixed rate. compute() must not allocate.
class Controller {
public:
    virtual ~Controller() = default;
    /// Prepares for a run starting at platform pose p.
    virtual void reset(const Pose& p) = 0;
    /// Actuator forces from the measured state (u, du) and the reference.
    virtual Status compute(const JointVector& u, const JointVector& du, const Reference& reference,
                           JointVector& tau) = 0;
    [[nodiscard]] virtual std::string name() const = 0;
};

/// tau = I(u) (ddu_d + K_d e' + K_p e) + C(u, du) du, with I and C (eq. 23) at the pose that
/// the direct-kinematics tracker finds for the measured u, starting from its last pose.
/// Holds a copy of the model; throws nocdyn::Error unless it has three actuators.
class ComputedTorqueController final : public Controller {
public:
    ComputedTorqueController(const Model& model, const Gains& gains);
    void reset(const Pose& p) override;
    Status compute(const JointVector& u, const JointVector& du, const Reference& reference, JointVector& tau) override;
    [[nodiscard]] std::string name() const override { return "computed-torque"; }
    [[nodiscard]] const Data& data() const { return data_; }

private:
    Model model_;
    Gains gains_;
    Data data_;
    ActuatorVector u_, du_;
    Pose pose_ = Pose::Zero();
};

/// tau = K_p e + K_d e' (no model).
class PdController final : public Controller {
public:
    explicit PdController(const Gains& gains) : gains_(gains) {}
    void reset(const Pose&) override {}
    Status compute(const JointVector& u, const JointVector& du, const Reference& reference, JointVector& tau) override;
    [[nodiscard]] std::string name() const override { return "pd"; }

private:
    Gains gains_;
};

/// The robot being controlled. Not real-time: methods may throw nocdyn::Error.
class Plant {
public:
    virtual ~Plant() = default;
    /// Assembles the robot at pose p with platform twist dp, time 0, zero forces.
    virtual void reset(const Pose& p, const Twist& dp) = 0;
    /// Actuator forces [N], held until changed.
    virtual void setForces(const JointVector& tau) = 0;
    /// Integrates dt seconds forward.
    virtual void advance(double dt) = 0;
    [[nodiscard]] virtual double time() const = 0;
    [[nodiscard]] virtual JointVector u() const = 0;
    [[nodiscard]] virtual JointVector du() const = 0;
    [[nodiscard]] virtual Pose pose() const = 0;
    [[nodiscard]] virtual Twist poseRate() const = 0;
    [[nodiscard]] virtual std::string name() const = 0;
};

/// Plant on nocdyn's own forward dynamics (Simulator) of a robot with three actuators.
class SimulatorPlant final : public Plant {
public:
    /// Throws nocdyn::Error unless the model has three actuators.
    explicit SimulatorPlant(const Model& model, const SimulatorOptions& options = {});
    void reset(const Pose& p, const Twist& dp) override;
    void setForces(const JointVector& tau) override { tau_ = tau; }
    void advance(double dt) override;
    [[nodiscard]] double time() const override { return simulator_.time(); }
    [[nodiscard]] JointVector u() const override { return simulator_.u(); }
    [[nodiscard]] JointVector du() const override { return simulator_.du(); }
    [[nodiscard]] Pose pose() const override { return simulator_.pose(); }
    [[nodiscard]] Twist poseRate() const override { return simulator_.poseRate(); }
    [[nodiscard]] std::string name() const override { return "nocdyn forward dynamics"; }

private:
    Simulator simulator_;
    JointVector tau_ = JointVector::Zero();
};

struct ClosedLoopOptions {
    double rate = 10000.0;      ///< controller ticks per second [Hz]
    double duration = 0.2;      ///< [s]
    double peak_force = 262.0;  ///< actuator saturation |tau_j| <= peak_force [N]; <= 0: none
    double noise_u = 0.0;       ///< standard deviation of the u measurement noise [m]
    double noise_du = 0.0;      ///< standard deviation of the du measurement noise [m/s]
    unsigned seed = 1;          ///< noise generator seed
};

/// One closed-loop run, one row per controller tick (state at the tick, before the forces act).
struct ClosedLoopResult {
    std::string controller, plant;
    std::vector<double> t;
    std::vector<Pose> p, p_d;
    std::vector<JointVector> u, u_d, du, tau;
    JointVector rms_error = JointVector::Zero();   ///< RMS of u_d - u per actuator [m]
    JointVector peak_error = JointVector::Zero();  ///< max |u_d - u| per actuator [m]
    Vector3 pose_rms_error = Vector3::Zero();      ///< RMS of p_d - p [rad, m, m]
    Vector3 pose_peak_error = Vector3::Zero();     ///< max |p_d - p| [rad, m, m]
    std::size_t saturated_ticks = 0;               ///< ticks where some force was clipped
};

/// Runs `controller` on `plant` along `trajectory`: the plant starts on the trajectory
/// (p_d(0), dp_d(0)); each tick measures (u, du) (+ noise), computes the reference on
/// `controller_model`, the forces, clips them at the peak force, holds them for 1 / rate.
/// Throws nocdyn::Error "t = ... s: reason" when the reference or the controller fails, and
/// before the first tick when the rate is not above twice the trajectory's highest frequency
/// or the reference leaves the workspace between ticks (requireReachable), and when the
/// model does not have three actuators.
[[nodiscard]] ClosedLoopResult runClosedLoop(Controller& controller, const Model& controller_model, Plant& plant,
                                             const PoseTrajectory& trajectory, const ClosedLoopOptions& options);

/// CSV table: t, x, y, theta, x_d, y_d, theta_d, u1..u3, u1_d..u3_d, e1..e3, tau1..tau3 (SI).
[[nodiscard]] io::Table toTable(const ClosedLoopResult& result);

/// The short-form robot with a payload rigidly fixed on the platform at C: platform mass and inertia
/// increased by `mass` [kg] and `inertia` [kg m^2] (a model mismatch when only the plant
/// gets it).
[[nodiscard]] RobotParameters withPayload(RobotParameters robot, double mass, double inertia);

}  // namespace nocdyn::control
