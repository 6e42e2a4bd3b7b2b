// Operating envelope of the 3-PRR vibration generator: for a sinusoid along one pose axis
// about the reference posture,
//   p(t) = A sin(2 pi f t) e_axis        (axis theta, x or y; the others stay at zero)
// the largest amplitude A at frequency f for which, over one period sampled finely, every
// pose is inside the workspace and non-singular, every |u_j| <= stroke / 2, and every
// |tau_j| <= peak force, with tau from the inverse dynamics (eq. 20).
//
// The stroke (and workspace) limit is kinematic, so it does not depend on f; the force limit
// scales as A ~ F_peak / (m_eff (2 pi f)^2) once the inertia forces dominate. Each limit is
// found by bisection on A, first the kinematic one, then the force one below it; the smaller
// binds.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/prr3/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn::prr3 {

/// Pose axis, numbered as in the pose p = [theta, x, y] (eq. 1).
enum class Axis { theta = 0, x = 1, y = 2 };
[[nodiscard]] const char* axisName(Axis axis);

/// Which limit stops a larger amplitude.
enum class BindingLimit { stroke, force, workspace };
[[nodiscard]] const char* limitName(BindingLimit limit);

/// Accepted frequency range [Hz] and largest number of frequencies per axis.
inline constexpr double kEnvelopeMinFrequency = 1e-3;
inline constexpr double kEnvelopeMaxFrequency = 1e4;
inline constexpr int kEnvelopeMaxPoints = 1000;

struct EnvelopeOptions {
    double min_frequency = 1.0;        ///< [Hz]
    double max_frequency = 100.0;      ///< [Hz]
    int frequencies = 41;              ///< log-spaced, both ends included
    int samples_per_period = 256;      ///< a multiple of 4 puts samples on the sinusoid's peaks
    double relative_tolerance = 1e-6;  ///< bisection stops when (hi - lo) <= tol * hi
};

/// The largest amplitude at one frequency along one axis.
struct EnvelopePoint {
    Axis axis = Axis::x;
    double frequency = 0.0;  ///< [Hz]
    double amplitude = 0.0;  ///< [rad] for theta, [m] for x and y
    BindingLimit limit = BindingLimit::stroke;
    int limb = -1;                     ///< 0-based limb that hits the limit first
    double kinematic_amplitude = 0.0;  ///< largest amplitude allowed by stroke and workspace alone
    double peak_force = 0.0;           ///< max_j,t |tau_j| at `amplitude` [N]
    double peak_stroke = 0.0;          ///< max_j,t |u_j| at `amplitude` [m]
};

/// Largest amplitude along `axis` at `frequency` (see the file header).
[[nodiscard]] EnvelopePoint maximumAmplitude(const Model& model, Axis axis, double frequency,
                                             const EnvelopeOptions& options = {});

/// The whole envelope: for each axis (theta, x, y), each log-spaced frequency.
[[nodiscard]] std::vector<EnvelopePoint> operatingEnvelope(const Model& model, const EnvelopeOptions& options = {});

}  // namespace nocdyn::prr3
