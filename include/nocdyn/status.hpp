// Outcome of a per-sample algorithm. The real-time path never throws, logs or allocates:
// it returns a Status, and the layer above (CLI, file tools) turns it into a message.
#pragma once

#include <string>

namespace nocdyn {

enum class StatusCode {
    ok,
    /// A direct-kinematics tracker lost its assembly mode: value = its scaled residual.
    assembly_mode_lost,
    /// Actuator values beyond the edge of the workspace: limb `limb` is next to a singular
    /// posture, where its actuator turns back; value = the scaled condition number of its J.
    workspace_edge,
    /// The integrator's step fell below its minimum (tolerances too tight for double
    /// precision, or a motion too violent): value = the step it needed [s].
    integration_step_too_small,
    /// The integrator took more steps than allowed over one interval: value = the steps.
    integration_too_many_steps,
    /// A limb cannot reach the pose on its home branch. value = how far the
    /// pose is out of the limb's reach [m].
    unreachable,
    /// A limb Jacobian J_j (eq. 4a) is ill-conditioned. value = its scaled
    /// condition number.
    singular_limb,
    /// The map from the platform twist to the actuator rates (eq. 5) is
    /// ill-conditioned (actuation singularity). value = its scaled condition number.
    singular_actuation,
    /// Joint `joint` of limb `limb` is outside [lower, upper]. value = q.
    joint_limit_exceeded,
    /// The actuator at (limb, joint) needs more than its effort limit. value = tau.
    effort_exceeded,
    /// Joint (limb, joint) moves faster than its velocity limit. value = q'.
    velocity_exceeded,
    /// An input (pose, rate, acceleration) is not a finite number. value = the input.
    not_finite,
    /// No assembly mode with every limb on its home branch has the actuator values, or fewer
    /// than the one asked for. value = how many there are.
    assembly_mode_missing,
    /// Actuator rates that no platform motion has at the pose (redundant actuation).
    /// value = max_a |A S(c) dp/dt - du|_a of the least-squares dp/dt.
    inconsistent_rates,
    /// Limb `limb` gives the platform no finite stiffness in some direction (an actuated joint
    /// without a stiffness is locked, and nothing else in the limb yields): value = 0.
    rigid_limb,
    /// The mass matrix M_p of the equations of motion (forward_dynamics.hpp) is not positive
    /// definite: some body has no mass or no inertia where the motion needs one. value = the
    /// smallest diagonal entry of M_p.
    singular_mass_matrix,
    /// The platform's stiffness spans more decades than double precision resolves: the softest
    /// direction it is held in is lost in the rounding of the stiffest (stiffness.hpp).
    /// value = the contrast, the ratio of K's largest to its smallest held eigenvalue.
    stiffness_contrast,
};

struct Status {
    StatusCode code = StatusCode::ok;
    int limb = -1;       ///< 0-based limb (paper's j - 1), or -1 when not limb-specific
    double value = 0.0;  ///< the offending quantity, see StatusCode
    int joint = -1;      ///< 0-based joint in the limb (chain order), or -1

    [[nodiscard]] bool ok() const { return code == StatusCode::ok; }
    explicit operator bool() const { return ok(); }
};

class Model;

/// One-line human-readable explanation: names the limb (by its name and 1-based number), the
/// joint and the limit. Not for the real-time path (it allocates).
[[nodiscard]] std::string describe(const Status& status, const Model& model);

}  // namespace nocdyn
