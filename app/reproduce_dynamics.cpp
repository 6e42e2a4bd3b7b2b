// The paper prototype's dynamics results for `nocdyn reproduce`: round trip, closed-loop control,
// operating envelope, all on the general model.
#include "app/reproduce_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <ostream>
#include <utility>

#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/text.hpp"
#include "app/plants.hpp"
#include "app/reproduce_sections.hpp"
#include "render/envelope_figure.hpp"

namespace nocdyn::app {

using render::AxisUnit;
using render::axisUnit;
using render::envelopeFigure;
using render::Figure;
using render::PlotPanel;
using render::PlotSeries;

ActuatorLimits actuatorLimits(const RobotDescription& robot) {
    for (const LimbDescription& limb : robot.limbs) {
        for (const JointDescription& joint : limb.joints) {
            if (joint.actuated) return {joint.limits.upper - joint.limits.lower, joint.limits.effort};
        }
    }
    throw Error("robot '" + robot.name + "' has no actuated joint");
}

Figure trackingErrorFigure(const std::string& title, const std::vector<PoseLoopResult>& runs,
                           const std::vector<std::string>& notes) {
    Figure figure;
    figure.title = title;
    for (std::size_t r = 0; r < runs.size(); ++r) {
        const PoseLoopResult& run = runs[r];
        PlotPanel panel;
        std::string heading;
        const std::string note = r < notes.size() && !notes[r].empty() ? ", " + notes[r] : std::string();
        heading = text::format("%s on the %s plant%s: RMS error %.3g um", run.controller.c_str(), run.plant.c_str(),
                               note.c_str(), *std::max_element(run.rms_error.begin(), run.rms_error.end()) * 1e6);
        panel.title = heading;
        panel.xlabel = "t [s]";
        double peak = 0.0;
        for (std::size_t k = 0; k < run.t.size(); ++k)
            peak = std::max(peak, (run.u_d[k] - run.u[k]).cwiseAbs().maxCoeff());
        const AxisUnit unit = axisUnit(peak, "m");  // PD errors are tens of um, computed torque's tens of nm
        panel.ylabel = "u_{d,j} - u_j [" + unit.unit + "]";
        for (int j = 0; j < run.actuators; ++j) {
            PlotSeries line;
            line.label = "e_" + std::to_string(j + 1);
            line.x = run.t;
            for (std::size_t k = 0; k < run.t.size(); ++k)
                line.y.push_back((run.u_d[k](j) - run.u[k](j)) * unit.factor);
            line.style = "lines lw 2";
            panel.series.push_back(std::move(line));
        }
        figure.panels.push_back(std::move(panel));
    }
    return figure;
}

namespace {

/// The short form's words for the limits: its actuated joints' range is the stroke and their
/// effort the peak force.
const char* limitWord(EnvelopeLimit limit) {
    switch (limit) {
        case EnvelopeLimit::effort:
            return "force";
        case EnvelopeLimit::workspace:
            return "workspace";
        case EnvelopeLimit::resonance:
            return "resonance";
        default:
            return "stroke";
    }
}

}  // namespace

namespace {

const char* kTrajectories[] = {"paper1", "paper2"};

PoseTrajectory paperTrajectory(int k) { return k == 0 ? paperTrajectory1() : paperTrajectory2(); }

}  // namespace

void reproduceControl(const RobotDescription& robot, FileSink& out, std::ostream& summary, double duration) {
    constexpr double kNaturalFrequency = 50.0;  // [Hz]
    const Model model(robot);
    const PlantKind plant_kind = defaultPlant();
    PoseLoopOptions loop;
    loop.duration = duration;
    const Payload payload{0.5, 1e-3, Vector2::Zero()};
    summary << "## Model-based control (closed loop)\n\n"
            << "Task-space controller (as `nocdyn control`) at " << loop.rate / 1000 << " kHz over " << duration
            << " s, with zero-order hold, pose error critically damped at " << kNaturalFrequency
            << " Hz, each force clipped at its joint's effort (" << actuatorLimits(robot).peak_force << " N), plant: "
            << (plant_kind == PlantKind::simbody ? "the independent Simbody model" : "nocdyn's forward dynamics")
            << ", pose and rate measured from it. Computed torque: A_p^T tau = M_p(p) (ddp_d + K_d e' + K_p e) + "
               "h_p(p, dp); PD: A_p^T tau = M_p(home) (K_p e + K_d e'). The payload case adds "
            << payload.mass << " kg and " << payload.inertia << " kg m^2 at C to the plant's platform only.\n\n"
            << "| trajectory | controller | payload unknown to the controller | RMS error u1, u2, u3 [um] | peak error "
               "[um] | peak pose error x, y [um], theta [urad] | saturated ticks |\n"
            << "| --- | --- | --- | --- | --- | --- | --- |\n";
    for (int k = 0; k < 2; ++k) {
        const PoseTrajectory trajectory = paperTrajectory(k);
        std::vector<PoseLoopResult> runs;
        for (const auto& [law, loaded] : {std::pair<ControlLaw, bool>{ControlLaw::computed_torque, false},
                                          {ControlLaw::pd, false},
                                          {ControlLaw::computed_torque, true}}) {
            PoseController controller(model, law, taskCriticallyDamped(kNaturalFrequency));
            const std::unique_ptr<RobotPlant> plant =
                makePlant(plant_kind, loaded ? withPayload(robot, payload) : robot);
            runs.push_back(runPoseLoop(controller, *plant, trajectory, loop));
            const PoseLoopResult& r = runs.back();
            std::string row;
            row = text::format(
                "| %s | %s | %s | %.4g, %.4g, %.4g | %.4g | %.4g, %.4g, %.4g | %zu |\n", kTrajectories[k], name(law),
                loaded ? "0.5 kg" : "none", r.rms_error[0] * 1e6, r.rms_error[1] * 1e6, r.rms_error[2] * 1e6,
                *std::max_element(r.peak_error.begin(), r.peak_error.end()) * 1e6, r.pose_peak_error(1) * 1e6,
                r.pose_peak_error(2) * 1e6, r.pose_peak_error(0) * 1e6, r.saturated_ticks);
            summary << row;
        }
        const std::string stem = std::string("control_") + kTrajectories[k];
        out.table(stem + ".csv", tables::toTable(runs[0]));
        out.figure(stem + "_errors",
                   trackingErrorFigure(std::string(kTrajectories[k]) + ": actuator tracking errors", runs,
                                       {"no payload", "no payload", "payload unknown to the controller"}));
    }
    summary << "\nFigures: `control_paper1_errors.png`, `control_paper2_errors.png` (panels: computed torque, PD, "
               "computed torque with the unknown payload); CSV of the computed-torque runs: `control_paper{1,2}.csv`. "
               "`nocdyn control --trajectory paper1 [--controller pd] [--payload-mass 0.5 --payload-inertia 1e-3]` "
               "reproduces each row.\n\n";
}

void reproduceEnvelope(const RobotDescription& robot, FileSink& out, std::ostream& summary) {
    const Model model(robot);
    const ActuatorLimits limits = actuatorLimits(robot);
    const auto points = operatingEnvelope(model);
    const EnvelopeResonance resonance = envelopeResonance(model);
    out.table("envelope.csv", tables::toTable(points, resonance));
    out.figure("envelope",
               envelopeFigure(points, robot.name, "flat = stroke-bound, slope -2 = peak-force-bound", resonance));

    summary
        << "## Operating envelope\n\n"
        << "Largest amplitude A of p(t) = A sin(2 pi f t) along one axis about the reference posture, within the "
           "stroke (+-"
        << limits.stroke * 0.5e3 << " mm), the workspace and the peak force (" << limits.peak_force
        << " N), from the inverse dynamics over one period (256 samples), f = 1..100 Hz log-spaced "
           "(`envelope.csv`, `envelope.png`).\n\n"
        << "| axis | stroke-bound amplitude | stroke binds up to [Hz] | force binds from [Hz] | amplitude at 100 Hz | "
           "A(50 Hz) / A(100 Hz) |\n| --- | --- | --- | --- | --- | --- |\n";
    for (const EnvelopeAxis axis : {EnvelopeAxis::x, EnvelopeAxis::y, EnvelopeAxis::theta}) {
        double last_stroke = 0.0, first_force = 0.0, kinematic = 0.0, at100 = 0.0;
        for (const auto& p : points) {
            if (p.axis != axis) continue;
            kinematic = p.kinematic_amplitude;
            if (p.limit != EnvelopeLimit::effort && p.limit != EnvelopeLimit::resonance) last_stroke = p.frequency;
            if (p.limit == EnvelopeLimit::effort && first_force == 0.0) first_force = p.frequency;
            at100 = p.amplitude;
        }
        const double ratio =
            maximumAmplitude(model, axis, 50.0).amplitude / maximumAmplitude(model, axis, 100.0).amplitude;
        const bool angle = axis == EnvelopeAxis::theta;
        const double scale = angle ? 180.0 / std::numbers::pi : 1e3;
        const char* unit = angle ? "deg" : "mm";
        std::string row;
        row = text::format("| %s | %.4g %s | %.3g | %.3g | %.4g %s | %.3f |\n", axisName(axis), kinematic * scale, unit,
                           last_stroke, first_force, at100 * scale, unit, ratio);
        summary << row;
    }
    summary << "\nBelow the crossover the stroke binds (amplitude independent of f); above it the peak force binds and "
               "the amplitude falls as 1/f^2 (ratio 4 per octave).\n\n"
            << "Paper trajectories against the envelope (each harmonic's amplitude over the envelope at its frequency; "
               "the combined motion's peak stroke and force from the inverse dynamics over 0.2 s):\n\n"
            << "| trajectory | axis | amplitude | frequency [Hz] | envelope | fraction of envelope |\n"
            << "| --- | --- | --- | --- | --- | --- |\n";
    for (int k = 0; k < 2; ++k) {
        const PoseTrajectory trajectory = paperTrajectory(k);
        const AxisMotion* motions[] = {&trajectory.theta, &trajectory.x, &trajectory.y};
        for (const EnvelopeAxis axis : {EnvelopeAxis::x, EnvelopeAxis::y, EnvelopeAxis::theta}) {
            const bool angle = axis == EnvelopeAxis::theta;
            const double scale = angle ? 180.0 / std::numbers::pi : 1e3;
            for (const Harmonic& h : motions[static_cast<int>(axis)]->harmonics) {
                const auto p = maximumAmplitude(model, axis, h.frequency);
                std::string row;
                row = text::format("| %s | %s | %.4g %s | %.4g | %.4g %s (%s-bound) | %.1f %% |\n", kTrajectories[k],
                                   axisName(axis), std::abs(h.amplitude) * scale, angle ? "deg" : "mm", h.frequency,
                                   p.amplitude * scale, angle ? "deg" : "mm", limitWord(p.limit),
                                   100.0 * std::abs(h.amplitude) / p.amplitude);
                summary << row;
            }
        }
        const auto series = sampleInverseDynamics(model, trajectory, sampleTimes(0.2, 10000.0), LimitPolicy::record);
        double stroke = 0.0, force = 0.0;
        for (std::size_t a = 0; a < series.summary.peak_u.size(); ++a) {
            stroke = std::max(stroke, series.summary.peak_u[a]);
            force = std::max(force, series.summary.peak_tau[a]);
        }
        std::string row;
        row = text::format(
            "| %s | combined | peak abs(u) %.3f mm = %.1f %% of half stroke | | peak abs(tau) %.2f N | %.1f "
            "%% of peak force |\n",
            kTrajectories[k], stroke * 1e3, 100.0 * stroke / (0.5 * limits.stroke), force,
            100.0 * force / limits.peak_force);
        summary << row;
    }
    summary << "\n";
}

void reproduceRoundTrip(const RobotDescription& robot, std::ostream& summary) {
    const Model model(robot);
    summary
        << "## Forward dynamics round trip\n\n"
        << "Inverse-dynamics forces of each paper trajectory sampled at 10 kHz (linear in between) drive the forward "
           "dynamics (Boost.Odeint Dormand-Prince 5(4), tolerances 1e-12 abs, 1e-10 rel) from the trajectory's initial "
           "state for 0.2 s.\n\n"
        << "| trajectory | max abs(u - u_d) [m] | max pose error x, y [m] | max theta error [rad] | steps |\n"
        << "| --- | --- | --- | --- | --- |\n";
    for (int k = 0; k < 2; ++k) {
        const PoseTrajectory trajectory = paperTrajectory(k);
        const auto series = sampleInverseDynamics(model, trajectory, sampleTimes(0.2, 10000.0), LimitPolicy::record);
        std::vector<double> times;
        std::vector<ActuatorVector> tau;
        for (const InverseDynamicsSample& s : series.samples) {
            times.push_back(s.t);
            tau.push_back(s.tau);
        }
        Simulator simulator(model);
        const InverseDynamicsSample& first = series.samples.front();
        if (const Status status = simulator.reset(first.p, first.dp, first.t); !status) {
            throw Error("round trip: " + describe(status, model));
        }
        simulator.setForces(ForceSignal(times, tau, Interpolation::linear, "round trip"));
        double u_error = 0.0, xy_error = 0.0, theta_error = 0.0;
        for (const InverseDynamicsSample& s : series.samples) {
            if (const Status status = simulator.advance(s.t - simulator.time()); !status) {
                throw Error("round trip: t = " + std::to_string(simulator.time()) + " s: " + describe(status, model));
            }
            u_error = std::max(u_error, (simulator.u() - s.u).cwiseAbs().maxCoeff());
            xy_error = std::max(xy_error, (simulator.pose() - s.p).tail<2>().cwiseAbs().maxCoeff());
            theta_error = std::max(theta_error, std::abs(simulator.pose()(0) - s.p(0)));
        }
        std::string row;
        row = text::format("| %s | %.3g | %.3g | %.3g | %zu |\n", kTrajectories[k], u_error, xy_error, theta_error,
                           simulator.acceptedSteps());
        summary << row;
    }
    summary
        << "\nThe error comes from the linear interpolation of the forces; it shrinks as the square of the sampling "
           "interval (test ForwardDynamics.RoundTripErrorIsSecondOrderInForceSampling).\n\n";
}

}  // namespace nocdyn::app
