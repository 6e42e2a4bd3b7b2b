// The 3-PRR's dynamics results for `nocdyn reproduce` and the helpers that `control`, `envelope` and
// `simulate` share: plants, closed-loop cases, figures, markdown sections.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "nocdyn/control.hpp"
#include "nocdyn/envelope.hpp"
#include "nocdyn/robot.hpp"
#include "plot.hpp"

namespace nocdyn::cli {

/// "simbody" (when built with the Simbody model) or "nocdyn" (our forward dynamics).
[[nodiscard]] std::string defaultPlantName();
/// A plant built from `robot`. Throws nocdyn::Error for an unknown name or a plant not built in.
[[nodiscard]] std::unique_ptr<control::Plant> makePlant(const std::string& name, const RobotParameters& robot);

/// One closed-loop case.
struct ControlCase {
    std::string controller = "computed-torque";  ///< "computed-torque" or "pd"
    double natural_frequency = 50.0;             ///< f_n of the error dynamics [Hz]
    std::string plant = defaultPlantName();
    double payload_mass = 0.0;     ///< [kg], on the plant's platform only (model mismatch)
    double payload_inertia = 0.0;  ///< [kg m^2]
    control::ClosedLoopOptions loop;
};

/// Runs one case of `trajectory` with the general model of `robot` as the controller's model.
[[nodiscard]] control::ClosedLoopResult runControlCase(const RobotParameters& robot, const PoseTrajectory& trajectory,
                                                       const ControlCase& options);

/// Tracking errors u_d - u per actuator [um] versus time, one panel per run.
[[nodiscard]] Figure trackingErrorFigure(const std::string& title, const std::vector<control::ClosedLoopResult>& runs);

/// Envelope as CSV: axis,frequency,amplitude,limit,limb,kinematic_amplitude,peak_force,peak_stroke
/// (axis 0 theta, 1 x, 2 y; limit 0 stroke (a joint's range), 1 force (an actuator's effort),
/// 2 workspace; limb 1..3): the envelope of the 3-PRR short form, whose actuators are its P joints.
[[nodiscard]] io::Table envelopeTable(const std::vector<EnvelopePoint>& points);
/// Amplitude versus frequency, log axes: one panel for x and y [mm], one for theta [deg].
[[nodiscard]] Figure envelopeFigure(const std::vector<EnvelopePoint>& points, const std::string& robot);

/// Section "Model-based control": for paper1 and paper2, computed torque and PD on the
/// default plant (Simbody when built in), plus computed torque with an unknown 0.5 kg payload;
/// control_<trajectory>.csv and control_<trajectory>_errors.png/.svg in `out`; a markdown table
/// of RMS and peak errors in `summary`.
/// duration: of each closed-loop run [s].
void reproduceControl(const RobotParameters& robot, const std::filesystem::path& out, std::ostream& summary,
                      double duration);

/// Section "Operating envelope": envelope.csv and envelope.png/.svg in `out`; a markdown table
/// of the binding limits, and the paper trajectories checked against it (per-axis amplitude
/// versus the envelope at its frequency, and the combined peak stroke and force).
void reproduceEnvelope(const RobotParameters& robot, const std::filesystem::path& out, std::ostream& summary);

/// Section "Forward dynamics round trip": the inverse-dynamics forces of paper1 and paper2
/// (10 kHz, linear in between) fed to the forward dynamics; max |u - u_d| and pose error.
void reproduceRoundTrip(const RobotParameters& robot, std::ostream& summary);

}  // namespace nocdyn::cli
