// Playing a ground-motion record on a robot (nocdyn shake, and its section of nocdyn reproduce),
// in three steps, each its own function:
//   fit    the record (times the amplitude) fitted to the robot by similitude (shake.hpp,
//          fitRecord), and the replay's memory checked before it is taken;
//   play   the fitted motion played on a plant carrying a payload the controller does not know,
//          by the table controller (shake_control.hpp) or computed torque on a noisy pose sensor
//          (control.hpp); optionally the payload identified first, and the drive iterated;
//   score  the achieved acceleration against the target: RMS and peak errors, spectra in the
//          record's passband, displacement and velocity errors.
// One options struct (ShakeReplayOptions) holds every choice of the replay; its defaults are the
// command's (app::ShakeOptions is this struct and the command's own fields).
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "nocdyn/choice.hpp"
#include "nocdyn/description.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/sim/plant.hpp"
#include "nocdyn/sim/shake.hpp"
#include "nocdyn/sim/shake_control.hpp"

namespace nocdyn {

/// The replay's controller: "table": encoders, accelerometers, estimator, low-gain feedback and
/// acceleration correction (shake_control.hpp); "pose": computed torque on a noisy pose and rate
/// sensor (noise_pose, noise_rate).
enum class ShakeController { table, pose };

inline constexpr std::array<Choice<ShakeController>, 2> kShakeControllers{
    {{ShakeController::table, "table"}, {ShakeController::pose, "pose"}}};
[[nodiscard]] constexpr std::span<const Choice<ShakeController>> choices(ShakeController) { return kShakeControllers; }

/// f_n of the pose controller's error dynamics by default [Hz]: the sensor noise moves the
/// platform by about K_p = (2 pi f_n)^2 times it, the unknown payload by (f / f_n)^2 of the
/// acceleration at frequency f; 30 Hz balances the two on El Centro (measured in README.md).
inline constexpr double kPoseNaturalFrequency = 30.0;
/// f_n of the table controller's pose feedback by default when the payload is identified first
/// [Hz]: the model carries the payload, the feedback holds the drift only.
inline constexpr double kIdentifiedNaturalFrequency = 2.0;

/// Every choice of a replay, in the units a user writes them. The fit's, the table loop's and
/// the sensors' defaults are those of FitOptions, ShakeLoopOptions and TableSensors.
// the fit (fitRecord): time_scale, highpass, margin; the drive-signal iteration
struct ShakeReplayOptions : FitSettings, DriveIterationSettings, TableSensors {
    double amplitude = 1.0;  ///< the record's accelerations times this before the fit
    // --- the plant
    /// nocdyn-rk4 (a 40 s record in seconds), nocdyn, or simbody (the independent check, about
    /// 70 times slower); the caller's factory builds it (playReplay)
    PlantKind plant = PlantKind::nocdyn_rk4;
    double accuracy = 1e-10;    ///< Simbody plant: its integrator's accuracy
    double payload_mass = 0.5;  ///< [kg] at C, on the plant only
    // --- the controller
    ShakeController controller = ShakeController::table;
    /// controller ticks per second [Hz]; none: the table's own (ShakeLoopOptions' 10 kHz on a
    /// planar table, 1 kHz on a hexapod), so that a rate given equal to one default is kept
    std::optional<double> rate;
    /// f_n of the pose feedback [Hz]; none: table 6 (kIdentifiedNaturalFrequency with
    /// identify_payload), pose kPoseNaturalFrequency
    std::optional<double> natural_frequency;
    double acceleration_gain = ShakeLoopOptions{}.acceleration_gain;  ///< table: g per tick
    // the table's sensors (TableSensors): noise_u, accel_noise_density, accel_bandwidth,
    // accel_baseline, no_accelerometer
    double noise_pose = 1e-6;  ///< pose [m, rad]
    double noise_rate = 1e-5;  ///< pose [m/s, rad/s]
    unsigned seed = 1;         ///< sensor noise
    // --- the payload identified before the replay (table controller)
    bool identify_payload = false;
    double excitation_duration = 2.0;  ///< [s] of the payload excitation
    // --- drive-signal iteration (DriveIterationSettings: iterations, iteration_gain,
    // iteration_tolerance), through the drive model's inverse closed loop (shake.hpp correctDrive)
    /// identity, or the inverse of the table controller's closed loop linearised at home on the
    /// controller's model, by its exact derivatives or by central differences (table only)
    DriveModel drive_model = DriveModel::identity;
    /// the linearised loop's plant is the robot carrying the payload (the specimen as weighed)
    bool drive_specimen = false;
    int difference_span = 5;  ///< ticks of the achieved-acceleration difference
};

/// A planar table's controller rate: the one given, else ShakeLoopOptions' default (10 kHz).
[[nodiscard]] inline double planarRate(const ShakeReplayOptions& o) { return o.rate.value_or(ShakeLoopOptions{}.rate); }

/// The plant of a replay, built from the robot it carries (the robot with the payload).
using PlantFactory = std::function<std::unique_ptr<RobotPlant>(const RobotDescription& robot)>;

/// The payload identified before the replay (identify_payload).
struct PayloadIdentification {
    bool done = false;
    PayloadResult estimate;
    LimitUse excitation_use;  ///< of the excitation run (no margin)
};

/// Memory ceiling of one replay [bytes]. The closed loop keeps t, p and p_d of every controller
/// tick (56 bytes; the table controller streams u and tau, the pose controller keeps them, 664
/// bytes a tick), and the scores a few numbers more; a replay whose ticks would hold more than
/// this is refused before it starts, with its size: about 1 MB per second of replay at 10 kHz
/// with the table controller, so about 1 000 s of replay.
inline constexpr double kMaxReplayBytes = 1.0e9;

/// Bytes a replay holds per controller tick (the ceiling's measure).
[[nodiscard]] double replayBytesPerTick(ShakeController controller);

struct ShakeOutcome {
    FittedRecord fit;
    PayloadIdentification payload;
    EstimatorReport estimator;                      ///< table controller only
    double amplitude = 1.0;                         ///< the asked amplitude
    double record_dt = 0.0;                         ///< the record's step [s]
    std::string sensing;                            ///< the sensors, their noise and resolution, in words
    std::vector<double> pass_rms;                   ///< RMS error of each pass (x, else the first driven axis)
    int best_pass = 0;                              ///< the pass kept (0: the first)
    std::string iteration_stop;                     ///< why the iteration stopped
    DriveModel drive_model = DriveModel::identity;  ///< the drive correction's model
    bool drive_specimen = false;                    ///< its loop's plant carries the specimen
    PoseLoopResult loop;  ///< t, p, p_d of the kept pass (u and tau below, at the record's samples)
    /// u and tau at the tick nearest each of fit.t (n values per sample, as many samples as the
    /// loop reached), for shake.csv
    std::vector<double> u_at_samples, tau_at_samples;
    std::array<std::vector<double>, 3> achieved;  ///< [alpha, ax, ay] at fit.t
    std::array<bool, 3> driven{};                 ///< [theta, x, y]
    std::array<ShakeScore, 3> score;              ///< of the driven axes
    double period_min = 0.0, period_max = 0.0;    ///< the passband's periods [s]
    LimitUse achieved_use;                        ///< of the limits (no margin), from the forces and u
    double seconds = 0.0;                         ///< wall time of the first pass of the closed loop [s]
    double margin = 0.0;                          ///< the fit's margin
};

/// The fit: `record` times options.amplitude fitted to `model` (fitRecord), into outcome.fit
/// (with the amplitude, the margin and the driven axes). Throws nocdyn::Error for a non-positive
/// amplitude, a record that does not fit, or a replay that would hold more than kMaxReplayBytes.
void fitReplay(const Model& model, const GroundRecord& record, const ShakeReplayOptions& options,
               ShakeOutcome& outcome);

/// The play: the fitted motion on the plant `make_plant` builds for the robot carrying the
/// payload, the payload identified first when asked, the drive iterated; fills the outcome's
/// passes, loop, achieved accelerations, actuators and sensing. `progress` is called with the
/// time of every tick (it may throw to stop the replay). Throws nocdyn::Error.
void playReplay(const RobotDescription& robot, const ShakeReplayOptions& options, const PlantFactory& make_plant,
                const std::function<void(double)>& progress, ShakeOutcome& outcome);

/// The score: the passband's periods and each driven axis's scores (scoreShake), displacement
/// and velocity errors.
void scoreReplay(const Model& model, const ShakeReplayOptions& options, ShakeOutcome& outcome);

/// fitReplay, playReplay and scoreReplay. Throws nocdyn::Error.
[[nodiscard]] ShakeOutcome runShakeReplay(const RobotDescription& robot, const GroundRecord& record,
                                          const ShakeReplayOptions& options, const PlantFactory& make_plant,
                                          const std::function<void(double)>& progress = {});

}  // namespace nocdyn
