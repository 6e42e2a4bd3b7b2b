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

#include "nocdyn/spatial_trajectory.hpp"
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

/// A spatial robot's trajectory file (spatial_trajectory.hpp) of `dimension` coordinates (6:
/// x, y, z, roll, pitch, yaw; 3: x, y, z for motion translation), every one given:
///
///   duration: 1.0
///   x:    {offset: 0.0, harmonics: [{amplitude: 0.005, frequency: 2}]}
///   z:    {offset: 1.0579369}          # absolute, not from home
///   roll: {harmonics: [{amplitude: 0.02, frequency: 3, phase: 0.5}]}
///   ...
///
/// each axis as the planar file's (offset, harmonics of amplitude, frequency, phase; m, rad,
/// Hz). A missing coordinate, an unknown key, a planar key (theta) or, for dimension 3, roll,
/// pitch or yaw are errors. Throws nocdyn::Error "FILE:LINE: field: reason".
[[nodiscard]] spatial::Trajectory parseSpatialTrajectory(const std::string& text, const std::string& source,
                                                         int dimension);

/// A spatial robot's samples (CSV): columns t [s] and every coordinate (positions, m and rad),
/// interpolated by the C2 spline of parseTrajectoryCsv with the same checks of the times; the
/// duration is the last time. Throws nocdyn::Error "FILE:LINE: column 'NAME': reason".
[[nodiscard]] spatial::Trajectory parseSpatialTrajectoryCsv(const std::string& text, const std::string& source,
                                                            int dimension);

/// A spatial trajectory file: samples when the name ends in .csv, else YAML. The built-in
/// names paper1 and paper2 (planar) are refused.
[[nodiscard]] spatial::Trajectory loadSpatialTrajectory(const std::string& path, int dimension);

}  // namespace nocdyn::io
