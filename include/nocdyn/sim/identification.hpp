// Inertia-parameter identification of the general planar parallel robot: the dynamics of
// dynamics.hpp written linearly in the inertial and friction parameters,
//   tau = Y(q, dq, ddq) pi,
// the identifiable (base) combinations of pi, and least-squares identification of a payload
// fixed to the platform (or of the base parameters) from measured actuator positions and forces.
//
// Standard parameters pi, per body i (model body order, the platform last), in the body's own
// frame: [m, m c_x, m c_y, I_O], with c the c.o.m. and I_O the moment of inertia about the
// frame's origin O_i (I_O = I + m |c|^2). A limb body's frame coincides with the base frame at
// home and moves with the body (product of exponentials: c is the c.o.m. at home, base axes);
// the platform's frame has its origin at C and turns with theta (c = the file's platform com).
// Then per joint (limb order, chain order): [damping, friction].
//
// Regressor. A planar body whose frame origin o (at r) moves with acceleration a_o, turning at
// omega with rate domega, needs the wrench (inertial minus weight, referred to the base origin O)
//   f   = m (a_o - g) + domega E h - omega^2 h,           h = R(phi) [m c_x; m c_y]
//   n_O = I_O domega + h x (a_o - g) + r x f
// linear in [m, m c_x, m c_y, I_O]: its 3 x 4 wrench regressor Y_w,i. The NOC maps it to the
// platform coordinates with the body's twist shaping referred to O, xi_i = U_i xi_P (U_i =
// [s_1 .. s_k] rows of J_j^-1, identity for the platform), W = sum_i U_i^T Y_w,i, plus the
// friction columns J_j^-T e_k (q'_k, sign q'_k); then tau = A^-T W (three actuators) or the
// minimum-norm A (A^T A)^-1 W (redundant), exactly as inverse dynamics applies them.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/sim/control.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Inertial parameters per body and friction parameters per joint.
inline constexpr int kBodyParameters = 4;
inline constexpr int kJointParameters = 2;
/// Largest number of standard parameters a model has.
inline constexpr int kMaxParameters = kBodyParameters * kMaxBodies + kJointParameters * 3 * kMaxLimbs;

/// Regressor Y: n actuators x P standard parameters. Fixed capacity: never allocates.
using RegressorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxActuators, kMaxParameters>;
/// The standard parameter vector pi. Fixed capacity.
using ParameterVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxParameters, 1>;

/// Number of standard parameters P = 4 bodies + 2 * 3 limbs.
[[nodiscard]] int parameterCount(const Model& model);
/// Index of body i's first parameter (m), and of joint k of limb j's damping (friction + 1).
[[nodiscard]] int bodyParameterIndex(int body);
[[nodiscard]] int jointParameterIndex(const Model& model, int limb, int joint);
/// "platform.m", "limb2.body1.I_O", "limb1.joint3.damping": the name of parameter `index`.
[[nodiscard]] std::string parameterName(const Model& model, int index);
/// The unit of parameter `index` ("kg", "kg m", "kg m^2", "N s/m", "N", ...).
[[nodiscard]] std::string parameterUnit(const Model& model, int index);

/// pi of the model (the values the robot file gives).
[[nodiscard]] ParameterVector standardParameters(const Model& model);
/// The inertial parameters [m, m c_x, m c_y, I_O] of a body of mass m, c.o.m. c (in its frame)
/// and moment of inertia I about the c.o.m.
[[nodiscard]] Eigen::Vector4d inertialParameters(double mass, const Vector2& com, double inertia);

/// Regressor stage: Y with tau = Y pi for the motion in `data`. Needs the position (with q),
/// velocity and acceleration stages (not the shaping stage). Allocation-free.
void regressor(const Model& model, const Data& data, RegressorMatrix& Y);

/// Position, velocity and acceleration stages from p, dp/dt, d2p/dt2, then Y.
Status inverseDynamicsRegressor(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                                RegressorMatrix& Y);

/// Base parameters: beta = K pi with Y pi = Y_b beta for every motion, Y_b the columns
/// `independent` of Y. Found by a column-pivoted QR of the regressors of random motions
/// (columns scaled to unit norm), rank by the relative tolerance.
struct BaseParameters {
    int rank = 0;
    std::vector<int> independent;     ///< standard-parameter indices of the base columns
    std::vector<int> unidentifiable;  ///< parameters with no effect on tau (zero columns)
    Eigen::MatrixXd K;                ///< rank x P: beta = K pi
    double condition = 0.0;           ///< of the scaled base regressor (ratio of R's extreme pivots)
};

struct BaseParameterOptions {
    int samples = 200;        ///< random motions
    unsigned seed = 1;        ///< of the random motions
    double tolerance = 1e-9;  ///< relative pivot below which a column is dependent
    double pose_scale = 1.0;  ///< scale of the random poses around home (0.05 rad, 5 mm)
};

/// Throws nocdyn::Error when too few random motions are valid.
[[nodiscard]] BaseParameters baseParameters(const Model& model, const BaseParameterOptions& options = {});

/// "beta_3 = limb1.body1.m + 0.0625 limb1.body2.m" lines, one per base parameter.
[[nodiscard]] std::string describeBaseParameters(const Model& model, const BaseParameters& base);

// ---------------------------------------------------------------------------------------------
// Identification from measurements.

/// What a logger recorded: time, actuator positions and forces (rows = samples, columns =
/// actuators in file order); du and ddu when measured or known (else empty).
struct Measurements {
    std::vector<double> t;
    Eigen::MatrixXd u, tau, du, ddu;
    /// What tau is: false, the force at each sample's instant (a force sensor's reading); true,
    /// the command applied from each sample until the next (zero-order hold, as sensorLog and
    /// `nocdyn control --log` give it; a log names these columns tau{a}_held).
    bool held_forces = false;
};

/// The robot's own base parameters as identified on it (identifyBase on data without payload):
/// they replace the robot file's in the known part of a payload identification.
struct Calibration {
    std::vector<int> independent;  ///< standard-parameter indices of the base columns
    Eigen::VectorXd beta;          ///< the identified base parameters
};

/// Throws nocdyn::Error unless the calibration has this model's base columns (was made for this
/// robot) and finite values.
void checkCalibration(const Model& model, const Calibration& calibration);

/// Bounds [lower, upper] on one parameter; an infinite side is open.
struct Bounds {
    double lower = -std::numeric_limits<double>::infinity();
    double upper = std::numeric_limits<double>::infinity();
};

/// What is known of a payload beforehand (a prior file, io/calibration.hpp): bounds on its
/// physical parameters. The estimate is then the weighted least-squares solution within them
/// and within mass > 0, inertia about the c.o.m. >= 0 (which hold without a prior too).
struct PayloadPrior {
    Bounds mass;          ///< [kg], lower > 0 when given
    Bounds com_x, com_y;  ///< the c.o.m. in the platform frame [m]
    Bounds inertia;       ///< about the payload's own c.o.m. [kg m^2], lower >= 0 when given
};

struct IdentificationOptions {
    /// Zero-phase low-pass cut-off when du and ddu are derived from u [Hz] (0: a tenth of the
    /// sampling rate, at most 50 Hz).
    double cutoff = 0.0;
    /// Fraction of the samples (the last ones) held out to check the fit.
    double holdout = 0.2;
    /// Identify the actuated joints' damping and Coulomb friction alongside the payload.
    bool friction = false;
    /// The logged forces are commands held until the next sample (zero-order hold, as `nocdyn
    /// control` logs them): the force at t_k is then the mean of the two holds around it,
    /// (tau_(k-1) + tau_k) / 2, so that it matches the accelerations the differences of u give.
    bool held_forces = false;
    /// With a payload: the robot's calibrated base parameters in place of the robot file's
    /// (its base columns must be those baseParameters(model) finds). Not with `friction`: the
    /// calibration holds the joints' friction already.
    std::optional<Calibration> calibration;
    /// Bounds on the payload's parameters (payload identification only; unbounded by default).
    PayloadPrior prior;
};

/// One identified value with its standard deviation (from the residuals, counting their
/// correlation along the samples: FitReport::correlation_samples).
struct Estimate {
    std::string name;
    std::string unit;
    double value = 0.0;
    double stddev = 0.0;
    double prior = 0.0;  ///< the robot file's value (base parameters), 0 for a payload
};

/// The fit of measured against predicted forces.
struct FitReport {
    int fit_samples = 0, holdout_samples = 0;
    std::vector<double> rms_fit, rms_holdout;  ///< per actuator [N or N m]
    std::vector<double> rms_measured;          ///< rms of the held-out measured forces
    double condition = 0.0;                    ///< of the weighted, column-scaled regressor
    /// The residuals' integrated autocorrelation time tau_int [samples]: a filtered log's
    /// residuals are correlated over about f_s / (2 B) samples (B the filter's equivalent noise
    /// bandwidth), so the fit holds fit_samples / tau_int independent ones (effective_samples).
    /// The covariances count it: the score's long-run covariance by overlapping batch means of
    /// block_samples = 4 tau_int samples (a sandwich N^-1 S N^-1), not the white-noise s^2 N^-1,
    /// which is sqrt(tau_int) times too small in standard deviation (about 11 at 10 kHz, 50 Hz).
    double correlation_samples = 1.0;
    int block_samples = 1;
    double effective_samples = 0.0;
    std::vector<double> t;                ///< held-out times
    Eigen::MatrixXd measured, predicted;  ///< held-out forces (rows: samples)
};

/// A bound the payload estimate lies on: the unbounded least-squares solution violates it.
struct ActiveBound {
    std::string parameter;  ///< "mass", "com_x", "com_y" or "inertia"
    bool upper = false;     ///< on the upper bound (else the lower)
    double bound = 0.0;
    /// The parameter in the unbounded solution (NaN when its mass is not positive, so that it
    /// has no c.o.m. or inertia).
    double unbounded = 0.0;
};

struct PayloadResult {
    double mass = 0.0;
    Vector2 com = Vector2::Zero();  ///< platform frame [m]
    double inertia = 0.0;           ///< about its own c.o.m. [kg m^2]
    double mass_sd = 0.0, inertia_sd = 0.0;
    Vector2 com_sd = Vector2::Zero();
    bool inertia_constrained = false;  ///< the unconstrained estimate was negative: set to 0
    double inertia_unconstrained = 0.0;
    /// The bounds (the prior's, and inertia >= 0) the estimate lies on; standard deviations
    /// stay those of the unbounded solution's linearisation at the estimate.
    std::vector<ActiveBound> active_bounds;
    std::vector<Estimate> friction;  ///< actuated joints' damping and friction, when asked
    /// Covariance of [m, c_x, c_y, I, then the friction's order] (first-order map from the
    /// linear parameters' at the estimate) [kg, m, m, kg m^2, friction units; products].
    Eigen::MatrixXd covariance;
    FitReport fit;
};

struct BaseResult {
    std::vector<Estimate> beta;
    Eigen::MatrixXd covariance;  ///< of beta (rank x rank)
    Calibration calibration;     ///< the same values, with their base columns
    FitReport fit;
};

/// Motion from the measurements: the platform pose by the direct-kinematics tracker (PoseTracker), its rates
/// from du (ddu) as given or by zero-phase low-pass filtering and differentiating u (tau is then
/// filtered alike). Throws nocdyn::Error naming the sample time on a lost tracker or a singular
/// posture, and on too few samples or a non-monotonic time.
struct Motion {
    std::vector<double> t;
    std::vector<Pose> p;
    std::vector<Twist> dp, ddp;
    Eigen::MatrixXd tau;
    /// The zero-phase low-pass u and tau went through [Hz] and the sampling rate [Hz]; 0 when
    /// the rates were given. The regressor's Coulomb friction columns (sign q', a step at every
    /// reversal) then go through the same filter, as the force's friction part did.
    double cutoff = 0.0, rate = 0.0;
};
[[nodiscard]] Motion reconstructMotion(const Model& model, const Measurements& data,
                                       const IdentificationOptions& options = {});

/// Payload [mass, com, inertia] fixed to the platform, the robot's own parameters taken from
/// the model: weighted least squares on tau - Y pi_robot = Y_platform delta_pi, then the
/// physically consistent solution within the prior's bounds (options.prior): when the
/// unbounded solution is outside them, the bounded least-squares solution over the physical
/// parameters (see identification.cpp). Throws nocdyn::Error when a parameter is unidentifiable
/// (naming it and the condition number) or the mass is not positive (without a lower bound).
[[nodiscard]] PayloadResult identifyPayload(const Model& model, const Motion& motion,
                                            const IdentificationOptions& options = {});

/// Base parameters from the motion (calibration of the robot itself).
[[nodiscard]] BaseResult identifyBase(const Model& model, const Motion& motion,
                                      const IdentificationOptions& options = {});

/// The experiment's log as the sensors see it: t, u and tau of a closed-loop run, du and ddu
/// left empty. u: when the run measured through its encoders (run.u_measured), their readings,
/// the very draws the controller used (noise_u is then not drawn again); else the plant's u
/// plus Gaussian encoder noise of std. dev. noise_u (each actuator's unit). tau: the applied
/// force plus Gaussian force-measurement noise noise_tau (the force sensor's alone).
[[nodiscard]] Measurements sensorLog(const PoseLoopResult& run, double noise_u, double noise_tau, unsigned seed = 1);

}  // namespace nocdyn
