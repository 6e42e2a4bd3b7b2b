// Independent Simbody model of the 3-PRR planar parallel robot.
//
// Ground; three MobilizedBody::Slider along the base sides (line L_j through B_j along e_j);
// a Pin per link at A_j; the platform on a Planar mobilizer from Ground; each loop closed by a
// Constraint::PointOnLine (a z-line through the link tip M_j, two equations per loop).
// The model shares only io::RobotParameters and PoseTrajectory with nocdyn: it never calls
// nocdyn's kinematics or dynamics. Simbody headers stay inside the implementation (pimpl).
//
// Conventions (see shared/model-notes.md): SI units, pose = [theta, x, y], slider coordinate
// u_j = displacement of A_j along e_j from its place at the reference posture (theta = 0,
// C = O), tau_j = force that actuator j exerts on slider j along e_j.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/io/short_form.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::prr3 {

/// One inverse-dynamics sample computed by Simbody.
struct EngineSample {
    double t = 0.0;        ///< [s]
    Eigen::Vector3d pose;  ///< platform pose [theta, x, y] as assembled by Simbody [rad, m]
    Eigen::Vector3d u;     ///< slider displacements [m]
    Eigen::Vector3d du;    ///< slider velocities [m/s]
    Eigen::Vector3d ddu;   ///< slider accelerations [m/s^2]
    Eigen::Vector3d tau;   ///< actuator forces along e_j [N]
    double kinetic = 0.0;  ///< kinetic energy of the whole robot (calcKineticEnergy) [J]
};

/// The 3-PRR robot as a Simbody multibody system.
class SimbodyRobot {
public:
    /// Builds the model. Throws nocdyn::Error if the parameters are not physical
    /// (nocdyn::validate) or the robot cannot be assembled at its reference posture.
    explicit SimbodyRobot(const io::RobotParameters& robot);
    ~SimbodyRobot();
    SimbodyRobot(SimbodyRobot&&) noexcept;
    SimbodyRobot& operator=(SimbodyRobot&&) noexcept;
    SimbodyRobot(const SimbodyRobot&) = delete;
    SimbodyRobot& operator=(const SimbodyRobot&) = delete;

    /// Inverse dynamics with the platform pose prescribed from the trajectory (custom Motion
    /// on the Planar mobilizer). Pass 1: Simbody assembles the sliders and links (Newton
    /// projection from the previous sample extrapolated in time; the Assembler, then a seed
    /// on the intended branch, as fallbacks), projects the velocities and solves the
    /// constrained accelerations. Pass 2: the sliders' accelerations are prescribed instead (platform
    /// free) and the actuator forces are minus the findMotionForces entries. One sample per
    /// time. Throws nocdyn::Error if a pose is outside the workspace, assembly fails, or the
    /// assembly lands on the wrong branch.
    std::vector<EngineSample> inverseDynamics(const PoseTrajectory& trajectory, const std::vector<double>& times);

    /// Joint-space inertia at a platform pose: N^T M N with M Simbody's mass matrix and N
    /// mapping du to Simbody's mobilities (from Simbody's constraint Jacobian G) [kg].
    Eigen::Matrix3d jointSpaceInertia(const Eigen::Vector3d& pose);

    // ---- forward-dynamics plant (constraints enforced by the integrator) -------------
    /// Assembles the robot at `pose` with platform twist `pose_rate` [rad/s, m/s, m/s],
    /// time 0, zero actuator forces.
    void resetPlant(const Eigen::Vector3d& pose, const Eigen::Vector3d& pose_rate = Eigen::Vector3d::Zero());
    /// Actuator forces [N], held constant until changed (zero-order hold).
    void setActuatorForces(const Eigen::Vector3d& tau);
    /// Integrates forward dt seconds (Runge-Kutta-Merson, error-controlled).
    void advance(double dt);
    /// Integrator accuracy (default 1e-10); constraint tolerance follows it.
    void setIntegratorAccuracy(double accuracy);

    [[nodiscard]] double time() const;
    [[nodiscard]] Eigen::Vector3d u() const;
    [[nodiscard]] Eigen::Vector3d du() const;
    [[nodiscard]] Eigen::Vector3d pose() const;
    [[nodiscard]] Eigen::Vector3d poseRate() const;
    /// Kinetic energy of the plant's current state [J].
    [[nodiscard]] double kineticEnergy() const;

private:
    class Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nocdyn::prr3
