// Calibration files: the robot's base parameters identified on the robot itself (`nocdyn identify
// --base --output cal.yaml`), read back to identify a payload against the calibrated robot.
//
//   robot: paper-3prr
//   base_parameters:
//     - {parameter: 'platform.m', value: 3.1, stddev: 0.002, robot_file: 3.0, unit: 'kg', name: '...'}
//
// One item per base parameter, in the order `nocdyn regressor` lists them; `parameter` names the
// standard parameter heading the combination (its column of the regressor), `value` its
// identified value; the other keys are for the reader. Unknown keys are errors.
//
// Prior files: what is known of a payload beforehand, as bounds on its parameters (`nocdyn
// identify --payload --prior prior.yaml`):
//
//   payload:
//     mass: [0.4, 0.6]        # kg, lower > 0
//     com_x: [-0.02, 0.02]    # m, the c.o.m. in the platform frame
//     com_y: [-0.02, 0.02]    # m
//     inertia: [0, 2e-3]      # kg m^2 about the payload's own c.o.m., lower >= 0
//
// Each key is optional, each value [lower, upper] with lower <= upper, ~ (null) for an open side
// (mass: [~, 0.6]); equal bounds fix the parameter (a mass known from a scale). Unknown keys,
// lower > upper, a mass bound <= 0 or a negative inertia bound are errors naming the line.
#pragma once

#include <string>

#include "nocdyn/sim/identification.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn::tables {

/// The calibration file text (as above) of identified base parameters.
[[nodiscard]] std::string calibrationToYaml(const Model& model, const BaseResult& result, const std::string& comment);

/// Parses calibration YAML for `model`. Throws nocdyn::Error "SOURCE:LINE: field: reason" for a
/// malformed file or a parameter name the model does not have.
[[nodiscard]] Calibration parseCalibration(const std::string& text, const std::string& source, const Model& model);
[[nodiscard]] Calibration loadCalibration(const std::string& path, const Model& model);

/// Parses prior YAML (as above). Throws nocdyn::Error "SOURCE:LINE: field: reason".
[[nodiscard]] PayloadPrior parsePayloadPrior(const std::string& text, const std::string& source);
[[nodiscard]] PayloadPrior loadPayloadPrior(const std::string& path);

}  // namespace nocdyn::tables
