// Independent MuJoCo model of a spatial parallel robot (SpatialRobotDescription: a Delta as
// 3-RUU, a 6-UPS or 6-RUS hexapod, ...), the spatial counterpart of MujocoMechanism and the
// second engine beside SimbodySpatialMechanism.
//
// MJCF generated from the description at home, every limb body's frame at the world's (so the
// description's home points and axes go in unchanged and every limb coordinate is 0 at home):
// each limb is a tree from the world through every listed joint but the last (R a hinge, P a
// slide, U two hinges a1 then a2 in one body, S a ball); the platform is a free body (its frame
// the platform frame at the home pose). The last joint closes the loop on the platform: S a
// <connect> at its centre (3 equations); U a <connect> plus the constant angle between a1 (in
// the limb's last body) and a2 (in the platform), a1 . a2 = its home value (1 equation):
// MuJoCo 2.2 has no equality leaving two rotations free (connect fixes 3 positions, weld 6,
// joint coordinates), so that row is formed from MuJoCo's body orientations (xmat) and
// rotational Jacobians (mj_jacBody). Gravity is MuJoCo's option/gravity.
//
// mj_inverse is not used: it would close the loops with MuJoCo's soft constraint solver, whose
// forces depend on solref/solimp and leave a regularisation error far above 1e-9. As the
// planar MujocoMechanism, per sample: Newton on the closure residuals (efc_pos of the connects,
// the U angles) for the passive coordinates (mj_kinematics, mj_comPos, mj_makeConstraint,
// steps by mj_integratePos so that ball and free quaternions stay unit); with K = [G; J_p], G
// the closures' Jacobian (efc_J) and J_p the platform frame's (mj_jacBody, translation and, for
// motion full, rotation), qvel = N dp from K N = [0; W] (W = I, or the Euler-rate map for
// the angles); qacc from K qacc = [-dG/dt qvel; W ddp + dW/dt dp - dJ_p/dt qvel] (the
// velocity-product terms from MuJoCo's cdof_dot, mj_objectVelocity and mj_objectAcceleration);
// h = M qacc + c - Q_gravity by mj_rne; the R and P joints' friction -(damping q' + friction
// sign q') as a generalized force Q_f; then N^T (h - Q_f) = A^T tau, A = the actuated dofs'
// rows of N, tau its minimum-norm solution: the same balance as SimbodySpatialMechanism.
// Shares only spatial_description.hpp with nocdyn; MuJoCo stays private (pimpl).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/spatial_description.hpp"

namespace nocdyn::validation {

class MujocoSpatialMechanism {
public:
    /// Builds and compiles the model. Throws nocdyn::Error for a limb whose last joint is an R
    /// or P (not modelled as a closure here), when MuJoCo rejects the model, or when the model
    /// is not assembled at home.
    explicit MujocoSpatialMechanism(const SpatialRobotDescription& robot);
    ~MujocoSpatialMechanism();
    MujocoSpatialMechanism(MujocoSpatialMechanism&&) noexcept;
    MujocoSpatialMechanism& operator=(MujocoSpatialMechanism&&) noexcept;
    MujocoSpatialMechanism(const MujocoSpatialMechanism&) = delete;
    MujocoSpatialMechanism& operator=(const MujocoSpatialMechanism&) = delete;

    /// The generated MJCF text.
    [[nodiscard]] std::string mjcf() const;

    /// The actuator forces tau (one row per sample, file order) at the poses p with rates dp and
    /// accelerations ddp (each of size 6 [x, y, z, roll, pitch, yaw] or 3 [x, y, z], Euler-angle
    /// rates), friction and damping of the R and P joints included, gravity on. The samples are
    /// a path: each is assembled from the previous one moved along the previous velocity map
    /// (subdivided when a step fails or jumps), the first from home. Throws nocdyn::Error
    /// naming the sample when a pose cannot be assembled or the closure or actuation is
    /// singular.
    Eigen::MatrixXd actuatorForces(const std::vector<Eigen::VectorXd>& p, const std::vector<Eigen::VectorXd>& dp,
                                   const std::vector<Eigen::VectorXd>& ddp);

    /// Number of actuated joints n.
    [[nodiscard]] int actuatorCount() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nocdyn::validation
