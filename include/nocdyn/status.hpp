// Outcome of a per-sample algorithm. The real-time path never throws, logs or allocates:
// it returns a Status, and the layer above (CLI, file tools) turns it into a message.
#pragma once

#include <string>

namespace nocdyn {

enum class StatusCode {
    ok,
    /// A limb cannot reach the pose: the distance d_j^M from M_j to the rail line L_j is
    /// not in (0, l). value = d_j^M [m].
    outside_workspace,
    /// H or D (eqs. 5-7) is too ill-conditioned: value = its condition number.
    singular_forward_jacobian,
    singular_inverse_jacobian,
    /// The pose needs more than half the actuator stroke: value = u_j [m].
    stroke_exceeded,
    /// The actuator force exceeds its peak: value = tau_j [N].
    force_exceeded,
    /// A direct-kinematics tracker lost its assembly mode: value = residual [m].
    assembly_mode_lost,
    /// Actuator displacements beyond the edge of the workspace: limb j's link is (nearly)
    /// normal to its rail, or along it, where u_j turns back; value = d_j^M [m].
    workspace_edge,
    /// The integrator's step fell below its minimum (tolerances too tight for double
    /// precision, or a motion too violent): value = the step it needed [s].
    integration_step_too_small,
    /// The integrator took more steps than allowed over one interval: value = the steps.
    integration_too_many_steps,
    /// General model: a limb cannot reach the pose on its home branch. value = how far the
    /// pose is out of the limb's reach [m].
    unreachable,
    /// General model: a limb Jacobian J_j (eq. 4a) is ill-conditioned. value = its scaled
    /// condition number.
    singular_limb,
    /// General model: the map from the platform twist to the actuator rates (eq. 5) is
    /// ill-conditioned (actuation singularity). value = its scaled condition number.
    singular_actuation,
    /// General model: joint `joint` of limb `limb` is outside [lower, upper]. value = q.
    joint_limit_exceeded,
    /// General model: actuator at (limb, joint) needs more than its effort limit. value = tau.
    effort_exceeded,
    /// General model: joint (limb, joint) moves faster than its velocity limit. value = q'.
    velocity_exceeded,
    /// An input (pose, rate, acceleration) is not a finite number. value = the input.
    not_finite,
};

struct Status {
    StatusCode code = StatusCode::ok;
    int limb = -1;       ///< 0-based limb (paper's j - 1), or -1 when not limb-specific
    double value = 0.0;  ///< the offending quantity, see StatusCode
    int joint = -1;      ///< 0-based joint in the limb (chain order), or -1

    [[nodiscard]] bool ok() const { return code == StatusCode::ok; }
    explicit operator bool() const { return ok(); }
};

struct RobotParameters;
class Model;

/// One-line human-readable explanation, naming the limb as the paper does (1..3).
/// Not for the real-time path (it allocates).
[[nodiscard]] std::string describe(const Status& status, const RobotParameters& robot);

/// The same for the general model: names the limb (by its name and 1-based number), the
/// joint and the limit.
[[nodiscard]] std::string describe(const Status& status, const Model& model);

}  // namespace nocdyn
