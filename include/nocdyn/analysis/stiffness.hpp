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
// Natural frequencies, lumped model: K v = w^2 M v with M = sum_i T_i^T M_i T_i, the NOC's
// inertia mapped to the pose coordinates (the rigid bodies' mass matrix).
// Elastodynamic model: every body keeps its inertia and every virtual spring (drive,
// flexure, beam deflection) is a degree of freedom; x = [dp; z_1 ... z_L], closure
// S dp = G_j z_j per limb, x = Z y on its null space, (Z^T H Z) v = w^2 (Z^T M_x Z) v.
// An elastic body's inertia rides on its root (inboard joint); its beam adds the tip DOFs.
// Coordinates that carry no mass (a beam tip's rotation at a free pivot) are condensed
// statically, which is exact for them.
// With rigid bodies the two models are one.
//
// Mixed units: rotations are scaled by the model's length_scale L wherever a rank or a
// threshold is decided, so that every decision is in metres.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn::analysis {

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

/// Static stiffness at one pose.
struct StiffnessData {
    /// 3 x 3 stiffness in the pose coordinates (nocdyn::Pose order): dQ = K dp, Q the
    /// generalized force [moment about C, f_x, f_y] [N m, N].
    Matrix3 K = Matrix3::Zero();
    std::array<Matrix3, kMaxLimbs> K_limb{};  ///< K_j on twists referred to O
    /// Eigen-decomposition of the scaled K_s = D^-1 K D^-1, D = diag(L, 1, 1) [N/m].
    Vector3 scaled_eigenvalues = Vector3::Zero();
    Matrix3 scaled_eigenvectors = Matrix3::Identity();
    int free_directions = 0;  ///< dimension of K's null space
    /// The first free_directions columns: unit free directions dp (pose order, scaled unit).
    Matrix3 free = Matrix3::Zero();
};

/// K at the pose of `data` (its position stage done). Fails with rigid_limb naming the
/// limb when a limb does not yield in some direction. Allocation-free.
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
/// Allocation-free.
void lumpedModes(const Model& model, const Data& data, const StiffnessData& stiffness, LumpedModes& out);

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
    /// The static stiffness of the platform by condensing the model (Schur complement):
    /// an independent computation of K (pose order).
    Matrix3 K_condensed = Matrix3::Zero();
};

/// At the pose of `data` (position stage done). Fails with rigid_limb; throws nocdyn::Error
/// when a degree of freedom carries no mass.
Status elastodynamicModes(const Model& model, const StiffnessModel& compliance, const Data& data,
                          ElastodynamicModes& out);

}  // namespace nocdyn::analysis
