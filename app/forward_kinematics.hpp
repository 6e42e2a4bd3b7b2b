// `forward-kinematics`: every platform pose that closes the loops of any robot with given
// actuator values (the general direct-kinematics solver, nocdyn/direct_kinematics.hpp).
#pragma once

#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/pose_order.hpp"

namespace nocdyn::app {

struct ForwardKinematicsOptions {
    /// u_1 .. u_n, one per actuated joint in file order [m or rad] (each in kLengthRange).
    std::vector<double> u;
    RobotSource robot;
    /// Every assembly mode, not only the working ones (every limb on its home branch).
    bool all_branches = false;
};

/// One assembly mode.
struct ForwardKinematicsSolution {
    Vector3 pose = Vector3::Zero();  ///< [x, y, theta] [m, m, rad], theta in (-pi, pi]
    bool working = false;            ///< every limb on its home branch
    std::vector<int> branch;         ///< per limb: +1 / -1, 0 for a limb with one solution
    double u_error = 0.0;            ///< max |u(p) - u| over the actuators [m or rad]
    double condition = 0.0;          ///< largest scaled condition number at the pose
};

struct ForwardKinematicsResult {
    std::string robot;
    /// 3: poses [x, y, theta]; 2: a two-DOF robot (motion: translation), poses [x, y] (theta
    /// stays at home, 0).
    int task_dimension = 3;
    std::vector<double> u;
    std::vector<bool> revolute;  ///< per actuator: an R joint (rad), else P (m)
    /// 1-based number of the first actuator whose value is beyond its joint's range; 0: none.
    int outside = 0;
    int solutions_all_branches = 0, solutions_working_branches = 0;
    /// The closures do not isolate the pose for every choice of equations: the list may be
    /// incomplete (an architecture singularity).
    bool degenerate = false;
    /// The modes listed (working ones, or all with all_branches), sorted by theta.
    std::vector<ForwardKinematicsSolution> solutions;
};

/// Throws OptionError("u") for a value outside kLengthRange.
void validate(const ForwardKinematicsOptions& options);

/// The assembly modes of options.u (two-DOF robots included). Throws OptionError("u") unless there is one value per
/// actuator; a value beyond its joint's range is reported (outside) and warned of. No pose
/// closing the loops is not an error (no solutions).
[[nodiscard]] ForwardKinematicsResult runForwardKinematics(const ForwardKinematicsOptions& options, Observer& observer);

}  // namespace nocdyn::app
