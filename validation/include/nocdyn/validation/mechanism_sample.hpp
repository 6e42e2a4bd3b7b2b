// One inverse-dynamics sample of a general planar parallel robot (RobotDescription) computed
// by an independent multibody engine (SimbodyMechanism, MujocoMechanism).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace nocdyn::validation {

/// Inverse dynamics at one time, SI units. n = number of actuated joints, in file order
/// (limbs in order, joints in chain order).
struct MechanismSample {
    double t = 0.0;                                  ///< [s]
    Eigen::Vector3d pose = Eigen::Vector3d::Zero();  ///< platform pose [theta, x, y] as assembled [rad, m]
    Eigen::VectorXd u;                               ///< actuated joint variables q (0 at home) [m or rad], size n
    Eigen::VectorXd du;                              ///< their rates [m/s or rad/s], size n
    Eigen::VectorXd ddu;                             ///< their accelerations [m/s^2 or rad/s^2], size n
    /// Actuator forces (torques) along the joint variables on the outboard bodies, including
    /// gravity and joint friction; with n > 3 the minimum-norm solution [N or N m], size n.
    Eigen::VectorXd tau;
    double kinetic = 0.0;      ///< kinetic energy of all moving bodies [J]
    double potential = 0.0;    ///< gravity potential energy relative to the home posture [J]
    double dissipation = 0.0;  ///< power lost in joint friction, sum (damping q'^2 + friction |q'|) [W]
    /// Largest condition number (2-norm) of the loop-closure Jacobian of the passive tree
    /// coordinates and of the map from the platform twist to the actuator rates.
    double condition = 0.0;
    /// Every joint's reaction with the actuator forces tau applied, limb by limb, joint by joint
    /// (3 per limb): [fx, fy, m] in the base frame, the wrench of the joint's inboard body on its
    /// outboard body without the joint's own effort and friction (R: the force at the axis, m = 0;
    /// P: the force normal to the joint and the couple about the outboard body's c.o.m.), as
    /// nocdyn's reactions.hpp. Empty when the engine does not give them.
    std::vector<Eigen::Vector3d> reactions;
};

}  // namespace nocdyn::validation
