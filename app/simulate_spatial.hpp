// `simulate` of a spatial robot (space: spatial): the forward dynamics integrated under actuator
// forces read from a table (spatial::Simulator, nocdyn/sim/spatial_simulator.hpp), with the
// options and the result of the planar job (app/simulate.hpp).
#pragma once

#include "app/observer.hpp"
#include "app/simulate.hpp"
#include "app/table.hpp"

namespace nocdyn::app {

/// Rows t, x, y, z (, roll, pitch, yaw), u1..un, du1..dun, tau1..taun, kinetic at t0 + k / rate
/// and at t0 + duration. The initial state is the first row's pose (x, y, z and, for motion
/// full, roll, pitch, yaw) with its rates dx.. (else du1..dun, else at rest), or home at rest
/// when the row gives no pose. --assembly-mode and --reactions are refused (planar for now).
SimulateResult runSpatialSimulate(const SimulateOptions& options, TableSink& table, Observer& observer);

}  // namespace nocdyn::app
