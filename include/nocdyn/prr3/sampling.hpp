// Sampling a pose trajectory through the 3-PRR inverse dynamics: the batch layer above the
// per-sample path. Turns a failing sample's Status into a nocdyn::Error that names the
// sample time and the limb.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "nocdyn/io/csv.hpp"
#include "nocdyn/prr3/model.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::prr3 {

/// Sampling instants t_k = k / rate, k = 0..n-1, n = round(duration * rate).
/// Throws nocdyn::Error for a non-positive or non-finite duration or rate, or when fewer
/// than one or more than 10^8 samples would result.
[[nodiscard]] std::vector<double> sampleTimes(double duration, double rate);

/// What to do when a sample exceeds the actuator stroke or peak force.
enum class LimitPolicy { error, record };

/// Inverse dynamics along a trajectory, one row per sample.
struct InverseDynamicsSeries {
    std::vector<double> t;
    std::vector<Pose> p, dp, ddp;
    std::vector<JointVector> u, du, ddu, tau;
    std::vector<double> kinetic;  ///< kinetic energy [J]
    std::array<double, kLimbs> peak_stroke{};  ///< max |u_j| [m]
    std::array<double, kLimbs> peak_force{};   ///< max |tau_j| [N]
    /// First limit violation met (when the policy is `record`), else empty.
    std::vector<std::string> limit_violations;
};

/// Runs the per-sample path at each time. Throws nocdyn::Error "t = ... s: <reason>" for a
/// pose outside the workspace or a singular posture, and (policy `error`) for a sample
/// beyond the stroke or the peak force; with `record`, violations are listed instead.
[[nodiscard]] InverseDynamicsSeries sampleInverseDynamics(const Model& model, const PoseTrajectory& trajectory,
                                                          const std::vector<double>& times,
                                                          LimitPolicy policy = LimitPolicy::error);

/// CSV table: t,x,y,theta,u1..u3,du1..du3,ddu1..ddu3,tau1..tau3,kinetic (SI).
[[nodiscard]] io::Table toTable(const InverseDynamicsSeries& series);

}  // namespace nocdyn::prr3
