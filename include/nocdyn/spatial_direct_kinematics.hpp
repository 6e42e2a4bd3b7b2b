// Direct kinematics of a spatial parallel robot (nocdyn/spatial.hpp): actuator values u -> the
// platform poses p with u(p) = u.
//
// Tracker. Newton on u(p) - u = 0 from the previous pose: du = A_task [v; w] (inverse
// kinematics' actuation map at the platform point) and w = E(p) [roll'; pitch'; yaw'] with
// E = [Rz Ry e_x, Rz e_y, e_z] (R = Rz(yaw) Ry(pitch) Rx(roll)), so the Jacobian of u over p is
// A_task diag(I_3, E) (A_task alone for motion translation); least squares when n > d. Each
// step's inverse kinematics starts from the previous step's limbs, so the limbs stay on their
// branches. No allocation.
//
// Three spheres (a translation robot of three R-U-U limbs, the Delta): with motor angle u_j
// limb j's elbow (the first U's point) is at E_j(u_j) = B_j + Rot(a_j, u_j) (E_j0 - B_j) and
// the platform's U point at P_j0 + p - p_0 (the platform only translates), and the forearm
// between them has the fixed length L_j = |P_j0 - E_j0|: p lies on the sphere of radius L_j
// about c_j = E_j(u_j) - (P_j0 - p_0). Three spheres meet in two points mirrored about the
// plane of their centres (the two assembly modes), one when tangent, none when u is out of
// reach.
//
// Many starts (any robot): from deterministic seed poses (home, home mirrored about the base
// joints' mean height, then poses spread about both), continuation in u from u(seed) to u by
// the tracker (at most 8 Newton steps each), halving the step in u when it fails; the limbs
// start on their home branches at even seeds and on the branches whose actuated variables are
// nearest u at odd ones. The poses reached are verified and duplicates dropped. It lists the
// modes it finds, not necessarily every real one.
//
// Verification (every listed mode): each limb is closed at p with its actuated variable held
// at u_a (Gauss-Newton from a few passive starts), then the tracker polishes p from there and
// inverse kinematics gives u back: u_error = max_a |u_a(p) - u_a|. A mode is on the home
// branches when inverse kinematics from home (as pose and the dynamics use) gives back u; the
// working mode is the one on the home branches nearest home.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "nocdyn/spatial.hpp"

namespace nocdyn::spatial {

/// Tracker: Newton on u(p) - u = 0 from p (the previous pose), at most 20 iterations, to
/// max_a |u_a(p) - u_a| <= 1e-13 (1 + max |u|). On success p is the pose and data holds its
/// inverse kinematics; else p is left as it was and the status says why: assembly_mode_lost
/// (no convergence, or the residual grew tenfold over the first; value: the residual),
/// not_finite (u or p of the wrong size or not finite), or inverse kinematics' own status (out
/// of reach, singular).
[[nodiscard]] Status directKinematics(const Model& model, Data& data, const ActuatorVector& u, TaskVector& p);

/// One line for a status of directKinematics (describe() for inverse kinematics' own).
[[nodiscard]] std::string describeDirect(const Status& status, const Model& model);

/// A translation robot of three R-U-U limbs, the R actuated: per limb the motor's axis a_j
/// through B_j, the elbow E_j0 and the platform's point P_j0 at home, and the forearm length.
struct ThreeSpheres {
    std::array<Eigen::Vector3d, 3> axis, base, elbow, platform;
    std::array<double, 3> forearm{};
    std::array<int, 3> actuator{};  ///< limb j's actuator
};

/// The structure of `model` when it is such a robot; otherwise nullopt and `why` says what
/// differs (naming the limb).
[[nodiscard]] std::optional<ThreeSpheres> threeSpheres(const Model& model, std::string& why);

/// The sphere intersection for motor angles u: 0 (out of reach; `gap` is how far the spheres
/// miss [m^2]), or 2 points (equal when tangent) mirrored about the plane of the centres.
/// Throws nocdyn::Error when the three centres are on one line.
int threeSpheresPoints(const ThreeSpheres& s, const Eigen::Vector3d& home, const ActuatorVector& u,
                       std::array<Eigen::Vector3d, 2>& points, double& gap);

/// One assembly mode.
struct AssemblyMode {
    TaskVector p;                ///< the pose; angles roll, yaw in (-pi, pi], pitch in [-pi/2, pi/2]
    double u_error = 0.0;        ///< max_a |u_a(p) - u_a| [m or rad]
    double condition = 0.0;      ///< the largest of the limbs' and the actuation map's condition numbers
    bool home_branches = false;  ///< inverse kinematics from home gives back u
    bool working = false;        ///< on the home branches and the nearest such mode to home
};

enum class DirectMethod { three_spheres, many_starts };

struct AssemblyModes {
    DirectMethod method = DirectMethod::many_starts;
    bool complete = false;            ///< every real mode is listed (three spheres)
    int starts = 0;                   ///< seeds tried (many starts)
    double gap = 0.0;                 ///< three spheres out of reach: how far they miss [m^2]
    std::vector<AssemblyMode> modes;  ///< sorted by distance from home
};

/// Bounds of the many-start search.
struct ManyStarts {
    int starts = 48;
    unsigned seed = 20260101u;
};

/// Every mode found for u: by three spheres when the robot is of that form, else by many
/// starts. Throws nocdyn::Error for u of the wrong size or not finite.
[[nodiscard]] AssemblyModes assemblyModes(const Model& model, const ActuatorVector& u, const ManyStarts& bounds = {});

/// Verifies a candidate pose (see above): the mode, or nullopt when the limbs cannot close at
/// p with u or u is not given back to 1e-9.
[[nodiscard]] std::optional<AssemblyMode> verifyMode(const Model& model, const ActuatorVector& u, const TaskVector& p);

/// The pose's angles brought to roll, yaw in (-pi, pi], pitch in [-pi/2, pi/2] (the same R).
[[nodiscard]] TaskVector canonicalPose(const TaskVector& p);

}  // namespace nocdyn::spatial
