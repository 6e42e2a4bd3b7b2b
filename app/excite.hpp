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

struct ExciteOptions {
    RobotSource robot;
    /// The guessed payload: mass [kg], c.o.m. x, y [m, platform frame], inertia about its c.o.m.
    /// [kg m^2]; empty: none.
    std::vector<double> payload_guess;
    bool base = false;       ///< design for the robot's base parameters (no payload)
    bool friction = false;   ///< with the payload: the actuated joints' friction too
    double duration = 5.0;   ///< [s], a whole number of base periods
    double frequency = 5.0;  ///< f0 [Hz]
    int harmonics = 4;
    double margin = 0.1;
    double max_condition = 100.0;
    int evaluations = 400;
    int random = 60;
    int samples = 0;
    int check_samples = 2000;
    unsigned seed = 1;
    /// The refinement after the random search: nelder-mead or gradient (excitation.hpp).
    ExcitationOptimizer optimizer = ExcitationOptimizer::nelder_mead;
    /// The trajectory file to write (none when empty).
    std::string output;
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

/// Designs the excitation (progress: evaluations; a stop ends it at the next evaluation);
/// writes options.output when given.
ExciteResult runExcite(const ExciteOptions& options, Observer& observer);

}  // namespace nocdyn::app
