// CSV tables of the results (rows in the column layouts of layouts.hpp), kept out of the physics.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/analysis/sampling.hpp"

namespace nocdyn::tables {

/// t,x,y,theta,u1..un,du1..dun,ddu1..ddun,tau1..taun,kinetic (SI; n actuators;
/// io::TableId::inverse_dynamics); without theta for a two-DOF robot (task_dimension 2, pose [x, y]).
[[nodiscard]] std::vector<std::string> inverseDynamicsColumns(int actuators, int task_dimension = 3);

/// `prefix`1..`prefix`n, e.g. "tau1".."tau4".
[[nodiscard]] std::vector<std::string> numbered(const std::string& prefix, int count);

/// One row of a sample in the order of inverseDynamicsColumns (of the same task_dimension), into
/// `row` (resized).
void inverseDynamicsRow(const InverseDynamicsSample& sample, std::vector<double>& row, int task_dimension = 3);

/// limb{i}_j{k}_fx, limb{i}_j{k}_fy, limb{i}_j{k}_m for every limb i and joint k (1-based,
/// file order): the joint reactions of reactions.hpp [N, N, N m].
[[nodiscard]] std::vector<std::string> reactionColumns(int limbs);

/// The reactions appended to `row` in the order of reactionColumns.
void appendReactions(const Reactions& reactions, int limbs, std::vector<double>& row);

/// The whole series as a table.
[[nodiscard]] io::Table toTable(const InverseDynamicsSeries& series, int actuators);

/// A closed-loop run: t, x_d, y_d, theta_d, x, y, theta, e_x, e_y, e_theta, u1..un, u1_d..un_d,
/// tau1..taun (SI; io::TableId::closed_loop); with task_dimension 2 (a two-DOF robot) no theta_d,
/// theta or e_theta.
[[nodiscard]] io::Table toTable(const PoseLoopResult& result, int task_dimension = 3);

/// An experiment's log: t,u1..un,tau1..taun, then du1..dun,ddu1..ddun when it has them (what
/// identify reads).
[[nodiscard]] io::Table toTable(const Measurements& measurements);

/// An operating envelope, one row per point (io::TableId::envelope; axis and limit as words); with a
/// known resonance, its first_natural_frequency column.
[[nodiscard]] io::Table toTable(const std::vector<EnvelopePoint>& points, const EnvelopeResonance& resonance = {});

}  // namespace nocdyn::tables
