// Trajectory files (YAML): per axis an offset plus harmonics a sin(2 pi f t + phase).
//
//   duration: 0.2                          # [s], optional
//   x:     {offset: 0.001, harmonics: [{amplitude: -0.002, frequency: 10, phase: 0.5236}]}
//   y:     {offset: 0.002, harmonics: [{amplitude: 0.004, frequency: 10, phase: -0.5236}]}
//   theta: {offset: 0.0, harmonics: [{amplitude: 0.05236, frequency: 10}]}
//
// Units m, rad, Hz, rad. An axis left out stays at zero; offset and phase default to 0;
// amplitude and frequency are required in a harmonic; unknown keys are errors.
#pragma once

#include <string>

#include "nocdyn/trajectory.hpp"

namespace nocdyn::io {

/// Reads a trajectory file. Throws nocdyn::Error "FILE:LINE: field: reason".
[[nodiscard]] PoseTrajectory loadTrajectory(const std::string& path);

/// Parses trajectory YAML text; `source` names it in error messages.
[[nodiscard]] PoseTrajectory parseTrajectory(const std::string& text, const std::string& source);

/// `paper1` or `paper2` (eqs. 33-34), else a trajectory file path.
[[nodiscard]] PoseTrajectory trajectoryByNameOrFile(const std::string& name_or_path);

}  // namespace nocdyn::io
