// Metrics of one design, and sweeps over many: the numbers a designer compares candidate
// geometries by, each the same number the single-robot computation gives:
//   workspace_area       area of the feasible region of C at theta (workspace.hpp) [m^2]
//   condition_median     median scaled condition number of A over that region [-]
//   condition_worst      largest scaled condition number of A over that region [-]
//   first_frequency_min  lowest first natural frequency of the lumped model over that region
//                        (frequency_map.hpp) [Hz]; needs the compliance the file declares
//   envelope_AXIS@F      largest amplitude along AXIS (x, y, theta) at F Hz (envelope.hpp)
//                        [m or rad]
//   moving_mass          platform and every limb body [kg]
//   peak_force, rms_force, stroke    over a trajectory (sampling.hpp, limits enforced): the
//                        largest |tau_a|, the largest RMS of tau_a over the samples, the largest
//                        max u_a - min u_a, over actuators [N or N m; m or rad]
//   peak_reaction        largest joint reaction force |(f_x, f_y)| over the trajectory
//                        (reactions.hpp) [N]
// A design that does not assemble at home, is singular there, has no feasible workspace,
// declares no compliance (first_frequency_min) or meets a limit along the trajectory is
// infeasible: its evaluation names the reason instead of throwing.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "nocdyn/choice.hpp"
#include "nocdyn/description.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/analysis/workspace.hpp"

namespace nocdyn {

enum class DesignMetricKind {
    workspace_area,
    condition_median,
    condition_worst,
    first_frequency_min,
    envelope,
    moving_mass,
    peak_force,
    rms_force,
    stroke,
    peak_reaction
};

/// One metric; `axis` and `frequency` for the envelope only.
struct DesignMetric {
    DesignMetricKind kind = DesignMetricKind::workspace_area;
    EnvelopeAxis axis = EnvelopeAxis::x;
    double frequency = 0.0;  ///< [Hz]
    /// Its column name: "workspace_area", "envelope_x@50", ...
    [[nodiscard]] std::string name() const;
    /// SI unit, for the column's description: "m^2", "m", "rad", "kg", "N", "-".
    [[nodiscard]] std::string unit() const;
    /// Whether a larger value is better (workspace, first frequency, envelope), else smaller is.
    [[nodiscard]] bool larger_is_better() const;
    /// Whether it needs a trajectory.
    [[nodiscard]] bool along_trajectory() const;
};

/// The metric a name means ("envelope_theta@50", "workspace_area", ...); throws nocdyn::Error
/// listing the accepted names.
[[nodiscard]] DesignMetric parseDesignMetric(const std::string& text);

/// How each metric is computed; the defaults are the single-robot commands'.
struct DesignOptions {
    WorkspaceOptions workspace{0.0, 201, false};
    bool workspace_theta_at_home = true;  ///< use the robot's home theta, not workspace.theta
    EnvelopeOptions envelope;
    /// For the trajectory metrics: the motion, its duration [s] and sampling rate [Hz].
    std::optional<PoseTrajectory> trajectory;
    double duration = 0.2;
    double rate = 10000.0;
};

/// The metrics of one design, in the order asked, or why it is infeasible (values NaN).
struct DesignEvaluation {
    bool feasible = false;
    std::string reason;          ///< empty when feasible
    std::vector<double> values;  ///< one per metric
};

/// Evaluates `metrics` for `robot` (see the file header). Never throws for a property of the
/// design; throws nocdyn::Error for metrics that need a trajectory when none is given.
[[nodiscard]] DesignEvaluation evaluateDesign(const RobotDescription& robot, const std::vector<DesignMetric>& metrics,
                                              const DesignOptions& options);

/// The range one design parameter is varied over.
struct DesignRange {
    std::string name;
    double lower = 0.0, upper = 0.0;
};

/// Most designs one sweep may hold.
inline constexpr std::size_t kMaxDesigns = 1'000'000;

/// Sample points of a sweep, one vector of values (in the order of `ranges`) per design.
///   grid:   n = round(samples^(1/d)) (at least 2) evenly spaced values per parameter, ends
///           included, the last parameter varying fastest; n^d designs
///   random: `samples` uniform draws (std::mt19937_64 from `seed`)
/// Throws nocdyn::Error for an empty or reversed range, or more than kMaxDesigns designs.
enum class SweepKind { grid, random };
inline constexpr std::array<Choice<SweepKind>, 2> kSweepKinds{
    {{SweepKind::grid, "grid"}, {SweepKind::random, "random"}}};
[[nodiscard]] constexpr std::span<const Choice<SweepKind>> choices(SweepKind) { return kSweepKinds; }
[[nodiscard]] std::vector<std::vector<double>> sweepPoints(const std::vector<DesignRange>& ranges, SweepKind kind,
                                                           std::size_t samples, std::uint64_t seed);

/// The one work queue of a sweep: evaluate(i) for i in [0, count) on `threads` worker threads
/// (at least 1; each index once), while the calling thread calls record(i, result) for each,
/// one at a time, in completion order, and stop() after each batch of records and at least
/// every 0.1 s (worker threads call neither). Once stop() returns true no new design starts;
/// those under way finish and are recorded. An exception from evaluate does the same and is
/// then rethrown; one from record or stop stops new designs, lets those under way finish and
/// is rethrown. Returns how many were recorded.
std::size_t evaluateInParallel(std::size_t count, int threads,
                               const std::function<DesignEvaluation(std::size_t)>& evaluate,
                               const std::function<void(std::size_t, DesignEvaluation&&)>& record,
                               const std::function<bool()>& stop = {});

/// Indices of the feasible designs no other feasible design dominates (at least as good in
/// every metric, better in one), metric m read as larger-is-better when larger_is_better[m],
/// else smaller-is-better; in index order. A design with a NaN value neither dominates nor is
/// dominated (it compares neither way), so it is on the front. O(n log n) for one or two
/// metrics (a sort and one pass), O(n |front|) for more. `progress(done, total)`, when given, is called as the
/// feasible designs are passed.
[[nodiscard]] std::vector<std::size_t> paretoFront(const std::vector<DesignEvaluation>& designs,
                                                   const std::vector<bool>& larger_is_better,
                                                   const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The same over a table: values row by row, larger_is_better.size() to a row, and one
/// feasible flag a row; throws nocdyn::Error when the sizes disagree.
[[nodiscard]] std::vector<std::size_t> paretoFront(std::span<const double> values, std::span<const bool> feasible,
                                                   const std::vector<bool>& larger_is_better,
                                                   const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The same, each metric's sense from its larger_is_better().
[[nodiscard]] std::vector<std::size_t> paretoFront(const std::vector<DesignEvaluation>& designs,
                                                   const std::vector<DesignMetric>& metrics,
                                                   const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace nocdyn
