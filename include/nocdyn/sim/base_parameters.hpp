// The base parameters: the combinations beta = K pi of the standard parameters (regressor.hpp)
// that the actuator forces determine, Y pi = Y_b beta for every motion.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/model.hpp"
#include "nocdyn/sim/regressor.hpp"

namespace nocdyn {

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
}  // namespace nocdyn
