// The rigid robot linearised at an operating point, and its frequency response.
//
// State x = [p; dp/dt] - [p0; dp0], input the actuator forces tau - tau0, with the exact
// derivatives of the forward dynamics (derivatives.hpp), d2p/dt2 = f(p, dp, tau):
//   dx/dt = A x + B du,  A = [0 I; df/dp df/d(dp)],  B = [0; df/dtau = M_p^-1 A_p^T]
//   y = C x + D du with y either
//     the platform acceleration d2p/dt2:  C = [df/dp df/d(dp)], D = df/dtau, or
//     the actuator variables u(p):        C = [A_p 0] (du = A_p dp/dt, A_p = A S(c)), D = 0.
// The frequency response is H(j w) = C (j w I - A)^-1 B + D, one complex matrix (outputs x
// actuators) per frequency.
//
// Compliant (lumped) model, linearizeCompliant: the compliance the robot file declares
// (stiffness.hpp: drive and joint springs, elastic links) is quasi-static and massless, the
// bodies rigid and carried by the platform's pose p as in the NOC (the lumped model of
// stiffness.hpp). Limb j's springs and beams transmit the wrench (twists referred to O)
//   w_j = -K_j (S dp - sum_{position drives a of j} s_a du_c,a) + (I - K_j C_j) W_j tau_f,j
// with K_j, C_j the limb's stiffness and compliance (stiffness.hpp), S = S(c), s_a the drive's
// screw, du_c,a a commanded drive position (the spring's rest position; a drive without a
// stiffness is locked: its commanded position is its position), and W_j tau_f,j any wrench
// with G_f^T W_j tau_f,j = [the free joints' forces] (a force actuator, stiffness 0, is a free
// joint loaded by its force; (I - K_j C_j) removes the part its springs take). The platform
//   M_p ddp + (rigid terms at p, dp, tau0) = S^T sum_j w_j
// linearised, the joint forces' preload tau0 acting as in the rigid model and the springs by
// the unloaded structure's K = S^T (sum_j K_j) S (stiffness.hpp: no preload stiffness):
//   A = [0 I; df/dp - M_p^-1 K, df/d(dp) - M_p^-1 C_d],  B = [0; M_p^-1 B_Q],
// C_d the modal damping of the robot file's damping_ratio zeta (0.02 by default), C_d = M_p
// Phi diag(2 zeta w_i) Phi^T M_p with K Phi = M_p Phi Omega^2, Phi^T M_p Phi = I,
//   B_Q column a = S^T K_j s_a        (position input du_c,a [m or rad]: drive with a
//                                      stiffness k > 0, or locked),
//                = S^T (I - K_j C_j) W_j e_a  (force input [N or N m]: stiffness 0).
// At rest with gravity off df/dp = df/d(dp) = 0: -M_p A_21 = K and the eigenvalues of A are
// w (-zeta +- j sqrt(1 - zeta^2)) with K v = w^2 M_p v, the lumped modes. Outputs as the rigid model; "actuators" is
// then A_p dp, the actuator variables of the platform's pose (the drives' rigid image), not
// the deflected drives.
#pragma once

#include <array>
#include <complex>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/choice.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// What the linearised model's output y is.
enum class LinearOutput { platform_acceleration, actuator_variables };

inline constexpr std::array<Choice<LinearOutput>, 2> kLinearOutputs{
    {{LinearOutput::platform_acceleration, "acceleration"}, {LinearOutput::actuator_variables, "actuators"}}};
[[nodiscard]] constexpr std::span<const Choice<LinearOutput>> choices(LinearOutput) { return kLinearOutputs; }

/// "acceleration" or "actuators".
[[nodiscard]] inline const char* name(LinearOutput output) { return nameOf(output).data(); }

/// What an input column of the linearised model is: an actuator force [N or N m] or a drive's
/// commanded position (its spring's rest position) [m or rad].
enum class LinearInput { force, commanded_position };

/// "tau" or "uc": the prefix of an input's channel name.
[[nodiscard]] const char* name(LinearInput input);

/// A continuous-time state-space model dx/dt = A x + B u, y = C x + D u.
struct StateSpace {
    Eigen::MatrixXd A, B, C, D;
    LinearOutput output = LinearOutput::platform_acceleration;
    std::vector<LinearInput> inputs;  ///< one per column of B (actuator order)
};

/// The linearised model at (p, dp/dt, tau) (see above). Fails as forwardDynamicsDerivatives.
/// For a two-DOF robot (motion: translation) the state is [p_t; dp_t] over the task coordinates
/// [x, y] (model.hpp's task map E) and the acceleration output ddp_t (2 rows).
Status linearize(const Model& model, Data& data, const Pose& p, const Twist& dp, const ActuatorVector& tau,
                 LinearOutput output, StateSpace& out);

/// The compliant (lumped) linearised model (see above) when compliance.any, else linearize's.
/// Fails as forwardDynamicsDerivatives and cartesianStiffness (rigid_limb). Throws nocdyn::Error
/// for a two-DOF robot with compliance (its lumped model is not built).
Status linearizeCompliant(const Model& model, const StiffnessModel& compliance, Data& data, const Pose& p,
                          const Twist& dp, const ActuatorVector& tau, LinearOutput output, StateSpace& out);

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

/// The phase at a grid's first frequency [deg], in (-180 + 1e-6, 180 + 1e-6]: a real negative
/// gain reads 180 whatever the sign its rounding gives the imaginary part; every channel's
/// phase is then unwrapped from there (each next frequency's phase the nearest, by multiples of
/// 360, to the previous one).
[[nodiscard]] double anchoredPhase(double phase_deg);

/// The low-frequency slope of channel (output o, input i) in units of 20 dB per decade, from the
/// grid's first two frequencies: 0 for a flat channel (acceleration per force), 2 for one that
/// rises as w^2 (acceleration per commanded position), -2 (a position per force).
[[nodiscard]] double lowFrequencySlope(const FrequencyResponse& response, int o, int i);

/// The low-frequency slope is that of an asymptote |H| ~ w^k (k an integer) when it is within
/// this of one.
inline constexpr double kSlopeTolerance = 0.25;

/// The -3 dB bandwidth of channel (output o, input i): the lowest frequency, linearly
/// interpolated in log frequency between grid points, where the magnitude has fallen 3 dB
/// below its low-frequency asymptote |H(f_1)| (f / f_1)^k, f_1 the grid's first frequency and
/// k the rounded lowFrequencySlope (0 for a flat channel: 3 dB below |H(f_1)|; 2 for an
/// acceleration per commanded position: the motion 3 dB below the commanded one). NaN when it
/// never does within the grid, or when the slope at f_1 is no integer (within kSlopeTolerance:
/// the grid starts above the channel's low-frequency asymptote).
[[nodiscard]] double bandwidth3dB(const FrequencyResponse& response, int o, int i);

/// `count` frequencies spaced evenly in log between f_min and f_max [Hz].
[[nodiscard]] std::vector<double> logGrid(double f_min, double f_max, int count);

}  // namespace nocdyn
