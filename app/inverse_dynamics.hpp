// `inverse-dynamics`: actuator variables, rates, accelerations and forces of any robot along a
// platform trajectory (eqs. 5, 20, Appendix A), sample by sample.
#pragma once

#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "app/table.hpp"
#include "nocdyn/analysis/sampling.hpp"

namespace nocdyn::app {

struct InverseDynamicsOptions : SamplingOptions {
    RobotSource robot;
    /// Warn instead of failing at a joint's range or velocity, or an actuator's effort; a pose
    /// out of reach, a singular posture or a non-finite value stays an error.
    bool allow_limits = false;
    /// Every joint's reaction as more columns (limb{i}_j{k}_fx, _fy, _m).
    bool reactions = false;
};

struct InverseDynamicsResult {
    std::size_t samples = 0;
    /// Peaks per actuator and, with allow_limits, the limits passed (each also a warning).
    LimitSummary summary;
};

/// Samples t_k = k / rate, k = 0..round(duration * rate) - 1, into `table` with the columns of
/// io::TableId::inverse_dynamics (and the reactions'), row by row as computed. Joint ranges,
/// velocities and efforts are also checked between samples (40 points per period of the
/// highest harmonic); a rate at or below twice that frequency is refused.
InverseDynamicsResult runInverseDynamics(const InverseDynamicsOptions& options, TableSink& table, Observer& observer);

}  // namespace nocdyn::app
