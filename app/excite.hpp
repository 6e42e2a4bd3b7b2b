// `excite`: an excitation trajectory for identification (sim/excitation.hpp), its condition
// number next to the paper's trajectories 1 and 2, and the trajectory file's text.
#pragma once

#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/sim/excitation.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::app {

inline constexpr Range kExciteDurationRange{1e-3, 1e6, "s"};
inline constexpr Range kExciteFrequencyRange{1e-3, 1e3, "Hz"};
inline constexpr Range kExciteMarginRange{0.0, 0.9, ""};
inline constexpr Range kMaxConditionRange{1.0001, 1e8, ""};
inline constexpr Range kPayloadGuessRange{-1e6, 1e6, ""};

/// The design's own options (sim/excitation.hpp: the excited parameters, f0, H, margin, limits,
/// search), with the robot, the guessed payload and the duration.
struct ExciteOptions : ExcitationOptions {
    RobotSource robot;
    /// The guessed payload: mass [kg], c.o.m. x, y [m, platform frame], inertia about its c.o.m.
    /// [kg m^2]; empty: none.
    std::vector<double> payload_guess;
    double duration = 5.0;  ///< [s], a whole number of base periods
};

/// Throws OptionError naming the field of a value out of range.
void validate(const ExciteOptions& options);

struct ExciteResult {
    std::string text;  ///< the report printed (YAML-like lines, # comments)
    std::string yaml;  ///< the trajectory file: the report as comments, then the trajectory
    PoseTrajectory trajectory;
    double condition = 0.0;
    int evaluations = 0;
    int gradients = 0;  ///< of the evaluations, exact gradients (optimizer "gradient")
};

/// Designs the excitation (progress: evaluations; a stop ends it at the next evaluation). Writes
/// no file: the front ends write `yaml` where their caller asks.
ExciteResult runExcite(const ExciteOptions& options, Observer& observer);

}  // namespace nocdyn::app
