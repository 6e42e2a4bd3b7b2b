// Section "Identification experiment" of `nocdyn reproduce`: the payload identification of the
// paper's prototype, simulated end to end on the Simbody plant generated from its robot file.
#pragma once

#include <filesystem>
#include <iosfwd>

namespace nocdyn::report {

/// Runs the experiment (designed excitation, with and without slider friction unknown to the
/// robot file; the paper's trajectories 1 and 2 as the naive baseline), each for `duration`
/// seconds of data at 10 kHz, and writes identification/*.csv, identification/forces.png/.svg
/// in `out` and its markdown section to `summary`. Deterministic (fixed seeds).
void reproduceIdentification(const std::filesystem::path& out, std::ostream& summary, double duration);

}  // namespace nocdyn::report
