// Trajectory files: sampled (CSV, below) or (YAML) per axis an offset plus harmonics a sin(2 pi f t + phase).
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

/// A harmonic trajectory as trajectory-file YAML (name, duration when set, offsets, harmonics;
/// every number to round-trip precision). Throws nocdyn::Error for a sampled trajectory.
[[nodiscard]] std::string trajectoryToYaml(const PoseTrajectory& trajectory);

/// Sampled trajectory (CSV, io/csv.hpp): a column `t` [s] and any of `x,y,theta` (positions,
/// m and rad) or `ax,ay,alpha` (accelerations, m/s^2 and rad/s^2), at most one of the two per
/// axis; an axis left out stays at zero. Times strictly increasing, uniform or not, at least 2
/// rows, and no gap: no step longer than kMaxTimeStepRatio times the median step. Positions are
/// interpolated by a C2 spline, accelerations integrated from zero velocity and displacement
/// (trajectory.hpp). The duration is the last time. Throws nocdyn::Error "FILE:LINE: column
/// 'NAME': reason".
[[nodiscard]] PoseTrajectory parseTrajectoryCsv(const std::string& text, const std::string& source);
[[nodiscard]] PoseTrajectory loadTrajectoryCsv(const std::string& path);

/// Longest step of a sampled trajectory, in median steps, before it is a gap.
inline constexpr double kMaxTimeStepRatio = 10.0;

/// `paper1` or `paper2` (eqs. 33-34), else a trajectory file path: CSV (sampled) when the name
/// ends in .csv, else YAML (harmonic).
[[nodiscard]] PoseTrajectory trajectoryByNameOrFile(const std::string& name_or_path);

}  // namespace nocdyn::io
