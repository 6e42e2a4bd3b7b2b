// `control`: closed-loop tracking of a pose trajectory by computed torque or PD in the
// platform coordinates (sim/control.hpp), on the Simbody plant generated from the robot file
// (when built in) or nocdyn's own forward dynamics.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "app/observer.hpp"
#include "app/options.hpp"
#include "app/simulate.hpp"
#include "nocdyn/choice.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/sim/control.hpp"
#include "app/plants.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

inline constexpr Range kControllerRateRange{1.0, 1e7, "Hz"};
inline constexpr Range kNaturalFrequencyRange{1e-3, 1e4, "Hz"};

/// What the controller measures: the plant's pose and rate (a pose sensor), or the encoders' u
/// and du with the pose from the direct-kinematics tracker.
enum class ControlMeasure { pose, encoders };

inline constexpr std::array<Choice<ControlMeasure>, 2> kControlMeasures{
    {{ControlMeasure::pose, "pose"}, {ControlMeasure::encoders, "encoders"}}};
[[nodiscard]] constexpr std::span<const Choice<ControlMeasure>> choices(ControlMeasure) { return kControlMeasures; }

struct ControlOptions : SamplingOptions, FeedbackSettings {
    RobotSource robot;
    // the feedback (FeedbackSettings): controller (computed-torque or pd), natural_frequency
    // (kNaturalFrequencyRange)
    PlantKind plant = defaultPlant();  ///< the plant the loop runs on
    /// False: `plant` is the build's default, not the caller's choice; a two-DOF robot, which
    /// the Simbody plant does not take, then runs on nocdyn's (a chosen Simbody plant is refused).
    bool plant_given = true;
    double payload_mass = 0.0;                      ///< [kg], on the plant's platform only (model mismatch)
    double payload_inertia = 0.0;                   ///< about the payload's c.o.m. [kg m^2]
    std::vector<double> payload_com;                ///< [x, y] in the platform frame [m]; empty: at C
    double noise_pose = 0.0;                        ///< pose sensor noise [m and rad]
    double noise_rate = 0.0;                        ///< its rate's [m/s and rad/s]
    double noise_tau = 0.0;                         ///< force measurement noise in the sensors' log [N or N m]
    ControlMeasure measure = ControlMeasure::pose;  ///< a pose sensor or encoders (u, du and the tracker)
    double noise_u = 0.0;                           ///< encoder noise [m or rad] (log, measure encoders)
    double noise_du = 0.0;                          ///< encoder rate noise [m/s or rad/s] (measure encoders)
    unsigned seed = 1;                              ///< noise seed
    bool no_saturation = false;                     ///< do not clip the forces at each joint's effort
    /// Also the sensors' log t,u1..un,tau1..taun (ControlResult::log), for identify.
    bool sensor_log = false;
};

struct ControlResult {
    PoseLoopResult loop;  ///< every tick: reference, pose, errors, u, tau; RMS and peak errors
    /// The closed-loop table (io::TableId::closed_loop columns).
    io::Table table;
    /// With sensor_log: the log as the sensors see it.
    io::Table log;
    /// The report: RMS and peak errors per axis and actuator (what the command line prints).
    std::string text;
    std::string trajectory;  ///< the reference's name
};

/// Throws OptionError naming the option that breaks its range, choices or a combination.
void validate(const ControlOptions& options);

/// Runs the loop; a reference beyond a joint's range or an actuator's effort is warned of (the
/// loop still tries to track it).
[[nodiscard]] ControlResult runControl(const ControlOptions& options, Observer& observer);

/// The actuator tracking errors' figure.
[[nodiscard]] render::Figure trackingFigure(const ControlResult& result);

}  // namespace nocdyn::app
