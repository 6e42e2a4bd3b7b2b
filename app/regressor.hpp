// `regressor`: the robot's standard inertial and friction parameters pi (tau = Y pi) and the
// base parameters, the combinations of them the actuator forces identify.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/sim/identification.hpp"

namespace nocdyn::app {

inline constexpr Range kRegressorSamplesRange{20.0, 100000.0, "motions"};

/// The random motions stacked (samples, within kRegressorSamplesRange, and their seed) and the
/// rank test are the library's (baseParameters).
struct RegressorOptions : BaseParameterOptions {
    RobotSource robot;
};

struct RegressorResult {
    std::vector<std::string> names, units;  ///< of each standard parameter, in order
    Eigen::VectorXd pi;                     ///< the standard parameters (robot file values)
    BaseParameters base;
    /// The report: pi one per line, then the base parameters described.
    std::string text;
};

/// Throws OptionError for samples out of range.
void validate(const RegressorOptions& options);

[[nodiscard]] RegressorResult runRegressor(const RegressorOptions& options, Observer& observer);

}  // namespace nocdyn::app
