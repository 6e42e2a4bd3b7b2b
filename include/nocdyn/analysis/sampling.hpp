// Sampling a pose trajectory through the inverse dynamics of any robot (model.hpp): the layer
// above the per-sample path. Turns a failing sample's Status into a nocdyn::Error that names
// the sample time and the limb.
//
// Limits are checked on the motion, not only at the output samples: between two output
// samples the joint ranges and velocities, the actuator efforts and the workspace are also
// checked at points spaced at most 1 / (kLimitChecksPerPeriod f_max) apart, f_max being the
// trajectory's highest harmonic (so a harmonic's peak is seen within 1 - cos(pi / 40) = 0.3 %
// of its amplitude), whatever the output rate. An output rate at or below 2 f_max (which would
// alias) is refused, and no non-finite number is ever produced: a pose out of reach, a
// singular posture or a non-finite value stays an error under either LimitPolicy.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "nocdyn/model.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn {

/// Output sampling instants t_k = k / rate, k = 0..count-1, without storing them.
struct SampleGrid {
    double rate = 0.0;      ///< [Hz]
    std::size_t count = 0;  ///< number of samples
    [[nodiscard]] double time(std::size_t k) const { return static_cast<double>(k) / rate; }
};

/// The grid of n = round(duration * rate) samples. Throws nocdyn::Error for a non-positive or
/// non-finite duration or rate, or when fewer than one or more than 10^8 samples would result.
[[nodiscard]] SampleGrid sampleGrid(double duration, double rate);

/// Sampling instants t_k = k / rate, k = 0..n-1, n = round(duration * rate) (as sampleGrid).
[[nodiscard]] std::vector<double> sampleTimes(double duration, double rate);

/// Points per period of the highest harmonic at which limits are checked between samples.
inline constexpr int kLimitChecksPerPeriod = 40;
/// Most harmonic terms a sampled trajectory may take to evaluate: points (samples or limit
/// checks, whichever are more) times harmonics; about 3 minutes of computing.
inline constexpr double kMaxTrajectoryWork = 2e10;

/// Throws nocdyn::Error, with the estimate of the work and its time, when sampling `trajectory`
/// over `duration` at `samples` points (and the limit checks between them) would evaluate more
/// than kMaxTrajectoryWork harmonic terms.
void requireBoundedWork(const PoseTrajectory& trajectory, double duration, std::size_t samples);

/// Highest harmonic frequency of any axis [Hz]; 0 for a constant pose.
[[nodiscard]] double highestFrequency(const PoseTrajectory& trajectory);

/// Throws nocdyn::Error naming the rate needed unless `rate` > 2 f_max (Nyquist).
void requireRateAboveNyquist(const PoseTrajectory& trajectory, double rate);

/// Throws nocdyn::Error "t = ... s: <reason>" at the first point of [0, duration] where the
/// pose is out of reach, singular, or gives a non-finite value, checked every
/// 1 / (kLimitChecksPerPeriod f_max) s and at both ends; joint and effort limits are not checked.
void requireReachable(const Model& model, const PoseTrajectory& trajectory, double duration);

/// What to do when a sample exceeds a joint range, joint velocity or actuator effort limit.
enum class LimitPolicy { error, record };

/// One output sample of the inverse dynamics (n = model.actuators).
struct InverseDynamicsSample {
    double t = 0.0;                  ///< [s]
    Pose p = Pose::Zero();           ///< pose [theta, x, y] [rad, m, m]
    Twist dp = Twist::Zero();        ///< its first time derivative
    Twist ddp = Twist::Zero();       ///< its second time derivative
    ActuatorVector u, du, ddu, tau;  ///< actuator variables, rates, accelerations, forces
    double kinetic = 0.0;            ///< kinetic energy [J]
};

/// Peaks and violations over a whole run, between-sample checks included.
struct LimitSummary {
    std::vector<double> peak_u;    ///< max |u_a| per actuator [m or rad]
    std::vector<double> peak_tau;  ///< max |tau_a| per actuator [N or N m]
    /// The first (at most 10) limit violations met when the policy is `record`.
    std::vector<std::string> limit_violations;
    std::size_t checks_between_samples = 0;  ///< points checked between output samples
};

/// Runs the per-sample path at each instant of `grid` and hands each sample to `sink` as it
/// is computed (memory does not grow with the sample count). Refuses a rate at or below
/// 2 f_max before computing anything. Throws nocdyn::Error "t = ... s: <reason>" for a pose
/// out of reach, a singular posture or a non-finite value at a sample or between samples,
/// and (policy `error`) for a joint range, joint velocity or effort beyond its limit; with
/// `record`, violations are listed instead. Allocates nothing per sample (`sink` aside).
LimitSummary streamInverseDynamics(const Model& model, const PoseTrajectory& trajectory, const SampleGrid& grid,
                                   LimitPolicy policy, const std::function<void(const InverseDynamicsSample&)>& sink);

/// As streamInverseDynamics, with every joint's reaction (reactions.hpp) at each sample, for
/// the forces the inverse dynamics applies. Allocates nothing per sample (`sink` aside).
LimitSummary streamInverseDynamicsWithReactions(
    const Model& model, const PoseTrajectory& trajectory, const SampleGrid& grid, LimitPolicy policy,
    const std::function<void(const InverseDynamicsSample&, const Reactions&)>& sink);

/// Inverse dynamics along a trajectory, one entry per sample.
struct InverseDynamicsSeries {
    std::vector<InverseDynamicsSample> samples;
    LimitSummary summary;
};

/// As streamInverseDynamics at increasing `times`, stored. Refuses a sampling interval of
/// 1 / (2 f_max) or more.
[[nodiscard]] InverseDynamicsSeries sampleInverseDynamics(const Model& model, const PoseTrajectory& trajectory,
                                                          const std::vector<double>& times,
                                                          LimitPolicy policy = LimitPolicy::error);

}  // namespace nocdyn
