// Excitation design for identification: a periodic multi-harmonic platform trajectory (the
// trajectory file's form, common base frequency f0) along which the stacked regressor of the
// parameters to identify is as well conditioned as possible, within the robot's limits.
//
// Each pose axis q in {theta, x, y} (a Fourier series, omega = 2 pi f0):
//   q(t) = q_home + s sum_{k=1..H} (a_k sin(k omega t) + b_k cos(k omega t))
// with the coefficients tied so that the motion starts (and every period returns) at home at
// rest: sum b_k = 0 (q(0) = home), sum k a_k = 0 (dq(0) = 0), sum k^2 b_k = 0 (ddq(0) = 0).
// A two-DOF robot (motion: translation) moves on x, y only: theta stays at home and its
// coefficients are inert; its payload is a point mass at the tool point (the mass column only).
// The free coefficients (2H - 3 per axis) give the shape; for each shape the scale s is the
// largest for which, at every sample of one period,
//   - every joint is within its range, |q - mid| <= (1 - margin) half-range,
//   - every joint within its velocity limit, every actuator within its effort (inverse dynamics
//     with the guessed payload, eq. 20), both with the same margin,
//   - every limb Jacobian J_j and the actuation map A have a scaled condition number at most
//     max_condition (away from singularities, as kinematics.hpp measures them),
// found by bisection on log s (the envelope's approach, envelope.hpp). The objective is the
// condition number of the column-scaled stacked regressor at that largest scale (the number
// `identify` reports): a seeded random search over shapes, then a local refinement from the
// best, bounded by a number of evaluations, deterministic for a seed. The refinement is
// Nelder-Mead (the default), or a descent on the exact gradient of the log condition number:
// tau = Y pi is linear in pi, so column k of Y and its derivatives d Y_k / d(p, dp, ddp) are
// those of the inverse dynamics (derivatives.hpp) of robots whose parameters combine to e_k,
// chained through the samples (linear in the shape) and the extreme eigenpairs of the scaled
// information matrix (see excitationConditionGradient).
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/choice.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn {

/// Which regressor columns the excitation is designed for.
enum class ExcitedParameters {
    payload,  ///< the four payload parameters [m, m c_x, m c_y, I_O] (the platform's columns)
    base,     ///< the robot's base parameters (calibration; identification.hpp)
};

/// The local refinement after the random search.
enum class ExcitationOptimizer {
    nelder_mead,  ///< derivative-free simplex
    /// BFGS on the exact gradient of the objective (log cond at the largest scale), then
    /// Nelder-Mead with the evaluations left where BFGS stops (at a kink of the objective, where
    /// the binding limit changes)
    gradient,
};

inline constexpr std::array<Choice<ExcitationOptimizer>, 2> kExcitationOptimizers{
    {{ExcitationOptimizer::nelder_mead, "nelder-mead"}, {ExcitationOptimizer::gradient, "gradient"}}};
[[nodiscard]] constexpr std::span<const Choice<ExcitationOptimizer>> choices(ExcitationOptimizer) {
    return kExcitationOptimizers;
}

/// "nelder-mead" / "gradient" (the table's), and back; the parse throws nocdyn::Error on another name.
[[nodiscard]] std::string optimizerName(ExcitationOptimizer optimizer);
[[nodiscard]] ExcitationOptimizer parseOptimizer(const std::string& name);

struct ExcitationOptions {
    ExcitedParameters parameters = ExcitedParameters::payload;
    bool friction = false;         ///< with payload: the actuated joints' damping and friction too
    double base_frequency = 5.0;   ///< f0 [Hz] (the period of the paper's trajectory 2)
    int harmonics = 4;             ///< H per axis (at least 3)
    double margin = 0.1;           ///< fraction of each range, velocity and effort limit kept free
    double max_condition = 100.0;  ///< largest scaled condition number of J_j and A
    int samples = 0;               ///< per period in the design (0: 25 H)
    int check_samples = 2000;      ///< per period in the final check of the limits
    int evaluations = 400;         ///< objective evaluations in all (random search and Nelder-Mead)
    int random_shapes = 60;        ///< of them, random shapes before Nelder-Mead
    unsigned seed = 1;
    ExcitationOptimizer optimizer = ExcitationOptimizer::nelder_mead;
    /// Called before each objective evaluation with the number made so far (progress); may
    /// throw to stop the design. None by default.
    std::function<void(int evaluations)> progress = {};
};

/// How much of each limit a trajectory uses at its worst sample, as a fraction of the allowed
/// value (the limit less the margin; condition: of max_condition); 0 where a limit is absent.
struct ExcitationLimitUse {
    double range = 0.0, velocity = 0.0, effort = 0.0, condition = 0.0;
    std::string binding;  ///< "effort of actuator 2 (limb2)": the largest of the four
    [[nodiscard]] double worst() const;
};

/// A trajectory judged: feasible (every sample computed and within the limits), its limit use
/// and the condition number of the column-scaled stacked regressor (infinite when a column
/// vanishes). `failure` says why an infeasible one is (pose unreachable, singular, ...).
struct ExcitationAssessment {
    bool feasible = false;
    double condition = 0.0;
    ExcitationLimitUse use;
    std::string failure;
};

/// The regressor columns (standard-parameter indices) the options designate.
[[nodiscard]] std::vector<int> excitedColumns(const Model& model, const ExcitationOptions& options);

/// Judges `trajectory` on [0, period) at `samples` evenly spaced times. `model` carries the
/// guessed payload (its effort is what the actuators must supply).
[[nodiscard]] ExcitationAssessment assessExcitation(const Model& model, const PoseTrajectory& trajectory, double period,
                                                    int samples, const ExcitationOptions& options);

struct ExcitationResult {
    PoseTrajectory trajectory;        ///< offset at home, harmonics k f0; duration as asked
    ExcitationAssessment assessment;  ///< at options.check_samples per period
    int evaluations = 0;              ///< objective evaluations made (gradients included)
    int gradients = 0;                ///< of them, exact gradients (the gradient refinement)
};

/// Designs the excitation (see the file header) for `duration` seconds (a whole number of base
/// periods). Throws nocdyn::Error on options out of range, a home posture that violates the
/// limits, or no feasible shape found.
[[nodiscard]] ExcitationResult designExcitation(const Model& model, double duration,
                                                const ExcitationOptions& options = {});

/// The shape's free Fourier coefficients (3 (2H - 3), per axis a_2..a_H then b_3..b_H, in rad
/// and length scales) as a trajectory of `duration` at scale s (see the file header).
[[nodiscard]] PoseTrajectory excitationTrajectory(const Model& model, const Eigen::VectorXd& shape, double scale,
                                                  const ExcitationOptions& options, double duration);

/// log of the condition number of the column-scaled stacked regressor of the shape at scale s
/// (options.samples per period, 0: 25 H), and its exact gradient with respect to the shape's
/// coefficients at that fixed scale:
///   S = D^-1/2 N D^-1/2, N = sum_i Y_i^T Y_i (excited columns), D = diag N,
///   d lambda = v^T dS v = u^T dN u - lambda sum_a v_a^2 dN_aa / N_aa   (u = D^-1/2 v),
///   d log cond = (d lambda_max / lambda_max - d lambda_min / lambda_min) / 2,
/// dN from dY_i = sum over (p, dp, ddp) of d Y_i / d x times d x / d shape (linear in it).
/// Coulomb friction columns are differentiated with sign q' frozen (derivatives.hpp). Infinite value
/// (gradient zero) where a sample cannot be computed or the matrix is singular.
[[nodiscard]] double excitationConditionGradient(const Model& model, const Eigen::VectorXd& shape, double scale,
                                                 const ExcitationOptions& options, Eigen::VectorXd& gradient);

/// The gradient with respect to the shape of the largest scale within the limits, from the limit
/// that binds at the design samples at `scale` (the scale the design found for the shape): its
/// use g(s z) = 1 gives grad s = -s grad_c g / (grad_c g . z), exact for a joint's range or
/// rate and an actuator's effort. False (gradient untouched) when a condition number of J_j or
/// A binds (its scaled 1-norm is not differentiated) or a sample fails. The design's gradient
/// refinement descends on s grad_c F + (grad_c F . z) grad s, F = log cond at a fixed scale.
[[nodiscard]] bool excitationScaleGradient(const Model& model, const Eigen::VectorXd& shape, double scale,
                                           const ExcitationOptions& options, Eigen::VectorXd& gradient);

/// The trajectory moved so that its offsets are relative to the robot's home (the paper's
/// trajectories were written about the paper robot's home, the origin).
[[nodiscard]] PoseTrajectory aboutHome(const Model& model, PoseTrajectory trajectory);

}  // namespace nocdyn
