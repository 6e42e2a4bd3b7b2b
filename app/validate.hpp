// `validate`: the actuator forces of nocdyn's model of any robot against Simbody's and MuJoCo's,
// each engine's model generated from the same robot file (built with both engines only).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/choice.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::app {

/// The engines a robot's forces are compared with: Simbody and MuJoCo, or the one named.
enum class ValidateEngine { both, simbody, mujoco };

inline constexpr std::array<Choice<ValidateEngine>, 3> kValidateEngines{
    {{ValidateEngine::both, "both"}, {ValidateEngine::simbody, "simbody"}, {ValidateEngine::mujoco, "mujoco"}}};
[[nodiscard]] constexpr std::span<const Choice<ValidateEngine>> choices(ValidateEngine) { return kValidateEngines; }

struct ValidateOptions : SamplingOptions {
    ValidateOptions() { rate = 1000.0; }
    RobotSource robot;
    /// The engines a spatial robot is compared with: both (Simbody and MuJoCo), simbody or
    /// mujoco. A planar robot is always compared with both (only both is taken).
    ValidateEngine engine = ValidateEngine::both;
};

struct ValidateResult {
    std::string robot, trajectory;
    std::size_t samples = 0;
    /// t, u, tau, each engine's u and tau, and their differences (validation::toTable).
    io::Table table;
    /// The largest absolute and relative difference per actuator and engine, as text.
    std::string agreement;
};

/// A spatial robot file (space: spatial) goes to runSpatialValidate (app/validate_spatial.hpp).
[[nodiscard]] ValidateResult runValidate(const ValidateOptions& options, Observer& observer);

/// When `source` is a spatial robot file (`space: spatial`): reads and checks it and returns a
/// short summary (limbs, joints by type, actuators, mass), what `validate` says of it without a
/// trajectory. std::nullopt for any other robot. Throws nocdyn::Error naming the file, line and field of an error in
/// it.
[[nodiscard]] std::optional<std::string> checkSpatialRobot(const RobotSource& source);

}  // namespace nocdyn::app
