// `frequency-response`: the rigid robot linearised at an operating point (exact derivatives of
// the forward dynamics) and its frequency response H(j w) = C (j w I - A)^-1 B + D from the
// actuator forces to the platform acceleration or the actuator variables; or, closed_loop, the
// shake-table loop (sim/closed_loop.hpp) linearised at rest, from the reference to the achieved
// platform acceleration per axis, with the loop transfer's crossover and phase margin and the
// closed loop's usable band (where |H| stays within [1/A, A]). With compliance declared in the
// robot file, the plant (open loop and closed loop alike) is the lumped compliant model
// (analysis/linearization.hpp: linearizeCompliant), the open loop from each drive's commanded
// position (or force, for a drive of stiffness 0), the closed loop through the drives' set
// points (sim/closed_loop.hpp).
#pragma once

#include <Eigen/Core>

#include <array>
#include <span>
#include <string>
#include <vector>

#include "app/envelope.hpp"
#include "app/observer.hpp"
#include "app/options.hpp"
#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/choice.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

/// Frequencies a response is evaluated at [Hz]: (2 pi f)^2 neither under- nor overflows, and
/// the plant's response y = s^2 (s^2 I - s A22 - A21)^-1 B2 keeps its digits over all of it.
inline constexpr Range kResponseFrequencyRange{1e-9, 1e9, "Hz"};
/// The closed loop's lowest frequency, as a fraction of its natural_frequency.
inline constexpr double kClosedLoopLowestFraction = 1e-5;

/// The plant's model: the lumped compliant one wherever the robot file declares compliance
/// (automatic), the rigid one, or the lumped one (the file must declare compliance).
enum class PlantCompliance { automatic, rigid, lumped };

inline constexpr std::array<Choice<PlantCompliance>, 3> kPlantCompliances{
    {{PlantCompliance::automatic, "auto"}, {PlantCompliance::rigid, "rigid"}, {PlantCompliance::lumped, "lumped"}}};
[[nodiscard]] constexpr std::span<const Choice<PlantCompliance>> choices(PlantCompliance) { return kPlantCompliances; }

struct FrequencyResponseOptions {
    RobotSource robot;
    /// Operating pose [x, y, theta] [m, m, rad]; empty: the robot's home.
    std::vector<double> pose;
    /// Operating pose rate [dx, dy, dtheta] [m/s, m/s, rad/s]; empty: at rest (closed_loop: empty).
    std::vector<double> rate;
    /// acceleration (the platform's, per axis) or actuators (the actuator variables).
    LinearOutput output_kind = LinearOutput::platform_acceleration;
    /// The open-loop plant's model: auto (the compliant one when the robot file declares
    /// joint or drive stiffness or elastic links, else the rigid one), rigid, or lumped (the
    /// compliant lumped model, linearizeCompliant; the file must declare compliance). Its inputs
    /// are then each drive's commanded position (a drive with a stiffness, or locked) or force
    /// (stiffness 0). The closed loop's plant likewise (LoopPlant::lumped: the drives' set points
    /// follow the rigid image of the forces' motion).
    PlantCompliance compliance = PlantCompliance::automatic;
    double min_frequency = 1.0;     ///< f_min [Hz], in kResponseFrequencyRange
    double max_frequency = 1000.0;  ///< f_max [Hz], in kResponseFrequencyRange, above f_min
    int points = 200;               ///< log-spaced frequencies (kPointsRange)
    bool closed_loop = false;
    /// A point mass at C on the plant [kg] (kPayloadMassRange); closed_loop: one the controller's
    /// model does not carry.
    double payload_mass = 0.0;
    double controller_rate = 10000.0;  ///< closed_loop: controller ticks [Hz], above 2 f_max
    double natural_frequency = 6.0;    ///< closed_loop: f_n of the pose feedback [Hz]
    /// closed_loop: the usable band ends where |H| leaves [1/A, A] (as the envelope's third bound;
    /// kAmplificationRange)
    double amplification = kDefaultAmplification;
};

inline constexpr int kMinPoints = 2, kMaxPoints = 100000;

/// One curve of the Bode figure: a channel's (or a loop transfer's) magnitude and phase.
struct BodeCurve {
    std::string label;  ///< "ddx/tau1"; closed loop: "H x" (closed), "L x" (loop transfer)
    std::vector<double> magnitude_db, phase_deg;
    /// The magnitude's unit, output per input: "(m/s^2)/N", "(rad/s^2)/m", "m/(N m)"; closed
    /// loop: "1" (a ratio of like quantities).
    std::string unit;
};

struct FrequencyResponseResult {
    std::string robot;
    std::vector<double> frequency;  ///< [Hz]
    /// The table: f, then per channel <output>_<input><i>_db and _deg, input "tau" (a force) or
    /// "uc" (a commanded drive position, compliant model) (closed loop: per axis
    /// <axis>_db, _deg, _loop_db, _loop_deg), axes in the order x, y, theta.
    std::vector<std::string> columns;
    Eigen::MatrixXd table;  ///< one row per frequency
    /// The summary: each channel's gain at both ends and -3 dB bandwidth (closed loop: also the
    /// crossover and phase margin), lines starting with '#' for the heading.
    std::string summary;
    std::vector<BodeCurve> curves;
    bool closed_loop = false;
    /// closed_loop: the plant was the lumped compliant model
    bool lumped = false;
    /// closed_loop, per axis x, y, theta: the usable band's end [Hz] (NaN: beyond the grid; 0: |H|
    /// is outside [1/A, A] at f_min already), and |H|'s largest value on the grid [dB] and its
    /// frequency [Hz] (shakeLoopBand)
    std::vector<double> band_end, peak_db, peak_frequency;
};

/// Throws OptionError naming the option that breaks its range.
void validate(const FrequencyResponseOptions& options);

[[nodiscard]] FrequencyResponseResult runFrequencyResponse(const FrequencyResponseOptions& options, Observer& observer);

/// The Bode figure (magnitude over phase, log frequency) of a result, for render::renderFigure.
[[nodiscard]] render::Figure bodeFigure(const FrequencyResponseResult& result);

}  // namespace nocdyn::app
