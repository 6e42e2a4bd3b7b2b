// Least-squares identification of a payload fixed to the platform, or of the robot's base
// parameters, from a measured motion (motion.hpp): weighted least squares on tau = Y pi
// (regressor.hpp), its covariance counting the residuals' correlation along the samples, and
// the physically consistent payload within known bounds.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/model.hpp"
#include "nocdyn/sim/identification_options.hpp"
#include "nocdyn/sim/motion.hpp"

namespace nocdyn {

/// Throws nocdyn::Error unless the calibration has this model's base columns (was made for this
/// robot) and finite values.
void checkCalibration(const Model& model, const Calibration& calibration);

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
    /// linear parameters' at the estimate) [kg, m, m, kg m^2, friction units; products]. For a
    /// two-DOF robot (a point payload at the tool point: com and inertia stay 0) of [m, friction..].
    Eigen::MatrixXd covariance;
    FitReport fit;
};

struct BaseResult {
    std::vector<Estimate> beta;
    Eigen::MatrixXd covariance;  ///< of beta (rank x rank)
    Calibration calibration;     ///< the same values, with their base columns
    FitReport fit;
};
/// Payload [mass, com, inertia] fixed to the platform (a two-DOF robot's: a point mass at the tool
/// point, its mass only; a prior bounding its com or inertia is refused), the robot's own parameters taken from
/// the model: weighted least squares on tau - Y pi_robot = Y_platform delta_pi, then the
/// physically consistent solution within the prior's bounds (options.prior): when the
/// unbounded solution is outside them, the bounded least-squares solution over the physical
/// parameters (see least_squares.cpp). Throws nocdyn::Error when a parameter is unidentifiable
/// (naming it and the condition number) or the mass is not positive (without a lower bound).
[[nodiscard]] PayloadResult identifyPayload(const Model& model, const Motion& motion,
                                            const IdentificationOptions& options = {});

/// Base parameters from the motion (calibration of the robot itself).
[[nodiscard]] BaseResult identifyBase(const Model& model, const Motion& motion,
                                      const IdentificationOptions& options = {});
}  // namespace nocdyn
