// What an identification is told: the robot's calibration, the bounds known of a payload, and
// how the measured motion is reconstructed and fitted (identification.hpp).
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/model.hpp"

namespace nocdyn {

/// The robot's own base parameters as identified on it (identifyBase on data without payload):
/// they replace the robot file's in the known part of a payload identification.
struct Calibration {
    std::vector<int> independent;  ///< standard-parameter indices of the base columns
    Eigen::VectorXd beta;          ///< the identified base parameters
};

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

/// How the measured motion is reconstructed and fitted: the settings a user chooses, shared by
/// the library's options and the application's (app::IdentifyOptions).
struct IdentificationSettings {
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
};

struct IdentificationOptions : IdentificationSettings {
    /// With a payload: the robot's calibrated base parameters in place of the robot file's
    /// (its base columns must be those baseParameters(model) finds). Not with `friction`: the
    /// calibration holds the joints' friction already.
    std::optional<Calibration> calibration;
    /// Bounds on the payload's parameters (payload identification only; unbounded by default).
    PayloadPrior prior;
};
}  // namespace nocdyn
