// Independent MuJoCo model of the 3-PRR robot: the same robot built from
// the same io::RobotParameters as MJCF, its loops closed with <equality><connect>, and its inverse
// dynamics computed by MuJoCo's rigid multibody building blocks (the position stage
// mj_kinematics/mj_comPos/mj_makeConstraint, mj_comVel, mj_rne, the constraint Jacobian efc_J)
// plus small Eigen solves for the loop closure and the slider forces (see the .cpp).
//
// Nothing here calls nocdyn's kinematics or dynamics: only io::RobotParameters and PoseTrajectory
// are shared with the NOC model. MuJoCo's headers stay in the implementation (pimpl).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/io/short_form.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::prr3 {

/// One inverse-dynamics sample computed by MuJoCo (SI units).
struct MujocoSample {
    double t = 0.0;                 ///< [s]
    Eigen::Vector3d pose;           ///< prescribed platform pose [theta, x, y] [rad, m, m]
    Eigen::Vector3d u;              ///< slider displacements from the reference posture [m]
    Eigen::Vector3d du;             ///< [m/s]
    Eigen::Vector3d ddu;            ///< [m/s^2]
    Eigen::Vector3d tau;            ///< force actuator j exerts on slider j along e_j [N]
    double kinetic = 0.0;           ///< kinetic energy 0.5 qvel^T M qvel from MuJoCo [J]
    double closure_residual = 0.0;  ///< largest loop-closure position error after the solve [m]
};

/// The 3-PRR robot as a MuJoCo model.
///
/// Tree: three sliders (slide joints along the base sides, qpos = u_j exactly: the slider
/// body sits at A_j's reference position), a hinge per limb link at A_j, and the platform
/// on slide x, slide y, hinge z (qpos = [x, y, theta]). The model is drawn at the reference
/// posture, where qpos0 = 0 is assembled; each loop is closed at M_j by a connect constraint.
class MujocoRobot {
public:
    /// Builds and compiles the model. Throws nocdyn::Error with a clear message when the
    /// parameters are not physical or MuJoCo rejects the model.
    explicit MujocoRobot(const io::RobotParameters& robot);
    ~MujocoRobot();
    MujocoRobot(MujocoRobot&&) noexcept;
    MujocoRobot& operator=(MujocoRobot&&) noexcept;
    MujocoRobot(const MujocoRobot&) = delete;
    MujocoRobot& operator=(const MujocoRobot&) = delete;

    /// The generated MJCF text.
    [[nodiscard]] std::string mjcf() const;

    /// One sample per time, the platform pose prescribed from the trajectory. The first
    /// sample's joint solve starts from the reference posture, each later one from the
    /// previous sample. Throws nocdyn::Error (naming the time) when a pose cannot be
    /// assembled on the robot's working branch.
    std::vector<MujocoSample> inverseDynamics(const PoseTrajectory& trajectory, const std::vector<double>& times);

    /// Single sample: pose p = [theta, x, y], its rate and acceleration -> u, du, ddu, tau.
    /// The Newton solve for the joint positions starts from the previous call's solution.
    /// Allocation-free (fixed-size Eigen, MuJoCo's preallocated mjData). Throws nocdyn::Error
    /// when the closure cannot be solved on the working branch.
    void inverseDynamicsSample(const Eigen::Vector3d& p, const Eigen::Vector3d& dp, const Eigen::Vector3d& ddp,
                               Eigen::Vector3d& u, Eigen::Vector3d& du, Eigen::Vector3d& ddu, Eigen::Vector3d& tau);

    /// Kinetic energy 0.5 qvel^T M qvel of the last sample (MuJoCo's mj_energyVel) [J].
    [[nodiscard]] double lastKineticEnergy() const;
    /// Largest loop-closure position error of the last sample's solve [m].
    [[nodiscard]] double lastClosureResidual() const;
    /// Restart the next Newton solve from the reference posture.
    void resetSeed();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nocdyn::prr3
