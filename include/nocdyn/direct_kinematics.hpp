// Direct kinematics of the general planar parallel robot (model.hpp): actuator values u ->
// every platform pose p = [theta, x, y] the robot assembles in, with every limb's branch.
//
// Constraints. With its actuated joints locked, limb j (product of exponentials from home,
// D = E_1(q_1) E_2(q_2) E_3(q_3), D the platform's displacement from home) is a chain of
// 3 - a_j passive joints and restricts D by a_j scalar equations. Moving the locked motions
// to the ends of the chain (E_a F E_b = E_a (F E_b F^-1) F), the passive joints a < b leave:
//   R R   a platform point at a fixed distance from a base point            (circle)
//   P R   a platform point on a base-fixed line                            (linear in C)
//   R P   a platform-fixed line through a base point                        (linear in C)
//   P P   the platform's orientation                                       (theta fixed)
//   R     a platform point on a base point (two linear equations)
//   P     the orientation and a platform point on a base-fixed line
//   none  the whole pose (a_j = 3).
// For a fixed angle phi = theta - theta_home every equation reads
//   kappa |C|^2 + a(phi) . C + b(phi) = 0,   kappa in {0, 1},
// with a and b linear in cos phi and sin phi: the circles share |C|^2, so their pairwise
// differences are linear in C.
//
// Elimination (no orientation equation). Two linear equations (or circle differences) give
// C = N(t) / Delta(t) by Cramer's rule, t = tan(phi / 2), after multiplying through by
// w = 1 + t^2; substituting into a third (a circle, or a linear equation) leaves one
// polynomial in t of degree <= 10 (<= 6 for three linear ones). Its roots are the eigenvalues
// of the balanced companion matrix (Eigen: its companion balancing and EigenSolver, as its
// PolynomialSolver does, in fixed-capacity storage: no allocation); the
// real ones, and phi = pi (t = oo), are candidates. With an orientation equation, phi is known
// and C solves the rest (two lines, or a line and a circle). Each candidate's C comes from the
// best-conditioned pair of linear equations at its phi (or a line meeting a circle when only
// one is independent there), is polished by Gauss-Newton on every equation, and is kept only
// if inverse displacement, on the branch of each limb that reproduces the limb's actuator
// values, gives back u to `tolerance`. Redundant actuation (n > 3): three equations are
// eliminated and the rest are checked by the same verification (the residual is reported).
//
// Degenerate cases: when every choice of three equations leaves a polynomial that vanishes
// identically (the pose is not isolated: an architecture singularity, e.g. a 3-RRR whose base
// and platform triangles are similar with equal legs, or a limb of two parallel P joints),
// `degenerate` is set and only the isolated candidates found at phi = pi and at the orientation
// fixed by a P P limb are returned. A limb without actuated joints does not restrict the pose;
// it is reported on its home branch when it reaches the pose on it (its other branch is then
// another assembly of that limb alone).
//
// Two-DOF robots (motion: translation, task map E): no limb fixes phi (every limb's last R
// joint is at the tool point), and the pose keeps theta at home: phi = 0 is added as an
// orientation equation, so C solves the rest at phi = 0. For the five-bar and the biglide that
// is the intersection of two circles (each centred at a locked elbow or slider pivot, radius
// the forearm): both assembly modes, the tool on either side of the line between the centres.
// Modes of equal theta are listed by x, then y.
//
// Tracker (trackPose): Newton from the previous pose of the working mode on the same locked-limb
// equations (Gauss-Newton when n > 3), which hold exactly where u(p) = u on some branches, then
// inverse displacement on the home branches at the converged pose: the pose is accepted only
// if it gives u back there, so that the tracker never jumps to another mode's branches. (The
// equations cost a few flops per limb; Newton on u(p) through inverse displacement and the
// actuation map A would cost a position and a velocity stage per step.) Newton converges
// quadratically, so a step below 1e-8 (phi [rad], C over L) leaves round-off: the iterate is
// verified without evaluating the equations again, and Newton resumes if the verification
// rejects it. PoseTracker starts Newton from the poses extrapolated along the motion: one
// Newton step per sample at 10 kHz on exact u, two on a table's encoders (1 um noise: the first
// step is about 1e-5 of the length scale, the second confirms round-off; shake_control_test).
#pragma once

#include <array>

#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Capacity of AssemblyModes: the degree-10 elimination polynomial has at most 10 real roots,
/// and t = oo is one more candidate.
inline constexpr int kMaxAssemblyModes = 12;

/// One real solution of the direct kinematics.
struct AssemblyMode {
    Pose p = Pose::Zero();  ///< [theta in (-pi, pi], x, y]
    LimbBranches branch{};  ///< each limb's inverse-kinematics branch (as LimbModel::branch)
    bool working = false;   ///< every limb on its home branch (the mode of inverseDisplacement)
    /// max over the actuators of |u_a(p) - u_a| by inverseDisplacement on `branch`, R joints
    /// modulo 2 pi [m or rad].
    double u_error = 0.0;
    /// Largest scaled condition number of the limb Jacobians J_j and of the actuation map at p
    /// (large next to a singularity, where a mode is sensitive to u).
    double condition = 0.0;
};

/// Every assembly mode (fixed capacity, sorted by theta).
struct AssemblyModes {
    std::array<AssemblyMode, kMaxAssemblyModes> mode{};
    int count = 0;
    /// The elimination polynomial vanished identically for every choice of equations (see the
    /// header): the modes listed may be incomplete, or the pose not isolated.
    bool degenerate = false;
    /// More modes were found than the capacity holds (not expected; the extra ones are dropped).
    bool truncated = false;

    [[nodiscard]] const AssemblyMode* begin() const { return mode.data(); }
    [[nodiscard]] const AssemblyMode* end() const { return mode.data() + count; }
};

struct DirectKinematicsOptions {
    /// Largest accepted |u_a(p) - u_a| of a mode [m or rad] (its round-off is ~1e-15 times
    /// the conditioning; redundant robots: how far from consistent u may be).
    double tolerance = 1e-9;
};

/// Every platform pose with actuator values u (model.actuators of them, file order), each
/// verified by inverse displacement on its limbs' branches. `data` is workspace (on return it
/// holds the position stage of the last candidate checked). Allocation-free. Fails only with
/// not_finite (an input u not finite); no assembly is ok with modes.count = 0.
Status directKinematics(const Model& model, Data& data, const ActuatorVector& u, AssemblyModes& modes,
                        const DirectKinematicsOptions& options = {});

/// A state to start from, given by actuator values (and rates).
struct ActuatorStart {
    Pose p = Pose::Zero();     ///< the pose of the chosen working assembly mode
    Twist dp = Twist::Zero();  ///< its rates dp/dt (zero at rest)
    int mode = 0;              ///< which working mode (1-based, sorted by theta as directKinematics lists them)
    int working = 0;           ///< how many modes have every limb on its home branch
    int modes = 0;             ///< how many modes on any branches
    bool nearest_home = true;  ///< the mode was chosen as the one nearest home
};

/// The state whose actuator values are u and rates du (du of size 0: at rest): among the
/// assembly modes with every limb on its home branch (the branches inverse displacement, the
/// dynamics and the simulation follow), the `choice`-th as directKinematics lists them
/// (1-based), or with choice 0 the one nearest home (max(|theta - theta_home|,
/// |C - C_home| / length_scale)); dp/dt from du by velocityFromActuatorRatesLeastSquares.
/// Leaves the position and velocity stages at that state in `data`. Fails with
/// assembly_mode_missing (none, or fewer than `choice`), inconsistent_rates, not_finite, or
/// as the stages fail there.
Status stateFromActuators(const Model& model, Data& data, const ActuatorVector& u, const ActuatorVector& du, int choice,
                          ActuatorStart& start);

struct TrackerOptions {
    int max_iterations = 20;
    /// Accepted when max_a |u_a(p) - u_a| / joint_scale_a <= tolerance (1 rad or
    /// model.length_scale m per unit), u(p) on the home branches.
    double tolerance = 1e-13;
    /// A Newton step larger than this (theta [rad], or C over model.length_scale, infinity
    /// norm) means the previous pose was too far away: the mode is considered lost.
    double max_step = 0.05;
    /// Redundant robots: the least-squares pose is accepted when the remaining scaled residual
    /// is at most this (inconsistent u beyond it is reported as assembly_mode_lost).
    double max_residual = 1e-6;
};

/// What one call of trackPose did.
struct TrackerReport {
    int iterations = 0;     ///< Newton steps taken
    double residual = 0.0;  ///< final max_a |u_a(p) - u_a| / joint_scale_a
};

/// Tracker of the working mode. p holds the previous pose on entry and the pose with actuator
/// values u on success; `data` then holds the position stage at p on the home branches, as
/// inverseDisplacement leaves it except that passive R joints have cos q and sin q but not q.
/// Allocation-free, at most options.max_iterations Newton steps. Fails with not_finite; with
/// unreachable or singular_limb when the pose reached is out of reach of a limb on its home
/// branch or a limb is singular there; with singular_actuation at a singular A; with
/// workspace_edge when it does not converge next to a limb singularity (a limb's condition
/// number within a factor 10 of model.max_condition: u beyond the workspace there); else with
/// assembly_mode_lost (value: the scaled residual; e.g. Newton converged onto another branch).
/// p is then left at the previous pose, or at the pose reached when that was verified and
/// rejected.
Status trackPose(const Model& model, Data& data, const ActuatorVector& u, Pose& p, const TrackerOptions& options = {},
                 TrackerReport* report = nullptr);

/// The tracker along a motion sampled at a constant rate: it remembers the last four poses it
/// found and starts Newton from the cubic through them one sample ahead,
/// p_k ~ 4 p_{k-1} - 6 p_{k-2} + 4 p_{k-3} - p_{k-4} (error about h^4 |d4p/dt4|, 2e-9 rad at
/// 10 kHz on the benchmark's 30 Hz harmonic, against h |dp/dt| from the previous pose alone),
/// so that one Newton step reaches round-off. Uneven samples, noisy u or a restart (fewer poses
/// known: a lower degree) only cost more steps. When Newton from the prediction fails, it
/// retries from the previous pose (as trackPose) before reporting. Allocation-free.
class PoseTracker {
public:
    explicit PoseTracker(const Pose& start = Pose::Zero()) { reset(start); }
    /// Forgets the motion: the next step starts from p (the previous pose of trackPose).
    void reset(const Pose& p);
    /// The pose with actuator values u, as trackPose does from the predicted pose; on success
    /// pose() is that pose, else it stays the last pose found and the motion is forgotten.
    Status step(const Model& model, Data& data, const ActuatorVector& u, const TrackerOptions& options = {},
                TrackerReport* report = nullptr);
    /// The last pose found (or given to reset).
    [[nodiscard]] const Pose& pose() const { return last_[0]; }
    /// Where the next step's Newton starts.
    [[nodiscard]] Pose prediction() const;

private:
    std::array<Pose, 4> last_{};  ///< the last poses found, newest first
    int known_ = 1;               ///< how many of them belong to the current motion
};

}  // namespace nocdyn
