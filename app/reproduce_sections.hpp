// The sections of `nocdyn reproduce` (app/reproduce.hpp runs them in order): each hands its files
// to `out` (named in the output folder) and writes its markdown section to `summary`, on the paper's prototype unless
// it says otherwise. Deterministic (fixed seeds); the wall-clock times go to the console only.
#pragma once

#include <iosfwd>

#include "app/outputs.hpp"
#include "nocdyn/description.hpp"

namespace nocdyn::app {

/// Both paper trajectories: CSV, figures in the spirit of Figs. 5 and 6 (with the engines'
/// curves when built in), and the peak stroke and force against the actuator limits.
void reproduceTrajectories(const RobotDescription& robot, FileSink& out, std::ostream& summary);

/// `stem`.html of the paper's trajectories 1 and 2 on the paper's robot (0.2 s at 10 kHz), and a
/// paragraph naming them.
void reproduceAnimations(FileSink& out, std::ostream& summary);

/// "Forward dynamics round trip": the inverse-dynamics forces of paper1 and paper2 (10 kHz,
/// linear in between) fed to the forward dynamics; max |u - u_d| and pose error.
void reproduceRoundTrip(const RobotDescription& robot, std::ostream& summary);

/// "Model-based control": for paper1 and paper2, task-space computed torque and PD (control.hpp)
/// on the default plant (Simbody when built in), plus computed torque with an unknown 0.5 kg
/// payload; control_<trajectory>.csv and control_<trajectory>_errors.png/.svg; a markdown table of
/// RMS and peak errors. duration: of each closed-loop run [s].
void reproduceControl(const RobotDescription& robot, FileSink& out, std::ostream& summary, double duration);

/// "Operating envelope": envelope.csv and envelope.png/.svg; a markdown table of the binding
/// limits, and the paper trajectories checked against it (per-axis amplitude versus the envelope
/// at its frequency, and the combined peak stroke and force).
void reproduceEnvelope(const RobotDescription& robot, FileSink& out, std::ostream& summary);

/// The prototype's workspace at theta = 0 with the paper's trajectories' paths of C over it.
void reproduceWorkspace(const RobotDescription& robot, FileSink& out, std::ostream& summary);

/// The El Centro replay on the paper's prototype (the general form), into out/elcentro.
void reproduceShake(FileSink& out, std::ostream& summary);

#ifdef NOCDYN_HAS_ENGINES
/// The example robots of other architectures along the paper's trajectory 1, our general model
/// against both engines built from the same file, and closed loops on their Simbody plants.
void reproduceExampleRobots(FileSink& out, std::ostream& summary, double closed_loop_duration);
#endif

/// "Identification experiment": the payload identification of the paper's prototype, simulated
/// end to end on the Simbody plant generated from its robot file (designed excitation, with and
/// without slider friction unknown to the robot file; the paper's trajectories 1 and 2 as the
/// naive baseline), each for `duration` seconds of data at 10 kHz; identification/*.csv and
/// identification/forces.png/.svg.
void reproduceIdentification(FileSink& out, std::ostream& summary, double duration);

}  // namespace nocdyn::app
