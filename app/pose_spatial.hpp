// `pose` of a spatial robot (space: spatial): the joint variables of every limb, the actuator
// values, the actuation map and, at rest under gravity, the actuator forces (nocdyn/spatial.hpp).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/spatial_description.hpp"

namespace nocdyn::app {

struct SpatialPoseLimb {
    int limb = 0;  ///< 1-based, file order
    std::string name, type;
    std::vector<double> q;        ///< every freedom's variable [rad or m], base to platform
    std::vector<char> kinds;      ///< 'R' or 'P' per freedom
    std::vector<std::string> of;  ///< the listed joint each freedom belongs to ("U1", ...)
    double cond_J = 0.0;          ///< largest over smallest singular value of J_j
};

struct SpatialPoseActuator {
    int actuator = 0, limb = 0, joint = 0;  ///< 1-based (joint: the listed joint)
    bool revolute = false;
    double u = 0.0;           ///< [rad or m]
    double range_used = 0.0;  ///< fraction of the range on the side u is on (0: unlimited)
};

/// One listed joint's reaction at rest under gravity (spatial::jointReactions): the inboard body
/// on the outboard body, base frame, its efforts taken out (an S carries no moment, a U none
/// about its two axes, an R none about its axis, a P no force along its direction).
struct SpatialPoseReaction {
    int limb = 0, joint = 0;                           ///< 1-based, file order
    char type = 'R';                                   ///< R, P, U or S
    Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< where the moment is taken [m]
    Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< [N]
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();  ///< about point [N m]
};

struct SpatialPoseResult {
    std::string robot;
    std::vector<std::string> coordinates;  ///< x, y, z (and roll, pitch, yaw)
    std::vector<double> pose;
    std::vector<SpatialPoseLimb> limbs;
    std::vector<SpatialPoseActuator> actuators;
    Eigen::MatrixXd A;  ///< n x d: du = A [v; w], v the platform point's velocity, w the angular velocity
    double cond_A = 0.0, max_condition = 0.0;
    Eigen::VectorXd tau;                         ///< actuator forces at rest under gravity
    std::vector<SpatialPoseReaction> reactions;  ///< every listed joint's, limb by limb
    double balance_residual = 0.0;               ///< |sum_j F_j - w_P| of the platform [N, N m]
    bool within_limits = true;
    std::string limits;  ///< the first range passed, when not within limits
};

/// Whether the source names a spatial robot file (space: spatial).
[[nodiscard]] bool isSpatialRobot(const RobotSource& source);

/// The report at `pose` ([x, y, z, roll, pitch, yaw], or [x, y, z] for motion translation).
/// Throws nocdyn::Error for a pose of the wrong length, out of reach or
/// singular; a joint beyond its range is reported (within_limits, limits) and warned of.
[[nodiscard]] SpatialPoseResult runSpatialPose(const RobotSource& source, const std::vector<double>& pose,
                                               Observer& observer);
/// The same for a description already read; `source` names it in errors.
[[nodiscard]] SpatialPoseResult runSpatialPose(const SpatialRobotDescription& description, const std::string& source,
                                               const std::vector<double>& pose, Observer& observer);

}  // namespace nocdyn::app
