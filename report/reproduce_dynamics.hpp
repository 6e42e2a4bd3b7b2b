// The paper prototype's dynamics results for `nocdyn reproduce` and the helpers that `control`,
// `envelope` and `simulate` share: figures, markdown sections. Every section runs the general
// model (the short form expanded by io).
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "nocdyn/description.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/io/csv.hpp"
#include "plot.hpp"

namespace nocdyn::report {

/// The actuators' limits of a robot whose actuated joints share them (the paper's prototype):
/// the first actuated joint's range (upper - lower, the total stroke) and effort (the peak force).
struct ActuatorLimits {
    double stroke = 0.0;      ///< [m or rad]
    double peak_force = 0.0;  ///< [N or N m]
};
[[nodiscard]] ActuatorLimits actuatorLimits(const RobotDescription& robot);

/// Tracking errors u_d - u per actuator [um] versus time, one panel per run.
/// `notes`: a few words per run added to its panel's title (e.g. "payload unknown to the
/// controller"), so that runs of the same controller and plant are told apart; may be empty.
[[nodiscard]] Figure trackingErrorFigure(const std::string& title, const std::vector<PoseLoopResult>& runs,
                                         const std::vector<std::string>& notes = {});

/// Amplitude versus frequency, log axes: one panel for x and y [mm], one for theta [deg]. With a
/// known resonance, each panel draws the first natural frequency as a vertical line (the band's
/// third bound) and shades the frequencies above it up to the last point.
[[nodiscard]] Figure envelopeFigure(const std::vector<EnvelopePoint>& points, const std::string& robot,
                                    const std::string& reading = "flat = stroke-bound, slope -2 = peak-force-bound",
                                    const EnvelopeResonance& resonance = {});

/// Section "Model-based control": for paper1 and paper2, task-space computed torque and PD
/// (control.hpp) on the default plant (Simbody when built in), plus computed torque with
/// an unknown 0.5 kg payload;
/// control_<trajectory>.csv and control_<trajectory>_errors.png/.svg in `out`; a markdown table
/// of RMS and peak errors in `summary`.
/// duration: of each closed-loop run [s].
void reproduceControl(const RobotDescription& robot, const std::filesystem::path& out, std::ostream& summary,
                      double duration);

/// Section "Operating envelope": envelope.csv and envelope.png/.svg in `out`; a markdown table
/// of the binding limits, and the paper trajectories checked against it (per-axis amplitude
/// versus the envelope at its frequency, and the combined peak stroke and force).
void reproduceEnvelope(const RobotDescription& robot, const std::filesystem::path& out, std::ostream& summary);

/// Section "Forward dynamics round trip": the inverse-dynamics forces of paper1 and paper2
/// (10 kHz, linear in between) fed to the forward dynamics; max |u - u_d| and pose error.
void reproduceRoundTrip(const RobotDescription& robot, std::ostream& summary);

}  // namespace nocdyn::report
