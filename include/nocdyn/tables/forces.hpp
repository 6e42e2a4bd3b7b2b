// Force signals from CSV files and tables: the columns t,tau1..taun (forward_dynamics.hpp's
// ForceSignal), with errors naming the file, line and column.
#pragma once

#include <string>

#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::tables {

/// Forces from a CSV table with columns t,tau1..taun (extra columns ignored). Throws
/// nocdyn::Error "SOURCE:LINE: column 'NAME': reason" (missing column, time not increasing,
/// non-uniform times for cubic).
[[nodiscard]] ForceSignal forcesFromTable(const io::Table& table, int actuators, Interpolation interpolation,
                                          const std::string& source);

/// Forces read from a CSV file row by row (io::readCsvFileRows) into flat storage: 8 bytes a
/// force and a time, whatever the file's size. The same columns and errors as forcesFromTable,
/// and a column tau(n+1) or beyond (forces for actuators the robot does not have) is an error
/// naming it. `first` receives the header and the first row (for the initial state).
[[nodiscard]] ForceSignal forcesFromCsvFile(const std::string& path, int actuators, Interpolation interpolation,
                                            io::Table& first);

}  // namespace nocdyn::tables
