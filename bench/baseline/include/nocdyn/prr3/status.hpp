// Outcome of a per-sample computation of the 3-PRR kernel: the failures its stages detect,
// naming the limb (the library's general model reports its own, nocdyn::Status). Same layout
// as nocdyn::Status, so that the baseline's timings are unchanged by its own type.
#pragma once

#include <string>

namespace nocdyn::io {
struct RobotParameters;
}

namespace nocdyn::prr3 {

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
};

struct Status {
    StatusCode code = StatusCode::ok;
    int limb = -1;       ///< 0-based limb (paper's j - 1), or -1 when not limb-specific
    double value = 0.0;  ///< the offending quantity, see StatusCode
    int joint = -1;      ///< unused (the layout of nocdyn::Status)

    [[nodiscard]] bool ok() const { return code == StatusCode::ok; }
    explicit operator bool() const { return ok(); }
};

/// One-line human-readable explanation, naming the limb as the paper does (1..3).
/// Not for the real-time path (it allocates).
[[nodiscard]] std::string describe(const Status& status, const io::RobotParameters& robot);

}  // namespace nocdyn::prr3
