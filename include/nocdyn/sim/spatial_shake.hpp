// A three-component ground motion replayed on a six-DOF table (a hexapod): the planar shake
// (shake.hpp) with the table's x, y, z translations driven and its rotations held at zero.
//
// Fit (fitRecord): the components high-passed, then scaled by similitude as in shake.hpp,
//   a_model,i(t) = A_i a_record,i(L t),  d_model,i = A_i d_i / L^2,   i = x, y, z,
// one time compression L for the three axes (the motion stays synchronous), and one amplitude
// scale A = A_x = A_y = A_z (the motion keeps its shape) unless per-axis scaling is asked. The
// pose is p(t) = home + [d_x, d_y, d_z, 0, 0, 0], each d_i the baseline-corrected double integral
// of its acceleration spline (baselineCorrectedAxis). L is the least L >= 1 at which every leg
// stays within (1 - margin) of its stroke, rate and force (inverse dynamics of the fitted
// motion at each sample, the specimen on the platform); when none up to max_time_scale fits, A < 1 at that L.
// Per-axis scaling: A_i = c min(1, B_i), B_i the largest amplitude at which axis i alone fits,
// c <= 1 the largest common factor at which the three together fit.
//
// Replay (replayRecord): computed torque on the simulated hexapod (spatial::runPoseLoop; the
// controller's model is the plant's, the specimen included), from the target's start; the
// caller chooses the loop's options (the shake command: the forces of the hold's middle state). The
// achieved accelerations are the central second differences of the achieved poses over a span
// of about 0.5 ms, at the record's instants. Scores per translational axis as shake.hpp's
// scoreShake; the rotations' parasitic motion is their peak |angle| over the replay.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "nocdyn/sim/shake.hpp"
#include "nocdyn/sim/spatial_control.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_description.hpp"
#include "nocdyn/spatial_trajectory.hpp"

namespace nocdyn::spatial {

/// The translational axes' names in shake.csv and shake.json, [x, y, z].
inline constexpr std::array<const char*, 3> kShakeAxes = {"ax", "ay", "az"};

/// A record's three components on the table's axes [x, y, z], on one uniform grid [m/s^2].
struct GroundRecord3 {
    double dt = 0.0;
    std::array<std::vector<double>, 3> a;
};

/// The description with a point mass `mass` [kg] at the platform frame's origin added to the
/// platform (its c.o.m. and inertia combined by the parallel-axis theorem). Throws
/// nocdyn::Error for a negative or non-finite mass.
[[nodiscard]] SpatialRobotDescription withSpecimen(SpatialRobotDescription description, double mass);

/// Inverse dynamics of `trajectory` every `step` over [0, duration]: the worst use of any
/// actuator's stroke, rate and force (accumulateLimitUse's ratios, the actuators named by their
/// limb); +infinity when a pose is out of reach or singular.
[[nodiscard]] LimitUse limitUse(const Model& model, const Trajectory& trajectory, double duration, double step,
                                double margin);

struct FittedRecord3 {
    double time_scale = 1.0;                   ///< L
    std::array<double, 3> amplitude{1, 1, 1};  ///< A_x, A_y, A_z
    bool per_axis = false;
    double dt = 0.0;                       ///< record step over L [s]
    std::vector<double> t;                 ///< target instants [s]
    std::array<std::vector<double>, 3> a;  ///< target accelerations at t [m/s^2]
    Trajectory trajectory;                 ///< home + d_model, rotations at home
    LimitUse use;                          ///< of the fitted motion
};

/// Filters, scales and integrates the record (see the header comment). Throws nocdyn::Error
/// for fewer than 4 samples, axes of unequal lengths, a value that is not finite, a robot that
/// is not a full six-DOF one, or a motion that fits at no amplitude above 1e-4.
[[nodiscard]] FittedRecord3 fitRecord(const Model& model, const GroundRecord3& record, const FitOptions& options,
                                      bool per_axis = false);

struct ShakeReplay3 {
    FittedRecord3 fit;
    LoopResult loop;
    std::array<std::vector<double>, 3> achieved;  ///< at fit.t [m/s^2]
    std::array<ShakeScore, 3> score;              ///< x, y, z
    std::array<double, 3> parasitic{};            ///< peak |roll|, |pitch|, |yaw| [rad]
    LimitUse achieved_use;  ///< the loop's strokes, rates (from u) and forces against the full limits
    double period_min = 0.0, period_max = 0.0;  ///< the scored passband [s]
    double seconds = 0.0;                       ///< wall-clock time of the closed loop
};

/// The closed loop of `loop` (its duration set to the fitted motion's) on `model` along the fit,
/// scored (see the header comment). `highpass` is the fit's cutoff [Hz], for the passband.
[[nodiscard]] ShakeReplay3 replayRecord(const Model& model, FittedRecord3 fit, LoopOptions loop, double highpass);

/// Drive-signal iteration (time waveform replication) on x, y, z, the identity drive model
/// (shake.hpp): after the first pass, each pass's drive is d_(i+1) = d_i + g (a_target - a_i)
/// per axis (as a planar table's identity correction), refitted at the target's L within half
/// its margin (driveFitOptions; the iteration stops when the drive would need A < 1), played
/// from the start by the same loop and scored against the target. A pass's error is its worst
/// axis's relative RMS error (the criterion of the pass kept and of the stop): a pass is kept
/// when it is the best so far, and the iteration stops after a pass that improves it by less
/// than `iteration_tolerance` (relative).
struct DriveIterationOptions : DriveIterationSettings {
    FitOptions fit;  ///< the target's (its margin halved for the drive)
};

struct DriveIterationPasses {
    std::vector<std::array<double, 3>> rms;  ///< each pass's relative RMS error [x, y, z] (0: an axis still)
    std::vector<double> worst;               ///< each pass's worst axis's (the criterion)
    int best_pass = 0;                       ///< the pass kept (0: the first)
    std::string stop;                        ///< why the iteration stopped (empty: no iteration)
};

/// The first pass (replayRecord), then up to options.iterations passes of the corrected drive
/// (see DriveIterationOptions); returns the kept pass, scored against the target (its `fit` the
/// target's, its loop's p_d the target's pose at each tick, the drive's kept nowhere). `loop`'s
/// progress is called with the time since the first pass's start, summed over the passes.
/// Throws nocdyn::Error as replayRecord does, or for a gain outside (0, 1].
[[nodiscard]] ShakeReplay3 iterateReplay(const Model& model, FittedRecord3 fit, const LoopOptions& loop,
                                         double highpass, const DriveIterationOptions& options,
                                         DriveIterationPasses& passes);

}  // namespace nocdyn::spatial
