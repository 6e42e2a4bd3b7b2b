// Recorded ground motion on a robot: baseline correction, similitude scaling within the
// robot's limits, and the scores of shake-table practice.
//
// Baseline correction (highPassZeroPhase): Butterworth high-pass of order kHighPassOrder
// (kHighPassOrder / 2 second-order sections, the bilinear transform of
// H(s) = s^2 / (s^2 + s w_c / Q_k + w_c^2) with w_c prewarped, Q_k = 1 / (2 cos((2k+1) pi / (2N)))),
// run forward then backward: zero phase, magnitude |H|^2 (order 2N, -6 dB at the cutoff).
// Each end is padded with the odd reflection x(-k) = 2 x(0) - x(k) of min(n - 1, 3 fs / f_c)
// samples, the filter starting from rest on the padded signal; the padding is then dropped.
//
// Similitude scaling (fitRecord): time compressed by L, accelerations kept,
//   a_model(t) = A a_record(L t),  v_model = A v / L,  d_model = A d / L^2,
// frequencies times L. The motion is p(t) = home + d_model(t) on each recorded axis,
// d_model the exact double integral of the acceleration spline (trajectory.hpp), so that the
// target acceleration is exactly the second derivative of the target displacement.
//
// Baseline correction of the displacement: the filtered acceleration fixes the displacement
// only up to d0 + v0 t. The zero-phase filter's response reaches into its padding, which is
// dropped, so the filtered record's velocity at t = 0 is not zero: integrated from rest, the
// displacement drifts linearly (on El Centro's 31 s, 3.1 m of drift against a 0.2 m stroke).
// The correction chooses v0 (a linear detrend of the displacement, which leaves the
// acceleration untouched) as the one that minimises the stroke max d - min d over the samples
// (golden-section search; the stroke is convex in v0), keeping v0 = 0, the start from rest,
// when no rate narrows it; d0 then centres the extremes on home. The replay then starts at
// home + d_model(0) moving at v0 A / L (the closed loop starts the plant on the target). L is the least time
// compression (L >= 1, the slowest replay) at which every actuator stays within (1 - margin) of its range, velocity and
// effort limits (inverse dynamics of the nominal model over the fitted motion); feasibility is taken to be monotonic in
// L (displacement and velocity shrink as L grows, inertial forces stay) and L is found by doubling then bisection to
// 0.1 %. When no L up to max_time_scale fits, the amplitude A < 1 is lowered (bisection) at that L.
//
// Scores (scoreShake): RMS of (achieved - target) over RMS of target; (peak |achieved| - peak
// |target|) / peak |target|; the 5 %-damped pseudo-acceleration spectra of both
// (responseSpectrum) and, among the periods of the record's passband where the target's
// S_a is at least 10 % of its peak (the counted periods), the share where they differ by more
// than 10 %. relativeRmsError gives the same RMS ratio for displacements and velocities.
//
// Drive correction (time waveform replication, driveInverse / correctDrive): a pass played with
// the drive d_i (reference accelerations on the record's grid, step dt) achieves a_i; the next
// drive is d_(i+1) = d_i + g H^-1 (a_target - a_i), H(f) the closed loop's frequency response
// from reference to achieved acceleration (closed_loop.hpp: the linearised shake-table loop,
// 3 x 3 per frequency, its block of the driven axes inverted). The error is zero-padded to
// N >= 2 n samples (no wrap-around of the correction), transformed (Eigen's FFT), multiplied by
// H^-1 at each bin f_k = k / (N dt) up to `band` (the record's passband: beyond it the target
// has no content and the error is noise; zero correction there) and transformed back; the mean
// (f = 0) is corrected as is (H(0) = 1: the pose feedback holds the table). With H = I
// (DriveModel::identity) it is the correction d_i + g (a_target - a_i).
#pragma once

#include <array>
#include <complex>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/choice.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn {

struct ShakeLoopLinearization;  // closed_loop.hpp

inline constexpr int kHighPassOrder = 4;

/// Zero-phase Butterworth high-pass (see the header comment); x sampled every dt [s],
/// cutoff [Hz] below the Nyquist frequency. Throws nocdyn::Error for bad dt or cutoff.
[[nodiscard]] std::vector<double> highPassZeroPhase(std::span<const double> x, double dt, double cutoff);

/// A record: accelerations of each axis on one uniform grid (an empty axis is not driven).
struct GroundRecord {
    double dt = 0.0;             ///< [s]
    std::vector<double> ax, ay;  ///< [m/s^2]
    std::vector<double> alpha;   ///< [rad/s^2]
};

/// The fit's settings a user chooses, shared by the fit's options and the replay's
/// (ShakeReplayOptions).
struct FitSettings {
    std::optional<double> time_scale;  ///< L given; none: the least time compression L >= 1 that fits
    double highpass = 0.1;             ///< cutoff [Hz] (record time); 0: no filter
    double margin = 0.1;               ///< share of each limit kept in reserve
};

struct FitOptions : FitSettings {
    double max_time_scale = 100.0;  ///< largest L tried
};

/// The worst use of any limit over a motion: ratio = used / allowed ((1 - margin) limit).
struct LimitUse {
    double ratio = 0.0;
    std::string what;  ///< "actuator 2 (limb2) stroke" etc., empty when ratio is 0
    double t = 0.0;    ///< where [s]
};

/// Folds one sample into `worst`: for each actuator with finite limits, |u - centre| /
/// ((1 - margin) half-range) ("range"), |du| / ((1 - margin) velocity limit) ("velocity", skipped
/// when du is null) and |tau| / ((1 - margin) effort) ("effort"); a larger ratio replaces `worst`,
/// named "actuator N (limb) range|velocity|effort" at time t.
void accumulateLimitUse(const Model& model, double t, const ActuatorVector& u, const ActuatorVector* du,
                        const ActuatorVector& tau, double margin, LimitUse& worst);

/// Inverse dynamics of `trajectory` at `step` intervals over [0, duration]; the worst ratio
/// of |u - centre| / ((1 - margin) half-range), |du| / ((1 - margin) velocity limit) and
/// |tau| / ((1 - margin) effort). A pose out of reach or singular gives ratio +infinity.
[[nodiscard]] LimitUse limitUse(const Model& model, const PoseTrajectory& trajectory, double duration, double step,
                                double margin);

/// A displacement axis from accelerations a at instants t: the exact double integral of their
/// spline with the two constants of integration chosen as the baseline correction (see the
/// header comment): the initial rate v0 that gives the least stroke, then the offset that
/// centres the extremes on `home`.
[[nodiscard]] SampledAxis baselineCorrectedAxis(const std::vector<double>& t, const std::vector<double>& a,
                                                double home);

struct FittedRecord {
    double time_scale = 1.0;            ///< L
    double amplitude_scale = 1.0;       ///< A
    double dt = 0.0;                    ///< record step over L [s]
    std::vector<double> t;              ///< target instants i dt [s]
    std::vector<double> ax, ay, alpha;  ///< target accelerations at t (empty: axis not driven)
    PoseTrajectory trajectory;          ///< home + d_model (sampled)
    LimitUse use;                       ///< of the fitted motion
};

/// Filters, scales and integrates `record` (see the header comment). Throws nocdyn::Error for
/// an empty record, axes of different lengths, or a motion that fits at no amplitude above
/// 1e-4 (naming the limit and by how much it is exceeded).
[[nodiscard]] FittedRecord fitRecord(const Model& model, const GroundRecord& record, const FitOptions& options);

/// Peak |u| of the SDOF oscillator u'' + 2 zeta w u' + w^2 u = -a(t), from rest, a linear
/// between samples: the exact recurrence of Nigam and Jennings (1969). Times w^2 it is the
/// pseudo-acceleration S_a(T) at T = 2 pi / w.
[[nodiscard]] double peakOscillatorDisplacement(std::span<const double> a, double dt, double period, double zeta);

/// S_a(T) = (2 pi / T)^2 peak |u| at each period.
[[nodiscard]] std::vector<double> responseSpectrum(std::span<const double> a, double dt,
                                                   std::span<const double> periods, double zeta = 0.05);

struct ShakeScore {
    double rms_error = 0.0;                               ///< RMS(achieved - target) / RMS(target)
    double peak_error = 0.0;                              ///< (peak |achieved| - peak |target|) / peak |target|
    std::vector<double> periods, target_sa, achieved_sa;  ///< [s], [m/s^2]
    /// of the counted periods (target S_a >= 10 % of its peak), those with |S_a ratio - 1| > 0.1
    double share_outside = 0.0;
    int counted = 0;                  ///< periods counted
    double displacement_error = 0.0;  ///< RMS(d_achieved - d_target) / RMS(d_target - home), when given
    double velocity_error = 0.0;      ///< the same for the velocity
};

/// RMS(achieved - target) / RMS(target - reference); 0 when the target equals the reference.
[[nodiscard]] double relativeRmsError(std::span<const double> target, std::span<const double> achieved,
                                      double reference = 0.0);

/// Acceleration of each pose coordinate [theta, x, y] at `times` from poses recorded every
/// `tick` seconds from t = 0: the central second difference over +-`span` ticks,
/// (p(t + h) - 2 p(t) + p(t - h)) / h^2, h = span tick (at the ends, the nearest full difference), linearly
/// interpolated between ticks. A difference over a span rather than one tick keeps the
/// integrator's error (divided by h^2) below the signal, as an accelerometer's bandwidth would.
[[nodiscard]] std::array<std::vector<double>, 3> poseAcceleration(const std::vector<Pose>& p, double tick,
                                                                  std::span<const double> times, int span);

/// Scores one axis; periods: n_periods log-spaced over [t_min, t_max] [s].
[[nodiscard]] ShakeScore scoreShake(std::span<const double> target, std::span<const double> achieved, double dt,
                                    double t_min, double t_max, int n_periods = 50);

/// What the drive correction inverts: nothing (H = I), the linearised closed loop by its exact
/// derivatives, or by central differences (closed_loop.hpp, LoopDerivatives).
enum class DriveModel { identity, exact, difference };

inline constexpr std::array<Choice<DriveModel>, 3> kDriveModels{
    {{DriveModel::identity, "identity"}, {DriveModel::exact, "exact"}, {DriveModel::difference, "difference"}}};
[[nodiscard]] constexpr std::span<const Choice<DriveModel>> choices(DriveModel) { return kDriveModels; }

/// "identity", "exact" or "difference".
[[nodiscard]] inline const char* name(DriveModel model) { return nameOf(model).data(); }

/// H^-1 of the driven axes on the correction's frequency grid (see the header comment).
struct DriveInverse {
    double dt = 0.0;                        ///< the drive's sample step [s]
    std::size_t samples = 0;                ///< n
    std::size_t fft_size = 0;               ///< N (a power of two >= 2 n)
    double band = 0.0;                      ///< the highest frequency corrected [Hz]
    std::array<bool, 3> driven{};           ///< [theta, x, y]
    std::vector<Eigen::Matrix3cd> inverse;  ///< bin k = 0 .. N / 2: H^-1 (zero rows / columns off the driven axes)
};

/// Builds H^-1 from the linearised loop (identity for DriveModel::identity: loop unused) for a
/// drive of `samples` samples every dt, corrected up to `band` [Hz] (at most below rate / 2).
/// Throws nocdyn::Error for fewer than 4 samples, a non-positive dt or band, no driven axis, or
/// a closed loop singular at a corrected frequency (naming it).
[[nodiscard]] DriveInverse driveInverse(DriveModel model, const ShakeLoopLinearization& loop, double dt,
                                        std::size_t samples, double band, const std::array<bool, 3>& driven);

/// drive[axis] += gain H^-1 error[axis] for the driven axes [theta, x, y] (error and drive of
/// inverse.samples each; see the header comment). Fails with not_finite (value: the first
/// non-finite error) and leaves the drive unchanged; throws nocdyn::Error for a length that is
/// not inverse.samples or a gain outside (0, 1].
Status correctDrive(const DriveInverse& inverse, const std::array<std::vector<double>, 3>& error, double gain,
                    std::array<std::vector<double>, 3>& drive);

// --- drive-signal iteration's bookkeeping, the same on a planar and a six-DOF table

/// The drive-signal iteration a user chooses: at most `iterations` passes after the first, each
/// playing the last drive corrected by `iteration_gain` times its error (correctDrive,
/// addDriveCorrection); it stops when the RMS error falls by less than `iteration_tolerance`
/// (relative: judgePass) or the drive would leave the limits, and keeps the best pass.
struct DriveIterationSettings {
    int iterations = 0;
    double iteration_gain = 0.7;  ///< g, in (0, 1]
    double iteration_tolerance = 0.02;
};

/// The fit of a pass's drive: the target's time scale L kept, no high-pass (the target is
/// filtered already) and half the target's margin (the drive's corrections may use half the
/// reserve the target keeps: they make up for what the plant does not follow).
[[nodiscard]] FitOptions driveFitOptions(FitOptions target, double time_scale);

/// d_(i+1) = d_i + g (a_target - a_i), sample by sample (the identity drive model); the three
/// spans of equal length.
void addDriveCorrection(std::span<double> drive, std::span<const double> target, std::span<const double> achieved,
                        double gain);

/// A pass's RMS error `rms` against the best pass's `best`: kept when below it; `stop` says why
/// the iteration stops after pass `pass` when it fell by less than `tolerance` (relative), else empty.
struct PassJudgement {
    bool kept = false;
    std::string stop;
};
[[nodiscard]] PassJudgement judgePass(int pass, double rms, double best, double tolerance);

/// Why the iteration stopped before pass `pass`: its drive would leave the limits.
[[nodiscard]] std::string driveLeavesLimits(int pass);

/// Why the iteration stopped when every pass asked was played.
inline constexpr const char* kLastPassAsked = "the last pass asked";

}  // namespace nocdyn
