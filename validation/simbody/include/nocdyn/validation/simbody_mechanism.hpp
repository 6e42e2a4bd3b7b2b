// Independent Simbody model of any planar parallel robot of the general form
// (RobotDescription: limbs of three R/P joints, any actuated joints, gravity, joint friction).
//
// Each limb is a tree plus one loop-closure constraint at one of its revolute joints (the last
// unactuated R joint, else the last R joint): the joints before it are Pin/Slider mobilizers
// from Ground, the joints after it Pin/Slider mobilizers hanging from the platform (reversed),
// and the closure is a Constraint::PointOnLine (a z-line through the joint axis on one link,
// followed by the axis point on the other: two equations). The platform is on a Planar
// mobilizer from Ground whose motion is prescribed. Gravity is a Force::UniformGravity; joint
// friction a Force::Custom (mobility forces on tree joints, opposite body torques across a
// closure joint), so that Simbody's applied forces hold both.
// See nocdyn/validation/detail/mechanism_common.hpp for how the actuator forces follow.
// The same model is also a forward-dynamics plant (resetPlant, setActuatorForces, advance): a
// second State in which the platform's Motion is disabled, the actuator forces held in a
// Force::DiscreteForces (mobility forces on tree joints, opposite body torques across a closure
// joint, as for friction), integrated by Simbody's Runge-Kutta-Merson integrator.
// Shares only description.hpp and trajectory.hpp with nocdyn; Simbody stays private (pimpl).
#pragma once

#include <memory>
#include <vector>

#include "nocdyn/description.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/validation/mechanism_sample.hpp"

namespace nocdyn::validation {

class SimbodyMechanism {
public:
    /// Builds the model from a description (validated by nocdyn::validate on a copy). Throws
    /// nocdyn::Error if a limb has no revolute joint or the model does not assemble at home.
    explicit SimbodyMechanism(const RobotDescription& robot);
    ~SimbodyMechanism();
    SimbodyMechanism(SimbodyMechanism&&) noexcept;
    SimbodyMechanism& operator=(SimbodyMechanism&&) noexcept;
    SimbodyMechanism(const SimbodyMechanism&) = delete;
    SimbodyMechanism& operator=(const SimbodyMechanism&) = delete;

    /// Inverse dynamics with the platform pose prescribed from the trajectory, one sample per
    /// time. Positions by Simbody's Newton projection (projectQ), continued from home along
    /// the samples (the previous solution extrapolated; subdivided in pose space when a step
    /// fails or jumps), so every limb stays on its home branch; velocities by projectU,
    /// accelerations by realize(Acceleration) with the platform's Motion; then
    /// h = M u' + c - Q_applied (calcResidualForceIgnoringConstraints) and the constraint
    /// Jacobian calcG give the actuator forces (minimum norm when redundant). Throws
    /// nocdyn::Error naming the time when a pose cannot be assembled or is singular.
    std::vector<MechanismSample> inverseDynamics(const PoseTrajectory& trajectory, const std::vector<double>& times);

    /// Number of actuated joints n.
    [[nodiscard]] int actuatorCount() const;

    // ---- forward-dynamics plant (the platform free, the loops closed by the constraints,
    // enforced by Simbody's integrator with projection). Independent of inverseDynamics. ----

    /// Assembles the robot at `pose` with platform twist `pose_rate` = dp/dt [rad/s, m/s, m/s]
    /// (the passive coordinates continued from home, as inverseDynamics does), at time t, with
    /// zero actuator forces. Throws nocdyn::Error when the pose cannot be assembled, and for a
    /// two-DOF robot (motion: translation: its point tool's angle, free in the plant, has no
    /// inertia).
    void resetPlant(const Eigen::Vector3d& pose, const Eigen::Vector3d& pose_rate = Eigen::Vector3d::Zero(),
                    double t = 0.0);
    /// Actuator forces (torques) along the actuated joint variables, on their outboard bodies,
    /// file order, size n; held until changed (zero-order hold). Throws for a wrong size.
    void setActuatorForces(const Eigen::VectorXd& tau);
    /// Integrates forward dt >= 0 seconds (Runge-Kutta-Merson, error-controlled, constraints
    /// projected). Throws nocdyn::Error naming the time when Simbody's integration fails.
    void advance(double dt);
    /// Integrator accuracy in (0, 1) (default 1e-10); the constraint tolerance is 1 % of it.
    void setIntegratorAccuracy(double accuracy);

    [[nodiscard]] double time() const;
    [[nodiscard]] Eigen::VectorXd u() const;         ///< actuated joint variables, 0 at home [m or rad]
    [[nodiscard]] Eigen::VectorXd du() const;        ///< their rates
    [[nodiscard]] Eigen::Vector3d pose() const;      ///< [theta, x, y]
    [[nodiscard]] Eigen::Vector3d poseRate() const;  ///< dp/dt
    [[nodiscard]] double kineticEnergy() const;      ///< [J]
    /// Gravity potential energy relative to the home posture [J].
    [[nodiscard]] double potentialEnergy() const;
    /// Integration steps Simbody took since the last resetPlant.
    [[nodiscard]] long plantSteps() const;

private:
    class Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nocdyn::validation
