// 3-PRR direct displacement (forward kinematics): actuator displacements u -> platform pose p.
//
// Loop closure of limb j (eqs. 35, 40-41, with u_j as defined in model-notes.md):
//   A_j(u_j) = B_j + (s_ref_j + u_j) e_j,   M_j(p) = C + Rot(theta) M_local_j,
//   |M_j - A_j| = l,                                                       (j = 0, 1, 2)
// and the working branch of limb j is phi_Aj in (0, pi/2) (eq. 39), i.e.
//   n_j . (M_j - A_j) > 0   and   e_j . (M_j - A_j) > 0.
//
// Exact method (directDisplacement). For a fixed theta, put P_j(theta) = A_j - Rot(theta)
// M_local_j: the closures read |C - P_j| = l, three circles of the SAME radius l, so C is the
// circumcentre of P_1 P_2 P_3 (two linear equations, from subtracting the circles pairwise)
// and theta must make the circumradius equal to l. With t = tan(theta / 2), cos = (1-t^2)/w,
// sin = 2t/w, w = 1+t^2, this is one polynomial equation of degree 12 in t,
//   |N(t) w(t) - Delta(t) P~_1(t)|^2 - l^2 Delta(t)^2 w(t)^2 = 0,
// (Delta = det of the 2x2 linear system, N its adjugate times the right-hand side, P~_1 =
// w P_1), of which t = +-i are triple roots (|P~_1|^2 vanishes there), so at most six real
// roots remain: the six assembly modes. All roots come from the eigenvalues of the companion
// matrix (Eigen's PolynomialSolver); each real one gives C from the linear system, is polished
// by Newton on the three closures and verified by inverse displacement (to 1e-12 m times
// the limb conditioning 1/|cos phi_Aj|, which is 1..1e4 wherever D is accepted). theta = pi (t = oo)
// is tried as an extra starting point.
//
// Fast tracker (trackPose): Newton in actuator space from the previous pose,
//   p <- p + H^{-1} D (u - u(p))                                          (eq. 5)
// with u(p) from inverseDisplacement, so it cannot leave the working branch of any limb. An
// iterate outside the workspace or at a singular H or D is reported as such (the status of
// inverseDisplacement or velocityFromActuatorRates: limb and value), no convergence next to the
// edge of the workspace as workspace_edge; otherwise a Newton step too large or no
// convergence is assembly_mode_lost.
#pragma once

#include <array>
#include <vector>

#include "nocdyn/prr3/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn::prr3 {

/// One real solution of the direct displacement problem.
struct AssemblyMode {
    Pose p = Pose::Zero();  ///< [theta in (-pi, pi], x_c, y_c]
    /// Per limb: sign of n_j . m_j (+1: M_j on the inner side of rail line L_j).
    std::array<int, kLimbs> side{};
    /// Per limb: sign of e_j . m_j (+1: M_j ahead of A_j along e_j).
    std::array<int, kLimbs> ahead{};
    /// All limbs on the working branch phi_Aj in (0, pi/2) (side and ahead all +1).
    bool working = false;
    /// max_j | |M_j - A_j| - l | after Newton polishing [m].
    double closure_residual = 0.0;
    /// max_j |u_j(p) - u_j|, u_j(p) recomputed from the pose on this solution's own branches
    /// (by inverseDisplacement for working solutions) [m].
    double u_error = 0.0;
    /// max_j l / |e_j . m_j| = 1 / |cos phi_Aj| >= 1: how much u_j(p) amplifies rounding in p
    /// (infinite when a link is normal to its rail, where D of eq. 6 is singular).
    double limb_condition = 1.0;
    /// Condition number of H diag(1/r, 1, 1) at this pose (large near a singularity).
    double cond_H = 0.0;
};

struct DirectKinematicsOptions {
    /// Keep only the working branch of every limb (phi_Aj in (0, pi/2)).
    bool working_branch_only = true;
    /// Largest accepted closure residual of a polished solution [m]; u_error may reach
    /// verify_tolerance * limb_condition.
    double verify_tolerance = 1e-12;
};

/// Every real platform pose with actuator displacements u (see the file header), sorted by
/// theta. Allocates: not for the real-time path. Throws nocdyn::Error only if the polynomial
/// solver fails; an empty result means u cannot be assembled.
[[nodiscard]] std::vector<AssemblyMode> directDisplacement(const Model& model, const JointVector& u,
                                                           const DirectKinematicsOptions& options = {});

/// Number of real solutions without the branch restriction and on the working branches.
struct AssemblyModeCount {
    int all = 0;
    int working = 0;
};
[[nodiscard]] AssemblyModeCount countAssemblyModes(const Model& model, const JointVector& u);

struct TrackerOptions {
    int max_iterations = 25;
    /// Converged when max_j |u_j(p) - u_j| <= tolerance [m].
    double tolerance = 1e-13;
    /// A Newton step larger than this (in theta [rad] or C [m], infinity norm) means the
    /// starting pose was too far away: the mode is considered lost.
    double max_step = 0.05;
};

/// Tracker. p holds the previous pose on entry and the pose with actuator displacements u on
/// success. On success `data` holds the position stage at p (velocity stage: NOT valid; call
/// velocityFromActuatorRates next). Allocation-free. Fails with outside_workspace or a
/// singular status when an iterate is out of reach or singular; with workspace_edge when it
/// does not converge next to the edge of the workspace (a link within 1 % of normal to, or
/// along, its rail: no pose has such u); else with assembly_mode_lost (value: the residual
/// max_j |u_j(p) - u_j| [m], limb: the worst limb or -1). p is then left at the last iterate.
Status trackPose(const Model& model, Data& data, const JointVector& u, Pose& p, const TrackerOptions& options = {});

}  // namespace nocdyn::prr3
