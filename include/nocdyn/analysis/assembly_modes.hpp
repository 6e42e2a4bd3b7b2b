// Every real assembly mode of a Gough-Stewart platform (a 6-UPS robot: each limb a U at the
// base point a_i, the actuated P, an S at the platform point b_i): the poses p at which the six
// legs have the lengths that the actuator values u give, by polynomial homotopy continuation
// (PHCpack's blackbox solver `phc -b`, Debian package phcpack, run as a separate program).
//
// The equations, in Study's parameters (e, g) of the platform's displacement (e a quaternion of
// the rotation, R x = e x e* / |e|^2; g = t e / 2 with t the platform origin's position, so
// that Study's quadric e . g = 0 holds):
//   leg i:     |e b_i - a_i e + 2 g|^2 - L_i^2 |e|^2 = 0   (|p + R b_i - a_i|^2 = L_i^2 times |e|^2)
//   Study:     e . g = 0
//   scale:     c . e = 1   (a fixed generic c: (e, g) is projective)
// with a_i, b_i as pure quaternions and L_i = |r_i + u_i d_i| the distance from the U point to
// the S point (r_i that vector at home, d_i the P joint's direction). Seven quadrics and a linear
// equation in eight unknowns: 2^7 = 128 paths (the total degree and the mixed volume), 40 of
// which end at the finite solutions of a general platform, the others diverging to the
// exceptional set e = 0. (Subtracting leg 1's equation from the others lowers the mixed volume
// to 84, but phc then loses finite solutions: it found 13 to 20 of 40 on random platforms.)
// Each real solution is polished by Newton on the pose, checked by spatial::inverseKinematics
// (the actuator values come back to u) and kept once.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/spatial.hpp"

namespace nocdyn::spatial {

struct HomotopyOptions {
    /// The phc executable: empty to look for `phc` in the folders of PATH.
    std::string executable;
    /// phc is killed after this many seconds (an Error says so).
    double timeout = 120.0;
    /// A solution of phc is taken as real when |imaginary part| <= this times (1 + |real part|)
    /// for every unknown.
    double imaginary_tolerance = 1e-6;
    /// A mode is kept when the inverse kinematics gives back u to this [m or rad].
    double u_tolerance = 1e-9;
    /// The seed of phc's random numbers (its option -0<seed>), 0 for a seed from the clock.
    unsigned seed = 0;
    /// phc -b -t1: the polyhedral homotopy (the mixed volume, 128 paths) on one thread, about a
    /// third faster here than phc -b's total-degree homotopy (also 128 paths), which false runs.
    bool polyhedral = true;
};

struct HomotopyMode {
    TaskVector pose;  ///< [x, y, z, roll, pitch, yaw]
    /// max_k |u_k(pose) - u_k|, u(pose) by spatial::inverseKinematics
    double u_error = 0.0;
    /// The condition number of the actuation map there (large near a parallel singularity).
    double actuation_condition = 1.0;
};

struct HomotopyModes {
    std::vector<HomotopyMode> modes;  ///< every real assembly mode once, by increasing distance from home
    int paths = 0;                    ///< the paths phc tracked
    int solutions = 0;                ///< the finite complex solutions phc found (40 for a general platform)
    int real_solutions = 0;           ///< of them real (before the polish and the check)
    /// Real solutions of the leg lengths that the limbs cannot take with these u: a U joint that
    /// cannot point its leg there, or the inverse kinematics not giving back u.
    int rejected = 0;
    double seconds = 0.0;      ///< phc's wall time
    double cpu_seconds = 0.0;  ///< phc's processor time (user and system)
    std::string executable;    ///< the phc that ran
};

/// The phc executable: `executable` when not empty (it must be an executable file), else the
/// first `phc` in PATH; empty when there is none.
[[nodiscard]] std::string findPhc(const std::string& executable = {});

/// True when the model is a 6-UPS robot (motion full; six limbs, each a U, the actuated P and
/// an S, and no other actuator); otherwise false and `reason` names the limb and what differs.
[[nodiscard]] bool isUpsHexapod(const Model& model, std::string* reason = nullptr);

/// Every real assembly mode of the 6-UPS robot `model` at the actuator values u (one per limb,
/// in actuator order). Throws nocdyn::Error for a robot of another kind, a u of the wrong size or
/// not finite, a leg of zero length, a missing phc (naming the package phcpack), a phc that fails,
/// times out or writes what cannot be read.
[[nodiscard]] HomotopyModes homotopyModes(const Model& model, const ActuatorVector& u,
                                          const HomotopyOptions& options = {});

}  // namespace nocdyn::spatial
