// 3-PRR forward dynamics: actuator forces -> actuator accelerations, and its time integration.
//
// From eq. 20 with two optional loads (both zero by default):
//   I(u) ddu = tau - C(u, du) du + T_7^T w_ext - diag(b) du
// where w_ext = [n; f_x; f_y] is an external wrench on the platform, moment n about C and
// force f, in the base frame (T_7 maps du to the platform twist at C, eq. 31, so T_7^T maps a
// wrench at C to actuator forces), and b_j >= 0 are viscous friction coefficients of the
// actuators (force -b_j du_j on slider j).
//
// The state is (u, du). The pose needed by I and C is recovered from u at every evaluation
// by the direct-kinematics tracker (trackPose), started from the last pose found.
//
// Simulator integrates the state with Boost.Odeint's controlled Dormand-Prince 5(4) stepper
// (runge_kutta_dopri5, adaptive step, error per component |err| <= abs + rel |x|).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "nocdyn/io/csv.hpp"

#include "nocdyn/prr3/direct_kinematics.hpp"
#include "nocdyn/prr3/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn::prr3 {

/// Loads other than the actuator forces. Both off (zero) by default.
struct ExternalLoads {
    /// Wrench [n; f_x; f_y] on the platform: moment about C [N m] and force [N], base frame.
    Wrench platform_wrench = Wrench::Zero();
    /// Viscous friction coefficient b_j of each actuator [N s/m]: force -b_j du_j.
    JointVector viscous_friction = JointVector::Zero();
};

/// Acceleration stage from forces. Needs the position and velocity stages (for example
/// trackPose, then velocityFromActuatorRates). Runs the shaping and dynamics stages, then
///   ddu = I^{-1} (tau - C du + T_7^T w_ext - b du)          (eq. 20 solved for ddu)
/// and the platform acceleration dt_M (time derivative of eq. 5). Stores tau (the actuator
/// forces as given), I, C, ddu and t_M_dot. Allocation-free. Fails with
/// singular_forward_jacobian if I is not positive definite (value: its smallest pivot).
Status forwardDynamics(const Model& model, Data& data, const JointVector& tau, const ExternalLoads& loads = {});

/// The whole path from the state: trackPose(u) starting at `pose` (updated in place), the
/// velocity stage from du, then forwardDynamics. Allocation-free.
Status forwardDynamicsFromState(const Model& model, Data& data, const JointVector& u, const JointVector& du,
                                const JointVector& tau, Pose& pose, const ExternalLoads& loads = {},
                                const TrackerOptions& tracker = {});

struct SimulatorOptions {
    double absolute_tolerance = 1e-12;  ///< per component of (u [m], du [m/s])
    double relative_tolerance = 1e-10;
    double initial_step = 1e-5;  ///< [s]
    double max_step = 1e-3;      ///< [s]
    /// Smallest step the controller may take [s]: below it advance() fails with
    /// integration_step_too_small instead of crawling forever.
    double min_step = 1e-10;
    /// Most steps (accepted and rejected) over one advance(): beyond it integration_too_many_steps.
    std::size_t max_steps = 1'000'000;
    ExternalLoads loads;
    TrackerOptions tracker;
};

/// Time integration of the forward dynamics. Not copyable across models: holds a copy of the
/// model. advance() does not allocate.
class Simulator {
public:
    explicit Simulator(const Model& model, const SimulatorOptions& options = {});
    ~Simulator();
    Simulator(Simulator&&) noexcept;
    Simulator& operator=(Simulator&&) noexcept;
    Simulator(const Simulator&) = delete;
    Simulator& operator=(const Simulator&) = delete;

    /// Starts at platform pose p with platform twist dp (inverse displacement and eq. 5 give
    /// u and du) at time t.
    Status reset(const Pose& p, const Twist& dp = Twist::Zero(), double t = 0.0);
    /// Starts from the actuator state (u, du); the pose is found by the tracker from
    /// pose_guess (the reference posture by default).
    Status resetActuators(const JointVector& u, const JointVector& du, const Pose& pose_guess = Pose::Zero(),
                          double t = 0.0);

    /// Integrates over dt [s] with the actuator forces held at tau (zero-order hold).
    Status advance(double dt, const JointVector& tau);
    /// Integrates over dt [s] with forces varying linearly from tau_begin to tau_end.
    Status advance(double dt, const JointVector& tau_begin, const JointVector& tau_end);

    [[nodiscard]] double time() const;
    [[nodiscard]] JointVector u() const;
    [[nodiscard]] JointVector du() const;
    [[nodiscard]] Pose pose() const;
    /// Platform twist dp/dt = H^{-1} D du (eq. 5) at the current state.
    [[nodiscard]] Twist poseRate() const;
    /// Kinetic energy du^T I du / 2 at the current state [J].
    [[nodiscard]] double kineticEnergy() const;
    /// Accepted and rejected integration steps since construction.
    [[nodiscard]] std::size_t acceptedSteps() const;
    [[nodiscard]] std::size_t rejectedSteps() const;
    /// Every stage (position .. acceleration) at the current state and the last forces.
    [[nodiscard]] const Data& data() const;
    [[nodiscard]] const Model& model() const;
    [[nodiscard]] const SimulatorOptions& options() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// ---- batch layer (allocates, throws nocdyn::Error) ------------------------------------

/// Actuator forces given at increasing sample times, linear in between, held constant
/// before the first and after the last sample.
struct ForceSeries {
    std::vector<double> t;         ///< [s], strictly increasing
    std::vector<JointVector> tau;  ///< [N]

    /// Forces at `time` (linear interpolation). Allocation-free.
    [[nodiscard]] JointVector at(double time) const;
};

/// A simulated run, one row per output instant.
struct SimulationSeries {
    std::vector<double> t;
    std::vector<Pose> p;
    std::vector<Twist> dp;
    std::vector<JointVector> u, du, tau;
    std::vector<double> kinetic;  ///< [J]
};

/// Runs `simulator` from its current state through every output time (increasing, not
/// before the simulator's time), with forces from `forces`; the integration restarts at every
/// force sample so that the forces are smooth within each integration segment. Throws
/// nocdyn::Error "t = ... s: reason" when the state leaves the workspace or the mode is lost.
[[nodiscard]] SimulationSeries simulateForces(Simulator& simulator, const ForceSeries& forces,
                                              const std::vector<double>& output_times);

/// Forces from a CSV table with columns t,tau1,tau2,tau3 (extra columns ignored). Throws
/// nocdyn::Error naming the missing column or the row whose time does not increase.
[[nodiscard]] ForceSeries forcesFromTable(const io::Table& table, const std::string& source);

/// CSV table: t,x,y,theta,u1..u3,du1..du3,tau1..tau3,kinetic (SI).
[[nodiscard]] io::Table toTable(const SimulationSeries& series);

}  // namespace nocdyn::prr3
