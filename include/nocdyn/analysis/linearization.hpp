// The rigid robot linearised at an operating point, and its frequency response.
//
// State x = [p; dp/dt] - [p0; dp0], input the actuator forces tau - tau0, with the exact
// derivatives of the forward dynamics (derivatives.hpp), d2p/dt2 = f(p, dp, tau):
//   dx/dt = A x + B du,  A = [0 I; df/dp df/d(dp)],  B = [0; df/dtau = M_p^-1 A_p^T]
//   y = C x + D du with y either
//     the platform acceleration d2p/dt2:  C = [df/dp df/d(dp)], D = df/dtau, or
//     the actuator variables u(p):        C = [A_p 0] (du = A_p dp/dt, A_p = A S(c)), D = 0.
// The frequency response is H(j w) = C (j w I - A)^-1 B + D, one complex matrix (outputs x
// actuators) per frequency. The model is rigid: joint and drive compliance are not included.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// What the linearised model's output y is.
enum class LinearOutput { platform_acceleration, actuator_variables };

/// "acceleration" or "actuators".
[[nodiscard]] const char* name(LinearOutput output);

/// A continuous-time state-space model dx/dt = A x + B u, y = C x + D u.
struct StateSpace {
    Eigen::MatrixXd A, B, C, D;
    LinearOutput output = LinearOutput::platform_acceleration;
};

/// The linearised model at (p, dp/dt, tau) (see above). Fails as forwardDynamicsDerivatives.
Status linearize(const Model& model, Data& data, const Pose& p, const Twist& dp, const ActuatorVector& tau,
                 LinearOutput output, StateSpace& out);

/// H(j 2 pi f) = C (j 2 pi f I - A)^-1 B + D, outputs x inputs, at the frequency f [Hz].
[[nodiscard]] Eigen::MatrixXcd frequencyResponse(const StateSpace& system, double frequency);

/// The frequency response of every output to every input over a grid: magnitude [dB] and
/// phase [deg], unwrapped along the grid, row k = frequency k, column o * inputs + i.
struct FrequencyResponse {
    std::vector<double> frequency;  ///< [Hz]
    Eigen::MatrixXd magnitude_db, phase_deg;
    int outputs = 0, inputs = 0;
};

/// The response over `frequencies` (increasing, positive) [Hz].
[[nodiscard]] FrequencyResponse frequencyResponse(const StateSpace& system, const std::vector<double>& frequencies);

/// The -3 dB bandwidth of channel (output o, input i): the lowest grid frequency, linearly
/// interpolated in log frequency, where the magnitude has fallen 3 dB below its value at the
/// first grid frequency; NaN when it never does within the grid.
[[nodiscard]] double bandwidth3dB(const FrequencyResponse& response, int o, int i);

/// `count` frequencies spaced evenly in log between f_min and f_max [Hz].
[[nodiscard]] std::vector<double> logGrid(double f_min, double f_max, int count);

}  // namespace nocdyn
