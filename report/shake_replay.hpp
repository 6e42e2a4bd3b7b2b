// Playing a ground-motion record on a robot (nocdyn shake, and its section of nocdyn reproduce):
// fit (shake.hpp), closed-loop computed torque on a plant with an unknown payload and sensor
// noise (control.hpp), then the scores, shake.csv, shake.json and the figures.
#pragma once

#include <array>
#include <iosfwd>
#include <string>
#include <vector>

#include "nocdyn/description.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/sim/shake.hpp"
#include "nocdyn/sim/shake_control.hpp"

namespace nocdyn::report {

struct ShakeSettings {
    FitOptions fit;
    /// "nocdyn-rk4" (a 40 s record in seconds), "nocdyn" or "simbody" (the independent check,
    /// about 70 times slower)
    std::string plant = "nocdyn-rk4";
    /// "table": encoders, accelerometers, estimator, low-gain feedback and acceleration correction
    /// (shake_control.hpp); "pose": computed torque on a noisy pose and rate sensor at f_n =
    /// natural_frequency (noise_pose, noise_rate)
    std::string controller = "table";
    ShakeLoopOptions table;  ///< the table controller's gains and sensors (rate and duration unused)
    double amplitude = 1.0;  ///< the record's accelerations times this before the fit (--amplitude)
    bool identify_payload = false;
    double excitation_duration = 2.0;  ///< [s] of the payload excitation
    /// Drive-signal iteration: at most this many passes after the first, each playing the drive
    /// a_drive + gain (a_target - a_achieved) of the last; stops when the RMS error falls by less
    /// than iteration_tolerance (relative) or the drive would leave the limits less half the margin;
    /// the best pass is kept.
    int iterations = 0;
    double iteration_gain = 0.7;
    /// The correction's model of the table (shake.hpp, correctDrive): identity (the correction
    /// above), or the inverse of the table controller's closed loop linearised at home on the
    /// controller's model (the one it knows: nominal, or with the payload identified), by its
    /// exact derivatives or by central differences; table controller only.
    DriveModel drive_model = DriveModel::identity;
    /// The linearised loop's plant is the robot carrying `payload` (the specimen as weighed; the
    /// controller's model does not carry it, or carries its identified estimate) rather than the
    /// controller's model.
    bool drive_specimen = false;
    double iteration_tolerance = 0.02;
    double rate = 10000.0;  ///< controller ticks per second [Hz]
    /// f_n of the error dynamics [Hz]: the sensor noise moves the platform by about K_p = (2 pi
    /// f_n)^2 times it, the unknown payload by (f / f_n)^2 of the acceleration at frequency f;
    /// 30 Hz balances the two on El Centro (measured in README.md)
    double natural_frequency = 30.0;
    Payload payload{0.5, 0.0, Vector2::Zero()};  ///< on the plant only
    double noise_pose = 1e-6;                    ///< [m, rad]
    double noise_rate = 1e-5;                    ///< [m/s, rad/s]
    unsigned seed = 1;
    double accuracy = 1e-10;  ///< Simbody's integrator accuracy
    int difference_span = 5;  ///< ticks of the achieved-acceleration difference
};

/// The payload identified before the replay (--identify-payload).
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
[[nodiscard]] double replayBytesPerTick(const std::string& controller);

struct ShakeOutcome {
    FittedRecord fit;
    PayloadIdentification payload;
    EstimatorReport estimator;                      ///< table controller only
    double amplitude = 1.0;                         ///< the user's --amplitude
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

/// Fits and plays `record` on `robot`. Throws nocdyn::Error.
[[nodiscard]] ShakeOutcome runShake(const RobotDescription& robot, const GroundRecord& record,
                                    const ShakeSettings& settings);

/// shake.csv's table: the record's (scaled) samples (io::TableId::shake), u and tau at the tick
/// nearest each.
[[nodiscard]] io::Table shakeTable(const ShakeOutcome& outcome, const Model& model);

/// shake.json's text: scales, limit use, and per driven axis the scores, every error in percent
/// with "_percent" in its name (rms_error_percent: 100 sqrt(sum e^2 / sum a^2);
/// spectrum_outside_band_percent: of the counted periods, those outside +-10 %), and the spectra.
[[nodiscard]] std::string shakeJson(const ShakeOutcome& outcome);

/// DIR/shake.csv, DIR/shake.json, DIR/shake_acceleration.{png,svg}, DIR/shake_spectrum.{png,svg}.
void writeShakeOutputs(const ShakeOutcome& outcome, const Model& model, const std::string& dir,
                       const std::string& title);

/// The scales, the limit use, the closed loop, then one line per driven axis: RMS error, peak
/// error, share outside the band. with_timing: also the closed loop's wall-clock time (which
/// differs from run to run, so it is left out of files meant to be reproducible).
void printShakeSummary(const ShakeOutcome& outcome, std::ostream& out, bool with_timing = true);

/// The El Centro replay on the paper's prototype, for summary.md of nocdyn reproduce.
void reproduceShake(const std::string& out_dir, std::ostream& summary);

}  // namespace nocdyn::report
