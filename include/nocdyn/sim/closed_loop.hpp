// The shake-table loop (shake_control.hpp) linearised at rest at a pose, and its frequency
// response from the reference platform acceleration to the achieved one.
//
// What is linearised: the plant (the forward dynamics of the plant's model, linearization.hpp),
// the control law tau = ID(p^, v^, ddp_cmd + c) of the controller's model (its exact
// derivatives, derivatives.hpp), the encoders' direct kinematics (q_m = p: the tracker returns
// the pose), the accelerometers' first-order filter, the steady-state Kalman estimator, the
// pose feedback and the acceleration correction. Noise and saturation are left out.
//
// Discrete time, exactly: the loop runs at the controller tick T = 1 / rate and the forces are
// held over a tick (zero-order hold), so the plant is discretised exactly,
//   x_(k+1) = Phi x_k + Gamma tau_k,  Phi = e^(A T),  Gamma = int_0^T e^(A s) ds B,
// and one tick of the loop (in runShakeLoop's order: accelerometers, estimator, correction,
// control law, plant) is the linear map s_(k+1) = F s_k + G w_k of the state
//   s = [p, dp, dp_(k-1), y, p^, v^, c, ddp_cmd,(k-1)] (24)
// and the input w = [a_r, dp_d, p_d, e] (the reference, and an injection e added to the demand
// ddp_cmd + c, where the loop is broken for the loop transfer). The response at f is that of
// s_k = S z^k, z = e^(j 2 pi f T), the reference a sampled sine:
//   a_r,k = (dp_d(t_(k+1)) - dp_d(t_k)) / T (the feed-forward, the reference's mean over a tick),
//   dp_d,k = a_r,k T / (z - 1),  p_d,k = dp_d,k / (j 2 pi f),
// and the achieved acceleration a_k = (dp(t_(k+1)) - dp(t_k)) / T, the platform's mean over the
// same tick. So H(z) = a / a_r compares like with like and is 1 for a perfect loop.
//
// The loop transfer L_i of axis i is broken at the demand of axis i (the other axes closed):
// with e_i injected, L_i = -(ddp_cmd,i + c_i - a_r,i) / (ddp_cmd,i + c_i + e_i) returned by the
// loop; its phase margin is 180 deg + arg L_i at the lowest frequency where |L_i| = 1.
//
// The plant may be the lumped compliant model (analysis/linearization.hpp: linearizeCompliant,
// the model of the open-loop response and of the envelope's amplification band) instead of the
// rigid one. Its drives with a stiffness are position servos (the spring's rest position u_c is
// the set point), so the controller's forces reach it as motion: the set points follow the
// rigid image of the motion those forces give the rigid machine,
//   M_p ddp_r = (rigid terms) + A_p^T tau,      u_c = A_p S p_r,
//   M_p ddp + C_d dp + K p = B_Q u_c (+ the forces of drives of stiffness 0) = K p_r at rest,
// so the platform p follows p_r through the lumped modes (p = H(w) p_r, H(0) = I: the envelope's
// dynamic amplification) and the sensors see p. The plant's state is then [p, dp, p_r, dp_r]:
// the loop's state s gains [p_r, dp_r] (30 in all). A robot without a drive of stiffness has
// no set point to follow: its lumped plant takes the forces directly (6 states). As the
// stiffness grows, H(w) -> I and the loop tends to the rigid one.
//
// The usable band of axis i: from the grid's first frequency up to the lowest where the closed
// loop's gain |H_ii| leaves [1/A, A] (A the amplification limit, as the envelope's band).
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/model.hpp"
#include "nocdyn/sim/shake_control.hpp"

namespace nocdyn {

/// How linearizeShakeLoop differentiates the plant and the control law: by their exact
/// derivatives (derivatives.hpp), or by central differences of forwardDynamics and
/// inverseDynamics with steps h (pose [rad, m], rate, acceleration) and h max(1, |tau_a|)
/// (forces), the comparison the exact ones are measured against.
enum class LoopDerivatives { exact, central_difference };

/// The plant of the linearised loop: the rigid robot, or the lumped compliant model driven
/// through its drives' set points (see above).
enum class LoopPlant { rigid, lumped };

/// The linearised shake-table loop: s_(k+1) = F s_k + G w_k, a_k = C s_k + D w_k (see above).
struct ShakeLoopLinearization {
    Eigen::MatrixXd F, G, C, D;
    /// The demand ddp_cmd + c + e in terms of (s, w) (3 x 36), for the loop transfer.
    Eigen::MatrixXd demand_s, demand_w;
    double dt = 0.0;  ///< T [s]
    /// The plant's states in s: 6 ([p, dp]) or 12 ([p, dp] and [p_r, dp_r], the lumped plant).
    int plant_states = 6;
};

/// Linearises the loop of runShakeLoop(model, plant on plant_model, ...) at rest at pose p
/// with `options` (rate, natural frequency, acceleration gain, sensors: their noise sets the
/// Kalman gain). `model` is the controller's model; `plant_model` may differ (a payload).
/// `plant` lumped: the compliant plant of plant_model's compliance (exact derivatives only).
/// Throws nocdyn::Error when p is out of reach or singular for either model, or when a lumped
/// plant is asked of a model without compliance.
[[nodiscard]] ShakeLoopLinearization linearizeShakeLoop(const Model& model, const Model& plant_model, const Pose& p,
                                                        const ShakeLoopOptions& options,
                                                        LoopDerivatives derivatives = LoopDerivatives::exact,
                                                        double step = 1e-6, LoopPlant plant = LoopPlant::rigid);

/// The spectral radius of the loop's one-tick map F, max |eig F| over the modes its inputs reach:
/// below 1 the linearised loop is stable (every such state decays tick by tick); at 1 or above it
/// diverges (or holds a mode that never decays), and a frequency response of it is no steady
/// state. A state the loop only holds, eigenvalue 1 with no input reaching it (PBH rank test; the
/// acceleration correction's sum at gain 0), is left out.
[[nodiscard]] double shakeLoopSpectralRadius(const ShakeLoopLinearization& loop);

/// The closed loop at frequency f [Hz] (0 < f < rate / 2): H(i, j) = achieved acceleration of
/// axis i per reference acceleration of axis j; and the loop transfers L_i (i = 0, 1, 2).
struct ShakeLoopResponse {
    Eigen::Matrix3cd closed_loop;
    Eigen::Vector3cd loop;
};
[[nodiscard]] ShakeLoopResponse shakeLoopResponse(const ShakeLoopLinearization& loop, double frequency);

/// Per axis over a frequency grid: the closed loop's diagonal and the loop transfer, magnitude
/// [dB] and phase [deg] (unwrapped), row k = frequency k, column = axis; the closed loop's -3 dB
/// bandwidth (as bandwidth3dB; NaN beyond the grid), and the loop's gain-crossover frequency and
/// phase margin (NaN when |L| never crosses 1 in the grid).
struct ShakeLoopFrequencyResponse {
    std::vector<double> frequency;
    Eigen::MatrixXd magnitude_db, phase_deg, loop_magnitude_db, loop_phase_deg;
    Vector3 bandwidth = Vector3::Zero(), crossover = Vector3::Zero(), phase_margin = Vector3::Zero();
};
[[nodiscard]] ShakeLoopFrequencyResponse shakeLoopFrequencyResponse(const ShakeLoopLinearization& loop,
                                                                    const std::vector<double>& frequencies);

/// Per axis, the closed loop's usable band and its peak over a response's grid:
///   end: the lowest frequency [Hz] where |H_ii| leaves [1/A, A], the last one inside by
///        bisection between grid points (shakeLoopResponse); NaN when |H_ii| stays inside over
///        the whole grid (the band reaches beyond it), 0 when it is outside at the first
///        grid frequency already;
///   peak_db, peak_frequency: the largest |H_ii| on the grid [dB] and its frequency [Hz].
struct ShakeLoopBand {
    double amplification = 0.0;  ///< A
    Vector3 end = Vector3::Zero(), peak_db = Vector3::Zero(), peak_frequency = Vector3::Zero();
};
/// Throws nocdyn::Error unless A > 1.
[[nodiscard]] ShakeLoopBand shakeLoopBand(const ShakeLoopLinearization& loop,
                                          const ShakeLoopFrequencyResponse& response, double amplification);

}  // namespace nocdyn
