// The 3-PRR robot of the paper: constant model and per-sample data.
//
// Model: everything that does not change with the posture (geometry of eqs. 8 and 35, the
// seven inertia dyads of eq. 9, actuator limits), built and validated once.
// Data: every per-sample quantity, fixed-size, filled by the stage functions of
// kinematics.hpp and dynamics.hpp in the order
//   position  (inverseDisplacement)             -> u, phi_A, phi_M, A_j, M_j, m_j
//   velocity  (velocityFromPlatformTwist or
//              velocityFromActuatorRates)       -> J_j, H, D, H^-1, t_M, du, gamma_dot_j
//   shaping   (twistShaping)                    -> T_i, dT_i, dH, dD       (eqs. 24-31)
//   dynamics  (jointSpaceDynamics)              -> I, C                    (eq. 23)
//   forces    (actuatorForces)                  -> tau                     (eq. 20)
// Limbs are 0..2 here and 1..3 in the paper; bodies are 0..6 here and 1..7 in the paper:
// sliders 0..2, links 3..5, platform 6.
#pragma once

#include <array>

#include "nocdyn/noc.hpp"
#include "nocdyn/prr3/kernel_constants.hpp"
#include "nocdyn/planar.hpp"
#include "nocdyn/io/short_form.hpp"

namespace nocdyn::prr3 {

inline constexpr int kBodies = 7;
inline constexpr int kDof = 3;

using ShapingMatrix = noc::ShapingMatrix<kDof>;
using JointMatrix = noc::JointMatrix<kDof>;
using JointVector = noc::JointVector<kDof>;

/// Index of the paper's body i (1..7) in code: slider j -> j-1, link j -> j+2, platform -> 6.
inline constexpr int sliderBody(int limb) { return limb; }
inline constexpr int linkBody(int limb) { return limb + 3; }
inline constexpr int kPlatformBody = 6;

/// Constant parameters of a 3-PRR robot. Immutable after construction.
class Model {
public:
    /// Validates the parameters (throws nocdyn::Error) and precomputes the geometry.
    explicit Model(const io::RobotParameters& parameters = io::RobotParameters{});

    io::RobotParameters parameters;    ///< as given (SI)
    double R = 0.0;                    ///< base circumradius b / sqrt(3) [m]
    double r = 0.0;                    ///< platform circumradius a / sqrt(3) [m]
    double l = 0.0;                    ///< link length [m]
    double l_c = 0.0;                  ///< A_j to link c.o.m. [m]
    std::array<double, kLimbs> phi{};  ///< phi_j, angle from X to e_j (eq. 8) [rad]
    std::array<Vector2, kLimbs> e{};   ///< e_j, rail direction (eq. 40)
    std::array<Vector2, kLimbs> n{};   ///< E e_j, inward normal of rail line L_j
    std::array<Vector2, kLimbs> B{};   ///< B_j, base vertex on L_j (eq. 35) [m]
    /// Platform vertex M_j - C in the platform frame at theta = 0: r [cos, sin](phi_j - pi/6).
    std::array<Vector2, kLimbs> M_local{};
    /// e_j . (A_j - B_j) at the reference posture (theta = 0, C = O), so that
    /// u_j = e_j . (A_j - B_j) - s_ref_j [m].
    std::array<double, kLimbs> s_ref{};
    /// Inertia dyads M_i (eq. 9), bodies 0..6 (sliders, links, platform).
    std::array<InertiaDyad, kBodies> M{};
    /// The constants above in the layout of the lean and batch kernels (batch.hpp, fast.hpp),
    /// computed last by the constructor: a Model always carries its own.
    batch_detail::Constants kernel{};
};

/// Per-sample workspace. Fixed-size members only; sized once, reused for every sample.
struct Data {
    // --- position stage (inverseDisplacement) ---
    Pose p = Pose::Zero();                ///< [theta, x_c, y_c] (eq. 1)
    JointVector u = JointVector::Zero();  ///< actuator displacements u_j [m]
    Vector3 d_M = Vector3::Zero();        ///< d_j^M, distance M_j to L_j (eq. 38) [m]
    Vector3 phi_A = Vector3::Zero();      ///< phi_Aj, from e_j to A_jM_j (eq. 39) [rad]
    Vector3 phi_M = Vector3::Zero();      ///< phi_Mj, from A_jM_j to the MP side (eq. 39) [rad]
    Vector3 sin_phi_A = Vector3::Zero();  ///< sin phi_Aj = d_j^M / l
    Vector3 cos_phi_A = Vector3::Zero();  ///< cos phi_Aj = d_j (eq. 6)
    std::array<Vector2, kLimbs> A{};      ///< A_j, proximal R joint [m]
    std::array<Vector2, kLimbs> Mj{};     ///< M_j, distal R joint (platform vertex) [m]
    std::array<Vector2, kLimbs> m{};      ///< m_j = A_j M_j (eq. 40) [m]
    std::array<Vector2, kLimbs> p_A{};    ///< p_Aj = A_j C (eq. 42) [m]
    std::array<Vector2, kLimbs> p_M{};    ///< p_Mj = M_j C (eq. 41) [m]

    // --- velocity stage ---
    std::array<Matrix3, kLimbs> J{};          ///< J_j, limb Jacobian (eq. 4a)
    std::array<Matrix3, kLimbs> J_inv{};      ///< J_j^{-1}
    Matrix3 H = Matrix3::Zero();              ///< forward Jacobian (eq. 7), rows [h_j1 h_j2 h_j3]
    Matrix3 H_inv = Matrix3::Zero();          ///< H^{-1}
    Vector3 D = Vector3::Zero();              ///< diagonal of the inverse Jacobian D (eq. 6)
    double cond_H = 0.0;                      ///< 1-norm condition number of H diag(1/r, 1, 1) (dimensionless)
    double cond_D = 0.0;                      ///< condition number of D: max d_j / min d_j
    Twist t_M = Twist::Zero();                ///< platform twist dp/dt (eq. 2)
    JointVector du = JointVector::Zero();     ///< actuator rates [m/s]
    std::array<Vector3, kLimbs> gamma_dot{};  ///< [du_j, dphi_Aj, dphi_Mj] (eq. 4b, 29)

    // --- shaping stage (twistShaping) ---
    Matrix3 H_dot = Matrix3::Zero();             ///< dH/dt
    Vector3 D_dot = Vector3::Zero();             ///< dD/dt (diagonal)
    std::array<ShapingMatrix, kBodies> T{};      ///< T_i (eqs. 25-31), t_i = T_i du
    std::array<ShapingMatrix, kBodies> T_dot{};  ///< dT_i/dt

    // --- acceleration, dynamics and forces ---
    Twist t_M_dot = Twist::Zero();          ///< d2p/dt2
    JointVector ddu = JointVector::Zero();  ///< actuator accelerations [m/s^2]
    JointMatrix I = JointMatrix::Zero();    ///< joint-space inertia (eq. 23) [kg]
    JointMatrix C = JointMatrix::Zero();    ///< Coriolis matrix (eq. 23) [kg/s]
    JointVector tau = JointVector::Zero();  ///< actuator forces on the sliders (eq. 20) [N]
};

}  // namespace nocdyn::prr3
