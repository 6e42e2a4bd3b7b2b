// Operating envelope of a spatial robot (spatial.hpp; a hexapod or a Delta): for a sinusoid
// along one pose coordinate about home,
//   p(t) = home + A sin(2 pi f t) e_axis      (axis x, y, z, and roll, pitch, yaw for motion
//                                             full; the other coordinates stay at home)
// the largest amplitude A at frequency f for which, over one period sampled finely, every pose
// is reachable and regular (inverseKinematics) and every freedom stays within its limits
// (checkLimits): each R or P joint's range and velocity, each actuator's effort by the inverse
// dynamics (gravity, damping and friction as the robot file sets them).
//
// The limit-use ratio of a sample is the largest over the freedoms of
//   q / upper or q / lower (the side q is on; q = 0 at home), |q'| / velocity, |tau| / effort,
// and of the period its largest over the samples; A is the largest amplitude whose ratio is at
// most 1 (a pose the model cannot take counts as beyond it, `workspace`). The legs' lengths are
// not linear in A, so A is bracketed (doubling or halving from the previous frequency's answer)
// and bisected, with a bounded number of passes. Range binds at low f (flat in f), velocity in
// the middle (A ~ 1 / f), effort at high f (A ~ 1 / f^2 once the inertia forces dominate).
#pragma once

#include <vector>

#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/spatial.hpp"

namespace nocdyn::spatial {

/// The largest amplitude at one frequency along one pose coordinate.
struct EnvelopePoint {
    int axis = 0;                               ///< index in the pose: x, y, z, roll, pitch, yaw (Model::coordinates())
    double frequency = 0.0;                     ///< [Hz]
    double amplitude = 0.0;                     ///< [m] for x, y, z; [rad] for the angles
    EnvelopeLimit limit = EnvelopeLimit::none;  ///< range, velocity, effort, workspace or none
    int limb = -1;                              ///< 0-based limb that reaches the limit (-1: none)
    int joint = -1;                             ///< 0-based listed joint of that limb (-1: none)
    int actuator = -1;                          ///< 0-based actuator at that joint (-1: passive or none)
    /// Largest amplitude within the ranges and the workspace alone (the period at rest).
    double kinematic_amplitude = 0.0;
    double peak_ratio = 0.0;         ///< the limit-use ratio of the period at `amplitude` (<= 1)
    double peak_effort_ratio = 0.0;  ///< max |tau_a| / effort_a over actuators and period at `amplitude`
    double peak_u = 0.0;             ///< max |u_a| [m or rad] at `amplitude`
    double peak_tau = 0.0;           ///< max |tau_a| [N or N m] at `amplitude`
};

/// The limit-use ratio of one period of p(t) = home + A sin(2 pi f t) e_axis (see the file
/// header), with the limit, limb, joint and actuator of its largest term and the peaks. A pose
/// the model cannot take gives ratio infinity and limit `workspace` (its limb when known); A = 0
/// with f = 0 is the home posture at rest. `dynamic` false: the period at rest (dp = ddp = 0),
/// ranges and workspace only. Allocation-free after Data is built.
[[nodiscard]] EnvelopePoint limitUse(const Model& model, Data& data, int axis, double frequency, double amplitude,
                                     int samples_per_period, bool dynamic = true);

/// Largest amplitude along `axis` at `frequency`; `hint` (> 0) is where the bracketing starts
/// (the previous frequency's answer). Throws nocdyn::Error for a frequency or option out of
/// range, an axis the robot has not, or a home posture not within the limits.
[[nodiscard]] EnvelopePoint maximumAmplitude(const Model& model, int axis, double frequency,
                                             const nocdyn::EnvelopeOptions& options = {}, double hint = 0.0);

/// Every axis (x, y, z, and roll, pitch, yaw for motion full), each log-spaced frequency; the
/// options' progress after each point and poll before each period.
[[nodiscard]] std::vector<EnvelopePoint> operatingEnvelope(const Model& model,
                                                           const nocdyn::EnvelopeOptions& options = {});

}  // namespace nocdyn::spatial
