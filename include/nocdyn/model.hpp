// The general planar parallel robot: constant Model and per-sample Data.
//
// Every limb j is a serial chain of three joints (R or P) from the base to the platform
// with two moving bodies (the paper's slider and link are the bodies of a PRR limb). Twists
// are planar screws referred to the base origin O unless a name says otherwise:
//   xi = [omega; v_O],  v_O the velocity of the body point passing through O,
// so that a joint's screw is constant in the base frame while the joint does not move:
//   R at point r: s = [1; r_y; -r_x],   P along unit d: s = [0; d].
// The platform twist of the paper, t_M = dp/dt = [omega; dc/dt] (eq. 2), is referred to the
// moving point C; the two are related by xi_P = S(c) t_M (see kinematics.hpp).
// A body's twist at its own c.o.m., t_i = [omega; dx_i/dt] (eq. 10), is Ad(x_i) xi.
//
// Model: everything constant (home geometry, inertia dyads, limits), validated once.
// Data: every per-sample quantity, fixed capacity (kMaxLimbs limbs), filled by the stages of
// kinematics.hpp and dynamics.hpp in order:
//   position  (inverseDisplacement)          q, joint screws s_jk, body c.o.m. x_i, u
//   velocity  (velocityFromPlatformTwist /
//              velocityFromActuatorRates)    J_j, J_j^-1, A, xi_P, gamma_dot_j, body twists, du
//   shaping   (twistShaping)                 T_i, dT_i                       (eqs. 22-31)
//   accel.    (accelerationFromPlatform /
//              accelerationFromActuators)    xi_P_dot, gamma_ddot_j, ddu
//   dynamics  (jointSpaceDynamics)           I, C, Q_gf                      (eq. 23)
//   forces    (actuatorForces)               tau                             (eq. 20)
//
// Independent coordinates: with exactly three actuators they are the actuator variables u
// (the paper's choice, eq. 16); with more (redundant actuation) they are the platform pose p,
// and the actuator forces are the minimum-norm solution of A_p^T tau = Q.
//
// Body numbering follows the paper: body b (0 = first, 1 = second) of limb j is
// i = b * limbs + j, the platform is i = 2 * limbs (for the 3-PRR: sliders 0..2, links 3..5,
// platform 6).
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "nocdyn/description.hpp"
#include "nocdyn/noc.hpp"
#include "nocdyn/planar.hpp"

namespace nocdyn {

inline constexpr int kMaxBodies = 2 * kMaxLimbs + 1;

/// What the dynamics are written in (see above).
enum class Coordinates { actuators, platform };

/// Joint-space (independent-coordinate) quantities: always 3 of them in the plane.
using ShapingMatrix3 = noc::ShapingMatrix<3>;
/// A vector over the actuators (n <= kMaxActuators): u, du, ddu, tau. Never allocates.
using ActuatorVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxActuators, 1>;
/// n x 3 map from the platform twist to the actuator rates.
using ActuationMatrix = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxActuators, 3>;

/// The joint types of a limb, base to platform (the closed form of its inverse displacement).
enum class LimbKind { RRR, PRR, RPR, RRP, PRP, RPP, PPR, PPP };

/// Constant description of one limb, prepared for the per-sample algorithms.
struct LimbModel {
    std::array<JointType, 3> type{};  ///< base to platform
    LimbKind kind = LimbKind::RRR;    ///< the same as one value
    /// R joints: axis at home relative to the home position of C, base axes [m].
    std::array<Vector2, 3> point{};
    /// R joints: axis at home in the base frame [m].
    std::array<Vector2, 3> point_home{};
    /// P joints: unit direction at home, base frame.
    std::array<Vector2, 3> direction{};
    /// Home screws s_k(0) = [1; r_y; -r_x] or [0; d], referred to O.
    std::array<Twist, 3> screw_home{};
    std::array<InertiaDyad, 2> M{};           ///< bodies 1 and 2 (eq. 9)
    std::array<Vector2, 2> com_home{};        ///< c.o.m. at home, base frame [m]
    std::array<int, 3> actuator{-1, -1, -1};  ///< actuator index of each joint, or -1
    std::array<JointLimits, 3> limits{};
    std::array<double, 3> damping{};
    std::array<double, 3> friction{};
    /// Inverse-kinematics branch kept from home: +1 or -1 for limbs with two solutions
    /// (a circle meeting a circle or a line), 0 for limbs with one.
    int branch = 0;
    /// Lengths used by the closed forms (|r2 - r1|, |r3 - r2|, ...) [m].
    double length1 = 0.0, length2 = 0.0;
    double inv_length1_sq = 0.0, inv_length2_sq = 0.0;  ///< 1 / length^2 (0 when the length is 0)
    /// Scale of each joint variable in the condition numbers: 1 for R (rad), the model's
    /// length_scale for P (m); and its inverse.
    std::array<double, 3> joint_scale{1.0, 1.0, 1.0};
    std::array<double, 3> inv_joint_scale{1.0, 1.0, 1.0};
    /// No damping and no Coulomb friction at any joint of the limb.
    bool frictionless = true;
};

namespace detail {
struct ModelKernel;  // the per-sample kernel's view of a Model (src/core, not installed)
}  // namespace detail

/// Constant parameters of a planar parallel robot. Immutable after construction.
class Model {
public:
    /// Validates the description (throws nocdyn::Error naming file, line, limb and field),
    /// prepares the limbs, and checks that every limb closes on its home branch and is
    /// regular at home (so that the home branch is well defined), as is the actuation.
    explicit Model(RobotDescription description);

    RobotDescription description;  ///< as validated (P directions unit)
    /// What the platform does: PlatformMotion::full (task coordinates [theta, x, y]) or
    /// PlatformMotion::translation (task coordinates [x, y] of the tool point, a point mass where every
    /// limb's last R joint meets). The core runs every robot in the pose p = [theta, x, y]: for
    /// translation theta stays at home(0) = 0 and the rates are t_M = E dp_task with the task map
    /// E = [0 0; 1 0; 0 1] (taskMap below), so that I_task = E^T I E, Q_task = E^T Q and the
    /// actuation map is A S(c) E (the last R joints take up the fictitious rotation: no body
    /// moves with it, and the point mass has no rotational inertia).
    PlatformMotion motion = PlatformMotion::full;
    int task_dimension = 3;  ///< n_t: 3 (full) or 2 (translation)
    int limbs = 0;           ///< number of limbs
    int actuators = 0;       ///< n, number of actuated joints
    int bodies = 0;          ///< 2 * limbs + 1
    Coordinates coordinates = Coordinates::actuators;
    std::array<LimbModel, kMaxLimbs> limb{};
    std::array<int, kMaxActuators> actuator_limb{};   ///< limb of actuator a
    std::array<int, kMaxActuators> actuator_joint{};  ///< joint (0..2) of actuator a
    InertiaDyad platform_M{};                         ///< platform inertia dyad (eq. 9)
    Vector2 platform_com = Vector2::Zero();           ///< c.o.m. in the platform frame (origin C) [m]
    /// The same at home in base axes, Rot(home(0)) platform_com: x_P = C + Rot(dtheta) of it.
    Vector2 platform_com_home = Vector2::Zero();
    Vector2 gravity = Vector2::Zero();      ///< [m/s^2]
    Pose home = Pose::Zero();               ///< platform pose at home
    double cos_home = 1.0, sin_home = 0.0;  ///< of home(0)
    /// Length scale of the condition numbers: the largest distance of a revolute axis from
    /// C at home [m] (1 m when there is none).
    double length_scale = 1.0;
    double max_condition = 1.0e4;
    /// When every limb has the same kind and exactly one actuated joint, at the same place
    /// in the chain: kind * 3 + that joint (the lean kernel is then compiled for it); else -1.
    int uniform_limbs = -1;
    /// Whether the per-sample path runs every limb at once, limb l in lane l of one vector:
    /// when uniform_limbs >= 0 and there are at most four limbs, all frictionless or none.
    [[nodiscard]] bool limbsInLanes() const { return limbs_in_lanes_; }

    /// Body index of body b (0, 1) of limb j, and of the platform.
    [[nodiscard]] int body(int j, int b) const { return b * limbs + j; }
    [[nodiscard]] int platformBody() const { return 2 * limbs; }
    /// Inertia dyad of body i.
    [[nodiscard]] const InertiaDyad& inertia(int i) const {
        return i == platformBody() ? platform_M
                                   : limb[static_cast<std::size_t>(i % limbs)].M[static_cast<std::size_t>(i / limbs)];
    }
    /// "limb 2 (left)" style name for messages (1-based).
    [[nodiscard]] std::string limbName(int j) const;

private:
    friend struct detail::ModelKernel;
    /// The limbs' constants lane by lane, as the per-sample kernel reads them (its layout is
    /// the kernel's own, src/core/limb_lanes.hpp): storage of that size, filled at construction.
    alignas(double) std::array<std::byte, 156 * sizeof(double)> lanes_{};
    bool limbs_in_lanes_ = false;
};

/// A vector over the task coordinates (n_t <= 3): [theta, x, y] or [x, y]. Never allocates.
using TaskVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
/// The task map E (3 x n_t): dp/dt = E dp_task/dt. Identity for PlatformMotion::full; for
/// PlatformMotion::translation E = [0 0; 1 0; 0 1] (the pose's theta is no task coordinate).
using TaskMap = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3>;
[[nodiscard]] TaskMap taskMap(const Model& model);
/// The core's pose of task coordinates p_task (size model.task_dimension): p_task itself for
/// PlatformMotion::full, [home(0), x, y] for PlatformMotion::translation.
[[nodiscard]] inline Pose poseOfTask(const Model& model, const TaskVector& p_task) {
    return model.task_dimension == 3 ? Pose(p_task) : Pose(model.home(0), p_task(0), p_task(1));
}
/// The core's pose rates E dp_task (and accelerations E ddp_task: E is constant).
[[nodiscard]] inline Twist rateOfTask(const Model& model, const TaskVector& dp_task) {
    return model.task_dimension == 3 ? Twist(dp_task) : Twist(0.0, dp_task(0), dp_task(1));
}

/// Per-limb workspace.
struct LimbData {
    Vector3 q = Vector3::Zero();           ///< joint variables [rad or m]
    Vector3 cos_q = Vector3::Ones();       ///< cos q for R joints (1 for P)
    Vector3 sin_q = Vector3::Zero();       ///< sin q for R joints (0 for P)
    std::array<Twist, 3> s{};              ///< current joint screws, referred to O (columns of J_j)
    std::array<Vector2, 2> x{};            ///< body c.o.m. positions [m]
    Matrix3 J = Matrix3::Zero();           ///< J_j = [s_1 s_2 s_3]: xi_P = J_j gamma_dot_j (eq. 3)
    Matrix3 J_inv = Matrix3::Zero();       ///< J_j^-1
    double cond = 0.0;                     ///< scaled 1-norm condition number of J_j
    Vector3 gamma_dot = Vector3::Zero();   ///< joint rates (eq. 4b generalised)
    Vector3 gamma_ddot = Vector3::Zero();  ///< joint accelerations
    std::array<Twist, 2> xi{};             ///< body twists referred to O
    std::array<Twist, 3> s_dot{};          ///< ds_k/dt = [xi of the body carrying joint k, s_k]
};

/// Per-sample workspace. Fixed capacity; sized once by the Model it is constructed for.
/// Frames and coordinates: every vector and twist is in the base frame; twists and wrenches
/// are referred to the base origin O unless a field says otherwise. The algorithms fill it in
/// stages (kinematics.hpp): position (p, x_P, limb q, s, x, u), velocity (t_M, xi_P, A, cond_A,
/// limb J, J_inv, cond, gamma_dot, xi, s_dot, du; Xi when the model's coordinates are the
/// actuators), acceleration (t_M_dot, xi_P_dot, gamma_ddot, ddu), shaping (Xi, Xi_dot, T, T_dot)
/// and dynamics (I, C, Q_gf, Q, tau, W_P, M_p, h_p). A field holds the last stage that set it.
struct Data {
    explicit Data(const Model& model);

    Pose p = Pose::Zero();                   ///< pose [theta, x_c, y_c] (eq. 1) [rad, m, m]
    Twist t_M = Twist::Zero();               ///< pose rates dp/dt = [omega, dx_c/dt, dy_c/dt] (eq. 2)
    Twist t_M_dot = Twist::Zero();           ///< d2p/dt2
    Twist xi_P = Twist::Zero();              ///< platform twist referred to O: xi_P = S(c) dp/dt (planar.hpp)
    Twist xi_P_dot = Twist::Zero();          ///< d xi_P / dt
    Vector2 x_P = Vector2::Zero();           ///< platform c.o.m. [m]
    std::array<LimbData, kMaxLimbs> limb{};  ///< per limb, file order (first model.limbs used)

    ActuatorVector u;     ///< actuator variables (the actuated q), size n, file order [m or rad]
    ActuatorVector du;    ///< actuator rates, size n
    ActuatorVector ddu;   ///< actuator accelerations, size n
    ActuatorVector tau;   ///< actuator forces (torques) on the outboard bodies, size n [N, N m]
    ActuationMatrix A;    ///< n x 3: du = A xi_P, the actuated rows of the J_j^-1 (eq. 5 generalised)
    double cond_A = 0.0;  ///< scaled condition number of A

    /// 3 x 3: xi_P = Xi v for the model's independent coordinates v (model.coordinates: v = du
    /// with Xi = A^-1, or v = dp/dt with Xi = S(c)), and dXi/dt. Always the model's coordinates.
    Matrix3 Xi = Matrix3::Identity();
    Matrix3 Xi_dot = Matrix3::Zero();
    /// The coordinates v of T, T_dot, I, C, Q_gf and Q: model.coordinates after twistShaping
    /// and inverseDynamics; Coordinates::platform after platformDynamics and forwardDynamics.
    Coordinates coordinates = Coordinates::platform;
    std::array<ShapingMatrix3, kMaxBodies> T{};      ///< T_i (3 x 3, body i's c.o.m. twist t_i = T_i v, eq. 22)
    std::array<ShapingMatrix3, kMaxBodies> T_dot{};  ///< dT_i/dt
    Matrix3 I = Matrix3::Zero();                     ///< 3 x 3 inertia in v (eq. 23), SPD
    Matrix3 C = Matrix3::Zero();                     ///< 3 x 3 Coriolis matrix in v (eq. 23), dI/dt = C + C^T
    Vector3 Q_gf = Vector3::Zero();                  ///< generalized gravity and friction force to supply, in v
    Vector3 Q = Vector3::Zero();                     ///< I dv + C v + Q_gf: the generalized force to supply, in v
    /// Platform wrench referred to O that the limbs must supply (lean path), [N m; N].
    Wrench W_P = Wrench::Zero();
    /// Equations of motion in the platform coordinates, M_p d2p/dt2 + h_p = A_p^T tau for every n
    /// (forward_dynamics.hpp): M_p = sum_i T_i^T M_i T_i (3 x 3) and h_p = C_p dp/dt + Q_gf with
    /// xi_P = S(c) dp/dt, A_p = A S(c).
    Matrix3 M_p = Matrix3::Identity();
    Vector3 h_p = Vector3::Zero();
};

}  // namespace nocdyn
