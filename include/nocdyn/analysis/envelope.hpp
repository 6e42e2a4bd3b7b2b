// Operating envelope of any planar parallel robot (model.hpp): for a sinusoid along one pose
// axis about the home posture,
//   p(t) = home + A sin(2 pi f t) e_axis        (axis theta, x or y; the others stay at home)
// the largest amplitude A at frequency f for which, over one period sampled finely, every pose
// is reachable and regular (no limb or actuation singularity), every joint stays within its
// range and velocity limits and every actuator within its effort (inverse dynamics, eq. 20,
// with gravity and friction when the robot file sets them).
//
// The range and workspace limits are kinematic and do not depend on f; the velocity limit
// scales as A ~ 1 / f and the effort limit as A ~ 1 / f^2 once the inertia forces dominate.
// Each is found by bisection on A: first the kinematic one (the period at rest, dp = ddp = 0),
// then the dynamic one below it; the smaller binds, and is named with its limb, joint and
// actuator.
//
// The band's third bound is the machine's own dynamics: when the robot file declares
// compliance, the lumped model K v = w^2 M v at the home posture (stiffness.hpp) with modal
// damping (the file's damping_ratio zeta, C = M Phi diag(2 zeta w_i) Phi^T M) is driven by the
// drives' commanded motion, whose quasi-static (rigid) image is the pose displacement p_s:
//   M ddp + C dp + K p = K p_s,   p = H(w) p_s,
//   H(w) = sum_i phi_i phi_i^T M w_i^2 / (w_i^2 - w^2 + 2 j zeta w_i w),   H(0) = I.
// The dynamic amplification of axis a is |H_aa(w)|, the platform's motion along the axis per
// unit of the commanded (rigid) motion. The band of axis a ends at the lowest frequency where
// it leaves [1 / limit, limit] (limit the user's, 1.1 by default: the rigid model's amplitude
// is then within 10 % of what the platform does); from there the limit is `resonance`. The
// first natural frequency f_1 is reported too; each axis' band ends below the first mode it
// couples to. Elastodynamic modes of elastic links can lie below f_1.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Pose axis, numbered as its index in the core's pose p = [theta, x, y] (eq. 1).
enum class EnvelopeAxis { theta = 0, x = 1, y = 2 };
[[nodiscard]] const char* axisName(EnvelopeAxis axis);

/// The axes in the user's pose order x, y, theta (pose_order.hpp): the order of the envelope's
/// points, tables and figures.
inline constexpr std::array<EnvelopeAxis, 3> kEnvelopeAxes{EnvelopeAxis::x, EnvelopeAxis::y, EnvelopeAxis::theta};

/// Whether a robot of task dimension n_t (model.hpp) moves along `axis`: every axis for n_t = 3;
/// x and y for a two-DOF robot (motion: translation), whose pose [x, y] has no theta.
[[nodiscard]] constexpr bool hasAxis(int task_dimension, EnvelopeAxis axis) {
    return task_dimension == 3 || axis != EnvelopeAxis::theta;
}

/// Which limit stops a larger amplitude. `none`: nothing up to the search bound (the robot's
/// joints are unlimited along this axis). `resonance`: the frequency is at or above the first
/// natural frequency (operatingEnvelope only).
enum class EnvelopeLimit { range = 0, velocity = 1, effort = 2, workspace = 3, none = 4, resonance = 5 };
[[nodiscard]] const char* limitName(EnvelopeLimit limit);

/// Accepted frequency range [Hz] and largest number of frequencies per axis.
inline constexpr double kEnvelopeMinFrequency = 1e-3;
inline constexpr double kEnvelopeMaxFrequency = 1e4;
inline constexpr int kEnvelopeMaxPoints = 1000;

/// The default and accepted range of the amplification limit of the band's third bound.
inline constexpr double kDefaultAmplification = 1.1;
inline constexpr double kMinAmplification = 1.001, kMaxAmplification = 100.0;

struct EnvelopeOptions {
    double min_frequency = 1.0;        ///< [Hz]
    double max_frequency = 100.0;      ///< [Hz]
    int points = 41;                   ///< log-spaced frequencies, both ends included
    int samples_per_period = 256;      ///< a multiple of 4 puts samples on the sinusoid's peaks
    double relative_tolerance = 1e-6;  ///< bisection stops when (hi - lo) <= tol * hi
    /// Called after each point with the points done and their total (e.g. a progress line).
    std::function<void(int done, int total)> progress = {};
    /// The band's third bound: the largest dynamic amplification accepted (see the header).
    double amplification = kDefaultAmplification;
    /// Called before each period the bisection checks (a caller's Ctrl-C); it may throw to stop.
    std::function<void()> poll = {};
};

/// The largest amplitude at one frequency along one axis.
struct EnvelopePoint {
    EnvelopeAxis axis = EnvelopeAxis::x;
    double frequency = 0.0;  ///< [Hz]
    double amplitude = 0.0;  ///< [rad] for theta, [m] for x and y
    EnvelopeLimit limit = EnvelopeLimit::none;
    int limb = -1;      ///< 0-based limb that reaches the limit first (-1: none)
    int joint = -1;     ///< 0-based joint of that limb (-1: not joint-specific)
    int actuator = -1;  ///< 0-based actuator at that joint (-1: a passive joint or none)
    /// Largest amplitude allowed by the ranges and the workspace alone.
    double kinematic_amplitude = 0.0;
    /// max over actuators with an effort limit and over the period of |tau_a| / effort_a at
    /// `amplitude` (0 when no actuator has one).
    double peak_effort_ratio = 0.0;
    double peak_u = 0.0;    ///< max over actuators and the period of |u_a| at `amplitude` [m or rad]
    double peak_tau = 0.0;  ///< max over actuators and the period of |tau_a| at `amplitude` [N or N m]
};

/// Largest amplitude along `axis` at `frequency` (see the file header). Throws nocdyn::Error
/// for a frequency or option out of range, a home posture that is not feasible, or theta on a
/// two-DOF robot (no such axis).
[[nodiscard]] EnvelopePoint maximumAmplitude(const Model& model, EnvelopeAxis axis, double frequency,
                                             const EnvelopeOptions& options = {});

/// The band's third bound: the lumped model at home (the elastodynamic one where the lumped one
/// does not hold), its first natural frequency and, per axis, where its dynamic amplification
/// leaves [1 / limit, limit].
struct EnvelopeResonance {
    bool declared = false;   ///< the robot file declares compliance (joint stiffness, elastic body)
    int task_dimension = 3;  ///< the robot's n_t: its axes are those hasAxis accepts
    bool known = false;
    double frequency = 0.0;                        ///< f_1 [Hz] when known
    double damping_ratio = 0.0;                    ///< zeta of every mode (the robot file's)
    double amplification = kDefaultAmplification;  ///< the limit
    /// Per axis (index: EnvelopeAxis), the lowest frequency [Hz] where the amplification leaves
    /// [1 / limit, limit] (infinity when it never does): the band's end.
    std::array<double, 3> band_end{};
    LumpedModes modes;  ///< the lumped model at home (known only)
    /// The model f_1 and the amplification come from: the lumped one, or the elastodynamic one
    /// where the lumped one does not hold at home (firstFrequency), and then `warning`
    /// says so.
    FrequencyModel model = FrequencyModel::lumped;
    std::string warning;
    /// The modes H sums over (known only): frequencies f_i [Hz], the platform's dp in each
    /// (3 x m, pose order) and participation (m x 3): phi_i^T M x_a, x_a the rigid image of a unit
    /// displacement along axis a (lumped: phi_i^T M itself), so that H(0) = shape participation = I.
    Eigen::VectorXd modal_frequency;
    Eigen::MatrixXd modal_shape, modal_participation;
    /// Why it is not known: the robot file declares no compliance, or the compliance it declares
    /// leaves a limb rigid or the platform free at home ("" when known).
    std::string reason;
};

/// f_1 and the band's ends of `model` at its home posture (stiffnessAndModes), or why there is
/// none. Throws nocdyn::Error for an amplification limit outside [kMinAmplification,
/// kMaxAmplification].
[[nodiscard]] EnvelopeResonance envelopeResonance(const Model& model, double amplification = kDefaultAmplification);

/// |H_aa| of the known resonance at frequency f [Hz] (see the file header).
[[nodiscard]] double dynamicAmplification(const EnvelopeResonance& resonance, EnvelopeAxis axis, double frequency);

/// The whole envelope: for each axis (x, y, theta; x, y of a two-DOF robot), each log-spaced
/// frequency. When
/// envelopeResonance is known, the points at f >= the axis' band end keep the rigid model's
/// amplitude and peaks but their limit is `resonance` (no limb, joint or actuator).
[[nodiscard]] std::vector<EnvelopePoint> operatingEnvelope(const Model& model, const EnvelopeOptions& options = {});

}  // namespace nocdyn
