// The NOC of a spatial parallel robot (a Delta as 3-RUU, a 6-UPS or 6-RUS hexapod): the planar
// model's stages carried to six-dimensional twists.
//
// Screws and twists are 6-vectors [angular; linear] referred to the base frame's origin O; a
// wrench [moment about O; force] pairs with a twist by the dot product (power). Every limb is a
// serial chain of one-freedom screws s_k (an R joint [a; r x a], a P joint [0; d]; a U two R
// screws through its point, an S three along the base axes at home), one moving body after
// each listed joint but the last. Per sample, as the planar stages (docs/architecture.md):
//   position   the limb's joint variables q_j by Newton on the product of exponentials
//              g_j(q_j) = exp(s_1 q_1) ... exp(s_n q_n) = D(p), D the platform's displacement
//              from home; the current screws s_k and the bodies' c.o.m. and inertia;
//   velocity   t_P = J_j gd_j (eq. 3 in 6-D), gd_j = J_j^+ t_P, J_j = [s_1 ... s_n] (6 x n,
//              n = 6, or 5 for a translation robot's RUU limb: J_j^+ its left inverse, exact
//              because t_P lies in its span);
//   accel.     gdd_j = J_j^+ (dt_P - sum_k ds_k gd_k), ds_k = t_(k-1) x s_k (the screw carried
//              by the body before joint k);
//   forces     w_i = M_i dt_i + t_i x* M_i t_i - gravity (Newton-Euler about the c.o.m.,
//              referred to O), the joints' efforts f_k = s_k . (the wrenches outboard of k)
//              plus friction, W_P = w_P + sum_j J_j^+T f_j; then A_E^T tau = E^T W_P, A the
//              actuated rows of the J_j^+ and E the task map (I_6, or [0; I_3] for a
//              translation robot): tau = A_E^-T E^T W_P, or the minimum-norm forces.
// The pose p is [x, y, z, roll, pitch, yaw] with R = Rz(yaw) Ry(pitch) Rx(roll) (motion full),
// or [x, y, z]; dp and ddp its time derivatives (Euler-angle rates, not the angular velocity).
// Model/Data as the planar core: the per-sample functions allocate nothing and return a Status.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/spatial_description.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn::spatial {

inline constexpr int kMaxFreedoms = 6;                                 ///< per limb
inline constexpr int kMaxBodies = 5;                                   ///< per limb (six listed joints at most)
inline constexpr int kMaxActuators = 12;                               ///< per robot
using Vector6 = Eigen::Matrix<double, 6, 1>;                           ///< a screw, twist or wrench [angular; linear]
using TaskVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;  ///< p, dp or ddp (3 or 6)
using LimbJacobian = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxFreedoms>;
using LimbInverse = Eigen::Matrix<double, Eigen::Dynamic, 6, 0, kMaxFreedoms, 6>;
using FreedomVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxFreedoms, 1>;
using ActuatorVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxActuators, 1>;
using ActuationMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxActuators, 6>;
using TaskMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;  ///< d x d

/// One freedom of a limb: a revolute or prismatic screw at home.
struct Freedom {
    bool revolute = true;
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< R: the axis; P: the direction (unit)
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< R: a point of the axis
    Vector6 screw = Vector6::Zero();                  ///< s_k at home
    int joint = 0;                                    ///< the listed joint it belongs to
    int actuator = -1;                                ///< its actuator, or -1
    double damping = 0.0;                             ///< its viscous coefficient, N s/m or N m s/rad
    double friction = 0.0;                            ///< its Coulomb force, N or N m
    JointLimits limits;
};

/// A moving body of a limb at home, and the last freedom it moves with.
struct Body {
    double mass = 0.0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();      ///< at home, base frame
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about the c.o.m., base frame at home
    int last_freedom = 0;
};

/// How a limb's inverse kinematics is solved, from its joints when the model is built: in
/// closed form on the home branch (U-P-S, R-U-S, R-U-U), or by Newton.
enum class LimbSolver { newton, ups, rus, ruu };

struct Limb {
    std::string name;
    std::vector<Freedom> freedoms;
    std::vector<Body> bodies;
    LimbSolver solver = LimbSolver::newton;
    double branch = 1.0;  ///< the sign of the home root of the leg's length or the crank's angle
    double elbow = 1.0;   ///< the sign of the home root of the (first) U's two angles
    [[nodiscard]] int size() const { return static_cast<int>(freedoms.size()); }
};

/// The constant part of a spatial robot, prepared from its description.
class Model {
public:
    /// Throws nocdyn::Error for what the per-sample path cannot take (more than kMaxFreedoms
    /// in a limb, kMaxActuators actuators, fewer actuators than pose coordinates).
    explicit Model(const SpatialRobotDescription& description);

    std::string name;
    PlatformMotion motion = PlatformMotion::full;
    int task_dimension = 6;  ///< 6, or 3 for motion translation
    int actuators = 0;
    double max_condition = 1.0e4;
    Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
    TaskVector home;  ///< the pose at home
    Eigen::Matrix3d home_rotation = Eigen::Matrix3d::Identity();
    double platform_mass = 0.0;
    Eigen::Vector3d platform_com = Eigen::Vector3d::Zero();      ///< platform frame
    Eigen::Matrix3d platform_inertia = Eigen::Matrix3d::Zero();  ///< about the c.o.m., platform frame
    std::vector<Limb> limb;
    /// actuator a's limb and freedom
    std::vector<std::pair<int, int>> actuator;

    [[nodiscard]] int limbs() const { return static_cast<int>(limb.size()); }
    /// The pose coordinates' names: x, y, z (and roll, pitch, yaw).
    [[nodiscard]] std::vector<std::string> coordinates() const;
};

/// One limb's per-sample quantities.
struct LimbData {
    FreedomVector q;                                  ///< joint variables
    FreedomVector gd;                                 ///< their rates
    FreedomVector gdd;                                ///< their accelerations
    LimbJacobian J;                                   ///< current screws s_k, column by column
    LimbInverse J_plus;                               ///< J^+ (J^-1 when square)
    std::array<Eigen::Vector3d, kMaxBodies> com;      ///< current c.o.m.
    std::array<Eigen::Matrix3d, kMaxBodies> inertia;  ///< about the c.o.m., base frame
    std::array<Vector6, kMaxBodies> twist;            ///< referred to O
    std::array<Vector6, kMaxBodies> twist_rate;       ///< referred to O
    std::array<Vector6, kMaxBodies> wrench;           ///< inertia wrench less gravity, about O
    /// The effort each freedom needs to move the limb's own bodies, with its friction (no
    /// platform): f_k = s_k . (the wrenches outboard of k) + damping gd_k + friction sign gd_k.
    FreedomVector effort;
    /// The listed joints' points (R, U, S; a P joint's entry is unused): joint 0 on the base,
    /// joint b + 1 moving with body b.
    std::array<Eigen::Vector3d, kMaxBodies + 1> joint_point;
    /// of J at the platform's point (largest over smallest singular value): after
    /// inverseKinematics an upper bound (exact when above the model's limit), exact after
    /// conditionNumbers
    double condition = 1.0;
    bool closed = false;       ///< q holds a solution (the next Newton starts there)
    bool closed_form = false;  ///< q came from the limb's closed form (not from Newton)
};

/// Every per-sample quantity; sized once from the model.
struct Data {
    explicit Data(const Model& model);
    std::vector<LimbData> limb;
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< the platform's orientation
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Vector6 t_P = Vector6::Zero();   ///< the platform twist
    Vector6 dt_P = Vector6::Zero();  ///< its rate
    Vector6 W_P = Vector6::Zero();   ///< sum_i T_i^T w_i
    Vector6 platform_wrench = Vector6::Zero();
    ActuationMatrix A;  ///< n x 6: the actuator rates du = A t_P
    /// n x d: du = A_task (v, w), v the platform point's velocity and w the angular velocity
    ActuationMatrix A_task;
    ActuatorVector u;    ///< actuator variables
    ActuatorVector du;   ///< their rates
    ActuatorVector ddu;  ///< their accelerations
    ActuatorVector tau;  ///< actuator forces
    /// of A_task (lengths in metres): an upper bound or exact, as LimbData::condition
    double actuation_condition = 1.0;
};

/// The platform's orientation R = Rz(yaw) Ry(pitch) Rx(roll).
[[nodiscard]] Eigen::Matrix3d rotation(double roll, double pitch, double yaw);

/// The cross-product matrix [v]: [v] x = v x x.
[[nodiscard]] inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
    Eigen::Matrix3d s;
    s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
    return s;
}

/// Inverse kinematics: every limb's joint variables at pose p, the current screws, the bodies'
/// c.o.m. and inertia, J_j^+, the actuator values u and the actuation map A. In closed form on
/// the home branch for the limbs that have one (Limb::solver), otherwise (or when it finds no
/// root) Newton from the previous solution (from home when there is none or it fails).
[[nodiscard]] Status inverseKinematics(const Model& model, Data& data, const TaskVector& p);

/// The exact condition numbers LimbData::condition and Data::actuation_condition after
/// inverseKinematics (which leaves upper bounds there: ||J_P||_F ||L||_F for a left inverse L, and
/// sqrt(trace G trace G^-1) for G = A_task^T A_task, needing no eigenvalues), by the
/// eigenvalues of their Gram matrices.
void conditionNumbers(const Model& model, Data& data);

/// Inverse dynamics: u, du, ddu and the actuator forces tau at (p, dp, ddp).
[[nodiscard]] Status inverseDynamics(const Model& model, Data& data, const TaskVector& p, const TaskVector& dp,
                                     const TaskVector& ddp);

/// The mass matrix M of the pose coordinates at p: E^T W_P(p, 0, ddp) = M ddp without gravity
/// (column i the inertia wrench of the unit acceleration e_i). Allocation-free.
[[nodiscard]] Status massMatrix(const Model& model, Data& data, const TaskVector& p, TaskMatrix& M);

/// Forward dynamics: the pose accelerations ddp under the actuator forces tau at the state
/// (p, dp), from E^T W_P(p, dp, ddp) = A_E^T tau, W_P affine in ddp: M ddp = A_E^T tau - h with
/// M's columns the inertia wrenches of unit accelerations (no gravity, at rest) and h the
/// wrench of (p, dp) at rest in acceleration (gravity, friction, the rates' terms). Every limb
/// follows from p (inverseKinematics), so a motion integrated in (p, dp) stays closed. Leaves
/// every stage at (p, dp, ddp) in data and data.tau = tau. Allocation-free.
[[nodiscard]] Status forwardDynamics(const Model& model, Data& data, const TaskVector& p, const TaskVector& dp,
                                     const ActuatorVector& tau, TaskVector& ddp);

/// The kinetic energy of every body and of the platform, and their potential energy in
/// gravity, after inverseDynamics (or inverseKinematics and the twists of a velocity pass).
[[nodiscard]] double kineticEnergy(const Model& model, const Data& data);
[[nodiscard]] double potentialEnergy(const Model& model, const Data& data);

/// One line naming the limb (by name and number) and the quantity.
[[nodiscard]] std::string describe(const Status& status, const Model& model);

}  // namespace nocdyn::spatial
