// `simulate`: the forward dynamics of any robot under actuator forces read from a table
// (M_p d2p/dt2 = A_p^T tau - h_p, eq. 23 in the platform coordinates; sim/forward_dynamics.hpp).
#pragma once

#include <optional>
#include <string>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "app/table.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/sim/simulator.hpp"

namespace nocdyn::app {

/// simulate and control integrate over time and hold what they sample: at most this long and
/// this many output samples (duration * rate).
inline constexpr Range kSimulatedDurationRange{1e-6, 1e3, "s"};
inline constexpr double kMaxSimulatedSamples = 1e7;
/// The integrator's tolerances on the pose [rad, m] and its rate, and relative.
inline constexpr Range kAbsoluteToleranceRange{1e-15, 1e-2, ""};
inline constexpr Range kRelativeToleranceRange{1e-14, 1e-2, ""};
/// The integrator's largest step [s].
inline constexpr Range kMaxStepRange{1e-6, 1.0, "s"};

/// The integrator's tolerances (atol in kAbsoluteToleranceRange, rtol in kRelativeToleranceRange,
/// max_step in kMaxStepRange) are the simulator's.
struct SimulateOptions : IntegrationTolerances {
    /// CSV with columns t,tau1..taun [s, N or N m] (and the initial state in its first row).
    std::string forces;
    /// The same table given in code (Python): used instead of the file when set.
    std::optional<io::Table> forces_table;
    RobotSource robot;
    /// Forces between samples: hold, linear or cubic.
    Interpolation interpolation = Interpolation::cubic;
    /// Seconds to simulate; empty: the span of the forces (kSimulatedDurationRange).
    std::optional<double> duration;
    double rate = 10000.0;  ///< output samples per second (kRateRange)
    /// Which working assembly mode of the first row's u (1-based, as forward-kinematics lists
    /// them); 0: the one nearest home.
    int assembly_mode = 0;
    /// When the simulation stops early, return the rows before it (SimulateResult::stopped).
    bool partial = false;
    /// Every joint's reaction at each sample as more columns (limb{i}_j{k}_fx, _fy, _m).
    bool reactions = false;
};

struct SimulateResult {
    std::size_t rows = 0;
    double duration = 0.0;
    /// Where the initial state came from ("first row's x,y,theta, at rest", ...).
    std::string origin;
    std::string interpolation;
    std::size_t accepted_steps = 0, rejected_steps = 0, evaluations = 0;
    /// With partial: why and when the simulation stopped early ("t = ... s: ..."); else empty.
    std::string stopped;
};

/// "simulated 0.2 s from the first row's ... (cubic forces): N steps accepted, ..." (the
/// command line's summary on standard error, Python's Table.text).
[[nodiscard]] std::string summaryLine(const SimulateResult& result);

/// Throws OptionError for an option outside its range or choices.
void validate(const SimulateOptions& options);

/// A spatial robot (space: spatial) is simulated by runSpatialSimulate (app/simulate_spatial.hpp).
/// Rows at t0 + k / rate, k = 0..round(duration * rate) - 1, and at t0 + duration, into `table`
/// with the columns of io::TableId::simulate (and the reactions'), as computed. A state out of
/// reach or singular is an Error "t = ... s: ..." (with partial: returned in `stopped`).
SimulateResult runSimulate(const SimulateOptions& options, TableSink& table, Observer& observer);

}  // namespace nocdyn::app
