// Sampling a pose trajectory through the 3-PRR inverse dynamics: the batch layer above the
// per-sample path. Turns a failing sample's Status into a nocdyn::Error that names the
// sample time and the limb.
//
// Limits are checked on the motion, not only at the output samples: between two output
// samples the stroke, the peak force and the workspace are also checked at points spaced at
// most 1 / (kLimitChecksPerPeriod f_max) apart, f_max being the trajectory's highest harmonic
// (so a harmonic's peak is seen within 1 - cos(pi / 40) = 0.3 % of its amplitude), whatever
// the output rate. An output rate at or below 2 f_max (which would alias) is refused, and no
// non-finite number is ever produced: a workspace exit, a singular posture or a non-finite
// value stays an error under either LimitPolicy.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "nocdyn/io/csv.hpp"
#include "nocdyn/prr3/model.hpp"
#include "nocdyn/sampling.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::prr3 {

// The sampling grid, the Nyquist check and the limit policy are the robot-independent ones.
using nocdyn::highestFrequency;
using nocdyn::kLimitChecksPerPeriod;
using nocdyn::LimitPolicy;
using nocdyn::requireRateAboveNyquist;
using nocdyn::SampleGrid;
using nocdyn::sampleGrid;
using nocdyn::sampleTimes;

/// Throws nocdyn::Error "t = ... s: <reason>" at the first point of [0, duration] where the
/// pose is outside the workspace, singular, or gives a non-finite value, checked every
/// 1 / (kLimitChecksPerPeriod f_max) s and at both ends; stroke and force are not checked.
void requireReachable(const Model& model, const PoseTrajectory& trajectory, double duration);

/// One output sample of the inverse dynamics.
struct InverseDynamicsSample {
    double t = 0.0;                         ///< [s]
    Pose p = Pose::Zero();                  ///< pose [theta, x, y] [rad, m, m]
    Twist dp = Twist::Zero();               ///< its first time derivative
    Twist ddp = Twist::Zero();              ///< its second time derivative
    JointVector u = JointVector::Zero();    ///< actuator displacements [m]
    JointVector du = JointVector::Zero();   ///< rates [m/s]
    JointVector ddu = JointVector::Zero();  ///< accelerations [m/s^2]
    JointVector tau = JointVector::Zero();  ///< forces [N]
    double kinetic = 0.0;                   ///< kinetic energy [J]
};

/// Peaks and violations over a whole run, between-sample checks included.
struct LimitSummary {
    std::array<double, kLimbs> peak_stroke{};  ///< max |u_j| [m]
    std::array<double, kLimbs> peak_force{};   ///< max |tau_j| [N]
    /// The first (at most 10) limit violations met when the policy is `record`.
    std::vector<std::string> limit_violations;
    std::size_t checks_between_samples = 0;  ///< points checked between output samples
};

/// Runs the per-sample path at each instant of `grid` and hands each sample to `sink` as it
/// is computed (memory does not grow with the sample count). Refuses a rate at or below
/// 2 f_max before computing anything. Throws nocdyn::Error "t = ... s: <reason>" for a pose
/// outside the workspace, a singular posture or a non-finite value at a sample or between
/// samples, and (policy `error`) for a stroke or force beyond the limits; with `record`,
/// violations are listed instead. Allocates nothing per sample (`sink` aside).
LimitSummary streamInverseDynamics(const Model& model, const PoseTrajectory& trajectory, const SampleGrid& grid,
                                   LimitPolicy policy, const std::function<void(const InverseDynamicsSample&)>& sink);

/// Inverse dynamics along a trajectory, one row per sample.
struct InverseDynamicsSeries {
    std::vector<double> t;
    std::vector<Pose> p, dp, ddp;
    std::vector<JointVector> u, du, ddu, tau;
    std::vector<double> kinetic;               ///< kinetic energy [J]
    std::array<double, kLimbs> peak_stroke{};  ///< max |u_j| [m]
    std::array<double, kLimbs> peak_force{};   ///< max |tau_j| [N]
    /// First limit violation met (when the policy is `record`), else empty.
    std::vector<std::string> limit_violations;
};

/// As streamInverseDynamics at increasing `times`, stored. Refuses a sampling interval of
/// 1 / (2 f_max) or more.
[[nodiscard]] InverseDynamicsSeries sampleInverseDynamics(const Model& model, const PoseTrajectory& trajectory,
                                                          const std::vector<double>& times,
                                                          LimitPolicy policy = LimitPolicy::error);

/// Column names of the inverse-dynamics CSV: t,x,y,theta,u1..u3,du1..du3,ddu1..ddu3,tau1..tau3,kinetic (SI).
[[nodiscard]] std::vector<std::string> inverseDynamicsColumns();

/// One CSV row of a sample, in the order of inverseDynamicsColumns().
[[nodiscard]] std::array<double, 17> toRow(const InverseDynamicsSample& sample);

/// CSV table: t,x,y,theta,u1..u3,du1..du3,ddu1..ddu3,tau1..tau3,kinetic (SI).
[[nodiscard]] io::Table toTable(const InverseDynamicsSeries& series);

}  // namespace nocdyn::prr3
