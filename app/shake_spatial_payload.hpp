// The specimen on a six-DOF table identified before the replay (`shake --identify-payload` on a
// spatial robot): a multi-sine excitation within the legs' limits played in computed torque on
// the plant carrying the specimen, the controller knowing the robot alone; the table's log of
// its motion and forces through the least squares of nocdyn/sim/spatial_payload.hpp. The
// replay's controller model then carries the specimen as identified.
#pragma once

#include <string>

#include "app/shake.hpp"
#include "nocdyn/sim/spatial_control.hpp"
#include "nocdyn/sim/spatial_payload.hpp"

namespace nocdyn::app {

struct SpatialSpecimen {
    spatial::SpatialPayloadEstimate estimate;
    spatial::SpatialPayload truth;  ///< the specimen on the plant: a point mass at the platform origin
    LimitUse excitation_use;
    double duration = 0.0;     ///< of the excitation [s]
    double force_noise = 0.0;  ///< of the logged forces [N]
    double seconds = 0.0;      ///< wall-clock time of the excitation and the fit
};

/// The specimen (options.payload_mass at the platform origin on `plant`) identified on the
/// robot alone (`description`): options.excitation_duration of excitation at the loop's rate,
/// feedback and integration, options.seed, forces logged with a noise of 1e-4 of the largest
/// actuator effort (a load cell's 0.01 % of full scale).
[[nodiscard]] SpatialSpecimen identifySpatialSpecimen(const SpatialRobotDescription& description,
                                                      const spatial::Model& plant, const ShakeOptions& options,
                                                      const spatial::LoopOptions& loop);

/// shake.json with "payload_estimate" added: the estimate and its standard deviations, the true
/// values, the 10 parameters, the excitation's use of the limits.
[[nodiscard]] std::string withPayloadJson(const std::string& metrics_json, const SpatialSpecimen& specimen);

/// The summary's lines: each identified value +- its standard deviation, the true one beside it.
[[nodiscard]] std::string payloadSummary(const SpatialSpecimen& specimen);

}  // namespace nocdyn::app
