// `pose`: everything the model knows at one platform pose of any robot.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/pose_order.hpp"

namespace nocdyn::app {

struct PoseOptions {
    double x = 0.0;  ///< x of the platform's operation point C [m] (kLengthRange)
    double y = 0.0;  ///< y of C [m] (kLengthRange)
    /// Platform rotation [rad] (kAngleRange). NaN: not given, which a two-DOF robot (motion:
    /// translation, no theta) needs and a turning platform refuses; a two-DOF robot takes 0 too.
    double theta = 0.0;
    RobotSource robot;
};

/// One limb at the pose.
struct PoseLimb {
    int limb = 0;  ///< 1-based, file order
    std::string name, type;
    Vector3 q = Vector3::Zero();  ///< joint variables [rad or m], joints 1..3
    std::array<bool, 3> revolute{};
    double cond_J = 0.0;  ///< condition number of the limb Jacobian
};

/// One actuator at the pose.
struct PoseActuator {
    int actuator = 0, limb = 0, joint = 0;  ///< 1-based
    bool revolute = false;
    double u = 0.0;           ///< [rad or m]
    double range_used = 0.0;  ///< fraction of the range on the side u is on (0: unlimited)
};

/// One joint's reaction at rest under gravity (base frame, inboard body on outboard body,
/// the joint's effort and friction taken out).
struct PoseReaction {
    int limb = 0, joint = 0;  ///< 1-based
    bool revolute = false;
    Vector3 f = Vector3::Zero();  ///< [fx, fy, m] [N, N, N m]
};

/// Stiffness and natural frequencies at the pose (robots whose file declares compliance). Every
/// vector and matrix over pose coordinates is in the order x, y, theta; a two-DOF robot's over
/// x, y (n_t = 2: K_t = E^T K E, M_t = E^T M E, TaskModes).
struct PoseCompliance {
    Eigen::MatrixXd K = Matrix3::Zero();  ///< n_t x n_t: dQ = K dp (virtual joint method, gravity preload ignored)
    std::vector<Eigen::VectorXd> free_directions;  ///< n_t each
    std::vector<std::string> free_descriptions;
    Eigen::VectorXd frequencies = Vector3::Zero();             ///< n_t: lumped model K v = w^2 M v [Hz], ascending
    Eigen::MatrixXd mode_shapes = Matrix3::Zero();             ///< n_t x n_t: columns, mass-normalised
    std::optional<Eigen::VectorXd> elastodynamic_frequencies;  ///< [Hz], elastic links only
    int elastodynamic_dofs = 0;
    /// The first natural frequency to use [Hz]: the lumped one where it holds, else (elastic
    /// links, the two more than 5 % apart: firstFrequency) the elastodynamic one.
    double first_frequency = 0.0;
    FrequencyModel first_frequency_model = FrequencyModel::lumped;
};

struct PoseResult {
    std::string robot;
    /// 3: pose [x, y, theta]; 2: a two-DOF robot (motion: translation), pose [x, y] (theta 0, no
    /// coordinate), and A, I over x, y only.
    int task_dimension = 3;
    Vector3 pose = Vector3::Zero();  ///< [x, y, theta]
    std::vector<PoseLimb> limbs;
    std::vector<PoseActuator> actuators;
    Eigen::MatrixXd A;  ///< du = A dp/dt, columns x, y, theta
    double cond_A = 0.0, max_condition = 0.0;
    /// "actuators": I in the actuator variables; "platform": in the pose (columns x, y, theta).
    std::string coordinates;
    Eigen::MatrixXd I;    ///< inertia (eq. 23)
    Eigen::VectorXd tau;  ///< actuator forces at rest under gravity
    std::vector<PoseReaction> reactions;
    bool within_limits = true;
    std::string limits;  ///< the first limit passed, when not within limits
    std::optional<PoseCompliance> compliance;
};

/// Throws OptionError for a pose outside its ranges (theta when given).
void validate(const PoseOptions& options);

/// The pose's report. A pose out of reach or singular is an Error; one outside a joint's range
/// is reported (within_limits, limits) and warned of through the observer.
[[nodiscard]] PoseResult runPose(const PoseOptions& options, Observer& observer);

}  // namespace nocdyn::app
