// Independent MuJoCo model of any planar parallel robot of the general form
// (RobotDescription: limbs of three R/P joints, any actuated joints, gravity, joint friction).
//
// MJCF generated from the description at home (every body frame at the world origin, joints
// at their home points and directions): each limb is a tree plus one <connect> equality at one
// of its revolute joints (the first unactuated R joint, else the first R joint): the joints
// before it hang from the world, the joints after it from the platform (reversed); the platform
// is on slide x, slide y and a hinge at C. Gravity is MuJoCo's option/gravity. A joint's
// stiffness (a drive or flexure spring) is MuJoCo's joint stiffness, at rest at home.
//
// mj_inverse is not used (its soft constraints are wrong for prescribed closed loops): per
// sample, Newton on the connect residuals efc_pos with efc_J for the passive joints
// (mj_kinematics, mj_comPos, mj_makeConstraint), velocities from efc_J qvel = 0,
// accelerations from efc_J qacc = -dJ/dt qvel (the anchors' relative acceleration at
// qacc = 0 from MuJoCo's cdof_dot and mj_objectAcceleration), h = M qacc + c - Q_gravity by
// mj_rne; the actuator forces then follow from the platform-force balance of
// nocdyn/validation/detail/mechanism_common.hpp (minimum norm when redundant).
// Shares only description.hpp and trajectory.hpp with nocdyn; MuJoCo stays private (pimpl).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/description.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/validation/mechanism_sample.hpp"

namespace nocdyn::validation {

class MujocoMechanism {
public:
    /// Builds and compiles the model (the description validated by nocdyn::validate on a
    /// copy). Throws nocdyn::Error if a limb has no revolute joint, MuJoCo rejects the model,
    /// or the home posture is not assembled.
    explicit MujocoMechanism(const RobotDescription& robot);
    ~MujocoMechanism();
    MujocoMechanism(MujocoMechanism&&) noexcept;
    MujocoMechanism& operator=(MujocoMechanism&&) noexcept;
    MujocoMechanism(const MujocoMechanism&) = delete;
    MujocoMechanism& operator=(const MujocoMechanism&) = delete;

    /// The generated MJCF text.
    [[nodiscard]] std::string mjcf() const;

    /// Inverse dynamics with the platform pose prescribed from the trajectory, one sample per
    /// time, the joints continued from home along the samples (the previous solution moved
    /// along the previous velocity map; subdivided in pose space when a step fails or jumps),
    /// so every limb stays on its home branch. Throws nocdyn::Error naming the time when a
    /// pose cannot be assembled or is singular.
    std::vector<MechanismSample> inverseDynamics(const PoseTrajectory& trajectory, const std::vector<double>& times);

    /// Number of actuated joints n.
    [[nodiscard]] int actuatorCount() const;

    // ---- forward-dynamics plant: mj_step (semi-implicit Euler at the model's 0.1 ms step),
    // the loops closed by MuJoCo's soft connect constraints with time constant 2 steps (solref
    // [2 dt, 1], the smallest MuJoCo recommends). Independent of inverseDynamics. ----

    /// Assembles the robot at `pose` with platform twist `pose_rate` (the passive joints
    /// continued from home, as inverseDynamics does) at time t, with zero actuator forces.
    /// Throws nocdyn::Error when the pose cannot be assembled, a joint has friction (the
    /// plant does not model it) or the robot is a two-DOF one (motion: translation: its point
    /// tool's angle, free in the plant, has no inertia).
    void resetPlant(const Eigen::Vector3d& pose, const Eigen::Vector3d& pose_rate = Eigen::Vector3d::Zero(),
                    double t = 0.0);
    /// Actuator forces along the actuated joint variables, file order, size n; held until changed.
    void setActuatorForces(const Eigen::VectorXd& tau);
    /// Advances by the whole number of model steps nearest to dt >= 0. Throws nocdyn::Error
    /// naming the time when MuJoCo reports an unstable acceleration.
    void advance(double dt);
    [[nodiscard]] double time() const;
    [[nodiscard]] Eigen::Vector3d pose() const;  ///< [theta, x, y]
    /// Largest loop-closure error of the soft constraints now [m].
    [[nodiscard]] double loopError() const;
    /// mj_step calls since the last resetPlant.
    [[nodiscard]] long plantSteps() const;

    /// One mode of small free vibration: natural frequency |lambda| / 2 pi [Hz], damping ratio.
    struct LinearMode {
        double frequency;
        double damping_ratio;
    };
    /// The plant linearised at rest at `pose` by mjd_transitionFD (centred differences), with
    /// the joints' springs (MJCF joint stiffness) at rest at the pose (qpos_spring = the pose's
    /// qpos, as springref), gravity off, at time step `timestep` (the loops' soft constraints
    /// then have the time constant 2 timestep): the oscillatory eigenvalues lambda of the
    /// continuous-time state matrix, ascending. Leaves the plant reset at the pose, with its own
    /// time step. Throws nocdyn::Error when a spring is at a loop closure (a connect).
    [[nodiscard]] std::vector<LinearMode> linearModes(const Eigen::Vector3d& pose, double timestep);

    /// MuJoCo's linearisation of the plant at its present state (resetPlant) and forces
    /// (setActuatorForces), mapped to the platform pose [theta, x, y]: mjd_transitionFD (centred
    /// differences of one mj_step, step `eps` in every joint coordinate and rate) gives
    /// d qacc/d(qpos, qvel) = (A_v - [0 I]) / dt; along the loop-consistent state of a pose
    /// direction e_i, dq = V e_i and dqvel = d(V dp)/dp e_i (V: qvel of a unit platform rate,
    /// from G qvel = 0; its derivative by centred differences of the assembly, step `h`),
    /// and of a rate direction dqvel = V e_i. d_tau: mjd_transitionFD perturbs only MuJoCo
    /// controls and the forces here are qfrc_applied, so centred differences of mj_forward in
    /// tau (exact: qacc is linear in the applied force). `impedance`: the loops' solimp d
    /// (MuJoCo's default 0.9 leaves a soft loop compliant by (1 - d) / d). The state and model
    /// are restored.
    struct PlatformDerivatives {
        Eigen::Vector3d ddp;    ///< the platform's qacc [theta, x, y]
        Eigen::Matrix3d d_p;    ///< d ddp / d p
        Eigen::Matrix3d d_dp;   ///< d ddp / d(dp/dt)
        Eigen::MatrixXd d_tau;  ///< d ddp / d tau, 3 x n
    };
    [[nodiscard]] PlatformDerivatives platformDerivatives(double eps = 1e-6, double h = 1e-6, double impedance = 0.9);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nocdyn::validation
