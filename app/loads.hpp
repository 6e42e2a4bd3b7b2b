// `loads`: every joint's design loads (reactions.hpp) along a trajectory, or over the operating
// envelope's motions: peak and RMS reaction force, peak couple, and where the peaks occur. The
// envelope's motions at and above the first natural frequency (limit resonance) are left out:
// there the platform does not follow the rigid model's motion, so its reactions are not loads
// the machine sees, and a design load must not be sized (nor its peak placed) on them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "app/envelope.hpp"
#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::app {

struct LoadsOptions : SamplingOptions {
    RobotSource robot;
    /// Over the operating envelope's motions instead of the trajectory (then none is given).
    bool envelope = false;
    double min_frequency = 1.0;    ///< envelope: [Hz] (kEnvelopeFrequencyRange)
    double max_frequency = 100.0;  ///< envelope: [Hz], at least min_frequency
    int points = 9;                ///< envelope: frequencies per axis
};

/// A spatial robot's (space: spatial, loads_spatial.hpp) has no model nor loads: its table,
/// text and worst joint only.
struct LoadsResult {
    std::shared_ptr<const Model> model;
    /// Per joint (limb j, joint k at joint[j][k], 0-based inside; numbered from 1 in the table).
    JointLoads loads;
    /// envelope: per joint (3 j + k) the frequency of the motion of its peak force [Hz]; else empty.
    std::vector<double> frequency;
    /// envelope: the envelope's points below the first natural frequency (the motions run).
    std::vector<EnvelopePoint> points;
    /// envelope: how many of the envelope's points were left out, at or above the first natural
    /// frequency (limit resonance: the rigid model's motion and loads do not hold there), and
    /// that frequency (resonance.known when any was left out).
    int beyond_resonance = 0;
    EnvelopeResonance resonance;
    int worst_limb = 1, worst_joint = 1;  ///< 1-based: the joint of the largest peak force
    /// The CSV's table (io::TableId::loads): limb and joint numbered from 1.
    io::Table table;
    /// The report the command line prints: one line per joint, then the largest.
    std::string text;
};

/// Throws OptionError for a sampling or envelope option out of range, a trajectory with the
/// envelope or none without it.
void validate(const LoadsOptions& options);

/// The loads (of a spatial robot file: runSpatialLoads); a pose out of reach or beyond a limit
/// along the trajectory is an Error (the envelope's motions are within every limit by
/// construction). The envelope's points at or
/// above the first natural frequency (robot files with compliance) are left out, and counted in
/// the text; OptionError("min_frequency") when that leaves none. A stop between envelope points.
[[nodiscard]] LoadsResult runLoads(const LoadsOptions& options, Observer& observer);

/// Throws OptionError("figure") for a spatial robot (the figure is planar): before the run, so
/// that no output is written for a figure that cannot be drawn.
void requireLoadsFigure(const LoadsOptions& options);

/// The robot at the pose of the largest peak force with each joint's force as an arrow (planar
/// robots only), written by writeLoadsFigure (app/outputs.hpp).
[[nodiscard]] render::Figure loadsResultFigure(const LoadsOptions& options, const LoadsResult& result);

}  // namespace nocdyn::app
