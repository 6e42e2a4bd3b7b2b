// Static stiffness and natural frequencies of the platform at a pose, by the virtual joint
// method (VJM) on the compliance the robot file declares (description.hpp):
//   - a joint with a stiffness k is a spring about its position at the pose (N/m, N m/rad);
//     an actuated joint without one is locked, a passive one is free;
//   - an elastic body is an Euler-Bernoulli cantilever clamped at its inboard joint, loaded
//     at its outboard joint, with the exact tip compliance in its axis frame (e, n = E e):
//       C_b = [l/EA 0 0; 0 l^3/(3 EI) l^2/(2 EI); 0 l^2/(2 EI) l/EI]  on [u_e, v_n, phi],
//     whose deflection moves the outboard chain by the twist G_b [u; v; phi],
//     G_b = [[0; e], [0; n], s_B], s_B the revolute screw at the outboard joint.
// Limb j (twists referred to O, wrenches dual to them):
//   C_j = sum_springs s s^T / k + sum_elastic G_b C_b G_b^T       compliance of its springs
//   G_f = [s of the free joints];  N = basis of null(G_f^T)       wrenches a limb can carry
//   K_j = N (N^T C_j N)^-1 N^T                                    (free joints carry no load)
// and the platform, in the pose coordinates p = [theta, x, y] (xi_P = S(c) dp/dt):
//   K = S^T (sum_j K_j) S.
// Gravity's preload (the geometric stiffness of the loaded joints) is ignored: K is the
// stiffness of the unloaded structure.
//
// Free directions are decided by the geometry, never by K's values: limb j carries the
// wrenches span(N_j), so dp is free when N_j^T S dp = 0 for every limb (a rank decision on unit
// columns in metres). A direction held by a stiffness 1e10 times softer than the stiffest is
// held, not free. K's softest held eigenvalue is then known to about eps times the contrast
// lambda_max / lambda_min (eps = 2.2e-16): above kContrastWarning a named warning gives the
// precision left, above kContrastLimit (a digit at most) cartesianStiffness fails with
// stiffness_contrast.
//
// Natural frequencies, lumped model: K v = w^2 M v with M = sum_i T_i^T M_i T_i, the NOC's
// inertia mapped to the pose coordinates (the rigid bodies' mass matrix).
// Elastodynamic model: every body keeps its inertia and every virtual spring (drive,
// flexure, beam deflection) is a degree of freedom; x = [dp; z_1 ... z_L], closure
// S dp = G_j z_j per limb (A x = 0), stiffness energy z_s^T C_s^-1 z_s / 2 on the spring
// coordinates z_s = P x (C_s: 1/k per spring, C_b per beam). An elastic body's inertia rides
// on its root (inboard joint); its beam adds the tip DOFs. The modes are found in flexibility
// form, mixed in the springs' forces g and the closure's multipliers l:
//   [0 P^T A^T; P -C_s 0; A 0 0] [x; g; l] = [f; 0; 0]   gives x = F f,
//   (L^T F L) y = mu y,  M_x = L L^T,  w^2 = 1 / mu,  x = F L y / mu,
// so that a stiff beam (C_b -> 0) tends to a rigid link instead of swamping the soft springs
// in rounding, and coordinates that carry no mass (a beam tip's rotation at a free pivot) are
// condensed statically, exactly. With free directions (F unbounded) the mass-proportional
// shift K + sigma M_x is factored instead (its x block sigma M_x).
// With rigid bodies the two models are one.
//
// Mixed units: rotations are scaled by the model's length_scale L wherever a rank or a
// threshold is decided, so that every decision is in metres.
#pragma once

#include <array>
#include <span>
#include <string>

#include <Eigen/Core>

#include "nocdyn/choice.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// One pose coordinate as reported: its name, unit and index in nocdyn::Pose.
struct PoseCoordinate {
    const char* name;
    const char* unit;
    int index;
};

/// The pose coordinates in the order every stiffness and mode result is reported: the user's
/// order x, y, theta (planar.hpp's userPose), as every table and array. The one place that
/// order is decided for compliance results.
inline constexpr std::array<PoseCoordinate, 3> kReportedCoordinates{
    {{"x", "m", 1}, {"y", "m", 2}, {"theta", "rad", 0}}};

/// "theta [rad]", "x [m]", "y [m]": coordinate r of the reported order.
[[nodiscard]] std::string coordinateLabel(int r);
/// Unit of entry (r, c) of K in the reported order: N m/rad, N/rad, N, N/m.
[[nodiscard]] std::string stiffnessUnit(int r, int c);
/// A pose-ordered vector or matrix in the reported order.
[[nodiscard]] Vector3 reported(const Vector3& v);
[[nodiscard]] Matrix3 reported(const Matrix3& m);
/// A pose displacement described in words: "a rotation about (x, y) = (0.01, 0) m" or "a
/// translation along (0.6, 0.8)".
[[nodiscard]] std::string describeDirection(const Vector3& dp);

/// What a joint does under load.
enum class JointSpring { locked, free, spring };

/// Constant compliance of a robot, prepared from its description.
struct StiffnessModel {
    explicit StiffnessModel(const Model& model);

    std::array<std::array<JointSpring, 3>, kMaxLimbs> joint{};
    std::array<std::array<double, 3>, kMaxLimbs> k{};  ///< spring joints [N/m, N m/rad]
    std::array<std::array<bool, 2>, kMaxLimbs> elastic{};
    /// Elastic bodies: tip compliance C_b on [u_e, v_n, phi] [m/N, 1/N, rad/(N m)].
    std::array<std::array<Matrix3, 2>, kMaxLimbs> beam_compliance{};
    bool any = false;          ///< any compliance declared at all
    bool any_elastic = false;  ///< any elastic body
};

/// Contrast lambda_max / lambda_min of the scaled K's held eigenvalues above which the lowest
/// natural frequency keeps fewer than about six digits (a named warning), and above which it
/// keeps at most one (stiffness_contrast: a relative error of 2e-2 and more).
inline constexpr double kContrastWarning = 1e10;
inline constexpr double kContrastLimit = 1e14;

/// Static stiffness at one pose.
struct StiffnessData {
    /// 3 x 3 stiffness in the pose coordinates (nocdyn::Pose order): dQ = K dp, Q the
    /// generalized force [moment about C, f_x, f_y] [N m, N].
    Matrix3 K = Matrix3::Zero();
    std::array<Matrix3, kMaxLimbs> K_limb{};  ///< K_j on twists referred to O
    /// Eigen-decomposition of the scaled K_s = D^-1 K D^-1, D = diag(L, 1, 1) [N/m].
    Vector3 scaled_eigenvalues = Vector3::Zero();
    Matrix3 scaled_eigenvectors = Matrix3::Identity();
    /// Dimension of the null space: the directions no limb carries a wrench in (geometry);
    /// the first free_directions columns of scaled_eigenvectors span it (eigenvalue 0).
    int free_directions = 0;
    /// The first free_directions columns: unit free directions dp (pose order, scaled unit).
    Matrix3 free = Matrix3::Zero();
    /// lambda_max / lambda_min of the held scaled eigenvalues (1 when none is held).
    double contrast = 1.0;
};

/// "" when contrast <= kContrastWarning, else a one-line warning naming the contrast and the
/// relative precision left to the lowest natural frequency.
[[nodiscard]] std::string contrastWarning(const StiffnessData& stiffness);

/// K at the pose of `data` (its position stage done). Fails with rigid_limb naming the
/// limb when a limb does not yield in some direction, with stiffness_contrast when the held
/// eigenvalues' contrast exceeds kContrastLimit. Allocation-free.
Status cartesianStiffness(const Model& model, const StiffnessModel& compliance, const Data& data, StiffnessData& out);

/// C_j of limb j at the pose of `data`: sum_springs s s^T / k + sum_elastic G_b C_b G_b^T, on
/// wrenches referred to O (unscaled) [m/N, rad/N ...]. Allocation-free.
[[nodiscard]] Matrix3 limbCompliance(const StiffnessModel& compliance, const Data& data, int j);

/// The displacement dp (pose order) under a generalized force f = [moment about C, f_x, f_y]:
/// K dp = f. False (dp untouched) when f loads a free direction (no equilibrium); with free
/// directions it does not load, the displacement with no free component.
[[nodiscard]] bool displacementUnderWrench(const StiffnessData& stiffness, double length_scale, const Vector3& f,
                                           Vector3& dp);

/// Modes: frequencies in Hz, ascending, and shapes (columns, mass-normalised).
struct LumpedModes {
    Matrix3 M = Matrix3::Identity();      ///< mass matrix in the pose coordinates
    Vector3 frequency = Vector3::Zero();  ///< [Hz], ascending (0 for a free direction)
    Matrix3 shape = Matrix3::Zero();      ///< columns dp, pose order, v^T M v = 1
};

/// Lumped modes K v = w^2 M v at the pose of `data`, which must hold the shaping stage.
/// The free directions are the first modes (0 Hz, their shapes the M-normalised free
/// directions); the others are solved on the M-orthogonal complement, so that a free
/// direction's rounding never passes for a soft mode. Allocation-free.
void lumpedModes(const Model& model, const Data& data, const StiffnessData& stiffness, LumpedModes& out);

/// The stiffness and lumped modes over the task coordinates p_t (model.hpp's task map E, n_t =
/// model.task_dimension, pose order): K_t = E^T K E, M_t = E^T M E, K_t v = w^2 M_t v. For a
/// two-DOF robot (motion: translation) theta is no coordinate: a rotation about the tool point
/// C moves no body and loads no limb (every limb's last joint is a free R joint at C), so K's
/// and M's theta rows and columns are zero and K_t, M_t are their x, y blocks (2 x 2), with
/// K_t = A_t^T diag(k) A_t for springs k at the actuators alone. For a three-DOF robot these are
/// K, M and lumpedModes' frequencies and shapes.
struct TaskModes {
    using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
    using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
    Matrix K;          ///< n_t x n_t stiffness [N/m, N/rad, N m/rad]
    Matrix M;          ///< n_t x n_t mass matrix
    Vector frequency;  ///< n_t natural frequencies [Hz], ascending (0 for a free direction)
    Matrix shape;      ///< columns dp_t, v^T M_t v = 1
};

/// TaskModes at the pose of `data` (the shaping stage done), from K (cartesianStiffness) and,
/// for a three-DOF robot, its lumped modes. Allocation-free.
void taskModes(const Model& model, const Data& data, const StiffnessData& stiffness, const LumpedModes& lumped,
               TaskModes& out);

/// Every stage needed, at pose p: the position, velocity (at rest) and shaping stages, K
/// and the lumped modes.
Status stiffnessAndModes(const Model& model, const StiffnessModel& compliance, Data& data, const Pose& p,
                         StiffnessData& stiffness, LumpedModes& modes);

/// Elastodynamic modes (allocates; not for the per-sample path).
struct ElastodynamicModes {
    int dofs = 0;                    ///< independent coordinates with mass (massless ones condensed)
    Eigen::VectorXd frequency;       ///< [Hz], ascending
    Eigen::MatrixXd platform_shape;  ///< 3 x dofs: the platform's dp in each mode (pose order)
    Eigen::MatrixXd shape;           ///< all coordinates x = [dp; z_1 ... z_L] in each mode
    Eigen::MatrixXd K, M;            ///< stiffness and mass on the dofs coordinates, for checks
    /// dofs x 3: phi_i^T M_x x_a, x_a the rigid image (links undeformed, springs at rest on the
    /// drives' commanded motion) of a unit platform displacement along pose axis a; the commanded
    /// motion drives mode i by w_i^2 times it, and platform_shape * participation = I. No columns
    /// when a locked joint leaves a limb without that image.
    Eigen::MatrixXd participation;
    /// The static stiffness of the platform by condensing the model (Schur complement):
    /// an independent computation of K (pose order).
    Matrix3 K_condensed = Matrix3::Zero();
    /// Estimated relative precision of the least precise frequency reported: each mode comes
    /// from the stiffness or the flexibility form, whichever rounds less for it, so that the
    /// worst is about eps sqrt(lambda_max / lambda_min) (0 with a single frequency).
    double precision = 0.0;
};

/// Relative difference between the lumped and the elastodynamic first natural frequency above
/// which the lumped model is said not to hold at the pose (kLumpedMismatch, 5 %).
inline constexpr double kLumpedMismatch = 0.05;

/// Whether the lumped model holds at the pose: the robot has no elastic body (elastic.dofs == 0),
/// either first frequency is 0 (a free direction), or the two are within kLumpedMismatch. Where it
/// does not (next to a limb singularity the lumped M carries the links rigidly while their speeds
/// diverge), every default answer and every bound on f_1 uses the elastodynamic frequencies.
[[nodiscard]] bool lumpedHolds(const LumpedModes& lumped, const ElastodynamicModes& elastic);

/// "" when lumpedHolds, else a one-line warning naming both first frequencies; `elastic_used`
/// says the elastodynamic frequencies are the ones given (the default answer), else that the
/// lumped ones were asked for explicitly.
[[nodiscard]] std::string lumpedMismatchWarning(const LumpedModes& lumped, const ElastodynamicModes& elastic,
                                                bool elastic_used = true);

/// Whether the lumped model fails at the pose of `data` (stiffnessAndModes done, giving `lumped`):
/// the robot has elastic bodies, their elastodynamic modes (then in `elastic`) are finite and
/// !lumpedHolds. False where the elastodynamic model fails at the pose (a rigid limb, a degree of
/// freedom with neither mass nor stiffness): the lumped answer and its own errors stand there.
[[nodiscard]] bool lumpedFailsAt(const Model& model, const StiffnessModel& compliance, const Data& data,
                                 const LumpedModes& lumped, ElastodynamicModes& elastic);

/// The limbs' largest scaled condition number (LimbData::cond) from which a map checks the lumped
/// model against the elastodynamic one. The lumped M carries every link rigidly at the speeds
/// J_j^-1 gives it, which diverge as cond grows. Towards the reach boundaries of the 3-RRR with
/// elastic links and of the compliant 3-PRR the two first frequencies agree to 0.1 % below cond
/// 100 and to 0.3 % up to 150, and part by 5 % only beyond 480 (docs/stiffness.md), so the check
/// is skipped below it, where it would cost an elastodynamic solve per point for nothing.
inline constexpr double kLumpedCheckCondition = 100.0;

/// Whether a limb of the pose of `data` (velocity stage done) is within kLumpedCheckCondition of
/// a singularity, where the lumped model may fail. Allocation-free.
[[nodiscard]] bool nearLimbSingularity(const Model& model, const Data& data);

/// The model a reported first natural frequency comes from: the lumped one (K v = w^2 M v at the
/// platform), or the elastodynamic one where the lumped one does not hold (lumpedFailsAt).
enum class FrequencyModel { lumped, elastodynamic };

inline constexpr std::array<Choice<FrequencyModel>, 2> kFrequencyModels{
    {{FrequencyModel::lumped, "lumped"}, {FrequencyModel::elastodynamic, "elastodynamic"}}};
[[nodiscard]] constexpr std::span<const Choice<FrequencyModel>> choices(FrequencyModel) { return kFrequencyModels; }

/// The first natural frequency [Hz] to use at the pose of `data` (stiffnessAndModes done, giving
/// `lumped`): the lumped one where it holds, else (lumpedFailsAt) the elastodynamic one, and then
/// `warning` (when not null) gets lumpedMismatchWarning. Allocates only with elastic bodies.
[[nodiscard]] double firstFrequency(const Model& model, const StiffnessModel& compliance, const Data& data,
                                    const LumpedModes& lumped, std::string* warning = nullptr);

/// "" when elastic.precision <= 1e-6, else a one-line warning naming it.
[[nodiscard]] std::string elastodynamicPrecisionWarning(const ElastodynamicModes& elastic);

/// At the pose of `data` (position stage done). Fails with rigid_limb; throws nocdyn::Error
/// when a degree of freedom carries no mass.
Status elastodynamicModes(const Model& model, const StiffnessModel& compliance, const Data& data,
                          ElastodynamicModes& out);

}  // namespace nocdyn
