// Sections of `nocdyn reproduce` (reproduce_sections.hpp): the paper's trajectories (Section V,
// Figs. 5 and 6), their animations, the workspace, the El Centro replay and the example robots
// against the engines.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <sstream>

#include "app/plants.hpp"
#include "app/reproduce_dynamics.hpp"
#include "app/reproduce_sections.hpp"
#include "app/shake_outputs.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/description.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/analysis/workspace.hpp"
#include "nocdyn/sim/shake_replay.hpp"
#include "render/animation.hpp"
#include "render/plot.hpp"
#include "render/workspace_figure.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/text.hpp"
#ifdef NOCDYN_HAS_ENGINES
#include "nocdyn/sim/control.hpp"
#include "nocdyn/validation/agreement.hpp"
#include "nocdyn/validation/simbody_plant.hpp"
#endif

namespace nocdyn::app {

using render::AxisUnit;
using render::axisUnit;
using render::Figure;
using render::PlotPanel;
using render::PlotSeries;

/// The El Centro record compiled in (generated from data/elcentro_1940_ns.AT2).
extern const char* const kElCentroAt2;

namespace {

constexpr double kPaperDuration = 0.2;  // s, as in the paper's figures
constexpr double kPaperRate = 10000.0;  // Hz

/// Motor displacements [mm] or forces [N] of our model, with an engine's curves overlaid
/// (dashed) when given.
PlotPanel jointPanel(const InverseDynamicsSeries& series, bool forces, const std::string& engine = {},
                     const std::vector<Eigen::VectorXd>* engine_values = nullptr) {
    PlotPanel panel;
    panel.title = forces ? "(a) Motor forces" : "(a) Motor displacements";
    panel.xlabel = "t [s]";
    panel.ylabel = forces ? "{/Symbol t}_j [N]" : "u_j [mm]";
    const double scale = forces ? 1.0 : 1e3;
    const std::string symbol = forces ? "{/Symbol t}_" : "u_";
    std::vector<double> t;
    t.reserve(series.samples.size());
    for (const InverseDynamicsSample& s : series.samples) t.push_back(s.t);
    for (int j = 0; j < 3; ++j) {
        PlotSeries line;
        line.label = symbol + std::to_string(j + 1) + (engine_values ? " model" : "");
        line.x = t;
        for (const InverseDynamicsSample& s : series.samples) line.y.push_back(scale * (forces ? s.tau(j) : s.u(j)));
        line.style = "lines lw 2 lc " + std::to_string(j + 1);
        panel.series.push_back(std::move(line));
        if (!engine_values) continue;
        PlotSeries other;
        other.label = symbol;
        other.label.append(std::to_string(j + 1)).append(" ").append(engine);
        other.x = t;
        for (const auto& value : *engine_values) other.y.push_back(scale * value(j));
        other.style = "lines dt 2 lw 3 lc " + std::to_string(j + 4);
        panel.series.push_back(std::move(other));
    }
    return panel;
}

#ifdef NOCDYN_HAS_ENGINES
/// engine - model, per actuator, in a unit fitted to the largest difference (axisUnit).
PlotPanel differencePanel(const InverseDynamicsSeries& series, bool forces, const std::string& engine,
                          const std::vector<Eigen::VectorXd>& engine_values) {
    PlotPanel panel;
    panel.title = "(b) " + engine + " minus model";
    panel.xlabel = "t [s]";
    const auto difference = [&](std::size_t k, int j) {
        const InverseDynamicsSample& s = series.samples[k];
        return engine_values[k](j) - (forces ? s.tau(j) : s.u(j));
    };
    double peak = 0.0;
    for (std::size_t k = 0; k < series.samples.size(); ++k) {
        for (int j = 0; j < 3; ++j) peak = std::max(peak, std::abs(difference(k, j)));
    }
    const AxisUnit unit = axisUnit(peak, forces ? "N" : "m");
    panel.ylabel = (forces ? "{/Symbol Dt}_j [" : "{/Symbol D}u_j [") + unit.unit + "]";
    for (int j = 0; j < 3; ++j) {
        PlotSeries line;
        line.label = (forces ? "{/Symbol Dt}_" : "{/Symbol D}u_") + std::to_string(j + 1);
        for (std::size_t k = 0; k < series.samples.size(); ++k) {
            line.x.push_back(series.samples[k].t);
            line.y.push_back(unit.factor * difference(k, j));
        }
        line.style = "lines lw 1 lc " + std::to_string(j + 1);
        panel.series.push_back(std::move(line));
    }
    return panel;
}
#endif  // NOCDYN_HAS_ENGINES

}  // namespace

void reproduceTrajectories(const RobotDescription& robot, FileSink& out, std::ostream& summary) {
    const Model model(robot);
    const ActuatorLimits limits = actuatorLimits(robot);
    summary << "## Paper trajectories 1 and 2 (eqs. 33-34): inverse dynamics\n\n"
            << "Sampled over " << kPaperDuration << " s at " << kPaperRate / 1000
            << " kHz. Actuator limits: total stroke " << limits.stroke * 1e3 << " mm (+-" << limits.stroke * 0.5e3
            << " mm about the reference posture), peak force " << limits.peak_force << " N.\n\n"
            << "| trajectory | actuator | u range [mm] | peak abs(u) / half stroke | peak abs(tau) [N] | peak abs(tau) "
               "/ peak force |\n"
            << "| --- | --- | --- | --- | --- | --- |\n";
    const auto times = sampleTimes(kPaperDuration, kPaperRate);
#ifdef NOCDYN_HAS_ENGINES
    std::ostringstream agreement;
    double worst_abs = 0.0, worst_rel = 0.0;
#endif
    struct Case {
        const char* name;
        PoseTrajectory trajectory;
        const char* figure;
    };
    for (const Case& c : {Case{"paper1", paperTrajectory1(), "Fig. 5"}, Case{"paper2", paperTrajectory2(), "Fig. 6"}}) {
        const auto series = sampleInverseDynamics(model, c.trajectory, times, LimitPolicy::record);
        out.table(std::string(c.name) + ".csv", tables::toTable(series, model.actuators));
        Figure displacements{std::string(c.name) + ": motor displacements (cf. the paper's " + c.figure + "a)", {}};
        Figure forces{std::string(c.name) + ": motor forces (cf. the paper's " + c.figure + "b)", {}};
#ifdef NOCDYN_HAS_ENGINES
        // The paper's figures overlay ADAMS; ours overlay Simbody, with their difference.
        const validation::EngineComparison comparison = validation::compareWithEngines(robot, c.trajectory, times);
        out.table(std::string(c.name) + "_validation.csv", validation::toTable(comparison));
        std::vector<Eigen::VectorXd> simbody_u, simbody_tau;
        for (const validation::MechanismSample& s : comparison.simbody) {
            simbody_u.push_back(s.u);
            simbody_tau.push_back(s.tau);
        }
        displacements.panels = {jointPanel(series, false, "Simbody", &simbody_u),
                                differencePanel(series, false, "Simbody", simbody_u)};
        forces.panels = {jointPanel(series, true, "Simbody", &simbody_tau),
                         differencePanel(series, true, "Simbody", simbody_tau)};
        agreement << "### " << c.name << "\n\n" << validation::agreementTable(comparison) << "\n";
        for (const validation::EngineAgreement* a : {&comparison.simbody_agreement, &comparison.mujoco_agreement}) {
            for (std::size_t j = 0; j < a->max_abs.size(); ++j) {
                worst_abs = std::max(worst_abs, a->max_abs[j]);
                worst_rel = std::max(worst_rel, a->max_rel_peak[j]);
            }
        }
#else
        displacements.panels = {jointPanel(series, false)};
        forces.panels = {jointPanel(series, true)};
#endif
        out.figure(std::string(c.name) + "_displacements", displacements);
        out.figure(std::string(c.name) + "_forces", forces);
        for (int j = 0; j < 3; ++j) {
            double lo = 0.0, hi = 0.0;
            for (const InverseDynamicsSample& s : series.samples) {
                lo = std::min(lo, s.u(j));
                hi = std::max(hi, s.u(j));
            }
            const double peak_stroke = series.summary.peak_u[static_cast<std::size_t>(j)];
            const double peak_force = series.summary.peak_tau[static_cast<std::size_t>(j)];
            std::string row;
            row = text::format("| %s | %d | %+.3f .. %+.3f | %.1f %% | %.2f | %.1f %% |\n", c.name, j + 1, lo * 1e3,
                               hi * 1e3, 100.0 * peak_stroke / (0.5 * limits.stroke), peak_force,
                               100.0 * peak_force / limits.peak_force);
            summary << row;
        }
        for (const std::string& violation : series.summary.limit_violations)
            summary << "\nLimit exceeded: " << violation << "\n";
    }
    summary
        << "\nFiles: `paper1.csv`, `paper2.csv` (columns t,x,y,theta,u1..u3,du1..du3,ddu1..ddu3,tau1..tau3,kinetic);"
        << " figures `paper{1,2}_displacements.{png,svg}` and `paper{1,2}_forces.{png,svg}`.\n\n";
#ifdef NOCDYN_HAS_ENGINES
    std::string line;
    line = text::format(
        "Largest force difference from either engine: %.3e N, %.3e of the peak force of the trajectory.\n\n", worst_abs,
        worst_rel);
    summary << "## Validation against independent multibody engines\n\n"
            << "The same robot file and trajectories were built in Simbody (the reference, as ADAMS was for the paper)"
            << " and MuJoCo, which never call nocdyn's kinematics or dynamics; the platform pose is prescribed and each"
            << " engine finds the slider motion and the actuator forces. Where the paper found its curves"
            << " \"apparently in agreement\", the measured agreement at all " << times.size()
            << " samples of each trajectory is:\n\n"
            << line << agreement.str()
            << "Figures overlay the Simbody curves (dashed) on the model's and plot their difference;"
            << " `paper{1,2}_validation.csv` hold every engine's u and tau.\n\n";
#endif
}

#ifdef NOCDYN_HAS_ENGINES
void reproduceExampleRobots(FileSink& out, std::ostream& summary, double closed_loop_duration) {
    constexpr double kExampleRate = 2000.0;  // [Hz]: both engines assemble every sample
    const auto times = sampleTimes(kPaperDuration, kExampleRate);
    summary << "## Other architectures: the example robots against both engines\n\n"
            << "The general model (any limbs of three R/P joints, any actuated joints) on the example robots of"
            << " `robots/`, along the paper's trajectory 1 over " << kPaperDuration << " s at " << kExampleRate / 1000
            << " kHz; Simbody and MuJoCo models generated from the same files (loops closed at a revolute joint)."
            << " The 4-RRR has four actuators: its forces are the minimum-norm ones.\n\n"
            << "| robot | limbs | actuators | peak abs(tau) [N or N m] | Simbody: max diff / peak | MuJoCo: max diff / "
               "peak |\n"
            << "| --- | --- | --- | --- | --- | --- |\n";
    std::string line;
    for (const char* name : {"3-rrr", "3-rpr", "4-rrr"}) {
        const RobotDescription robot = io::exampleRobot(name);
        const validation::EngineComparison c = validation::compareWithEngines(robot, paperTrajectory1(), times);
        out.table(std::string("example_") + name + "_validation.csv", validation::toTable(c));
        std::string types;
        for (const LimbDescription& limb : robot.limbs) {
            if (!types.empty()) types += ' ';
            types += limb.type();
        }
        double peak = 0.0;
        for (double v : c.ours.summary.peak_tau) peak = std::max(peak, v);
        line = text::format("| %s | %s | %d | %.4g | %.2e | %.2e |\n", name, types.c_str(), c.actuators, peak,
                            c.simbody_agreement.worstRelative(), c.mujoco_agreement.worstRelative());
        summary << line;
    }
    summary << "\nFiles: `example_{3-rrr,3-rpr,4-rrr}_validation.csv` (ours and both engines' u and tau at every"
            << " sample).\n\n";

    // closed loop on each robot's Simbody plant (control.hpp)
    constexpr double kNaturalFrequency = 50.0;  // [Hz]
    const Payload payload{0.3, 2e-4, {0.01, -0.005}};
    summary
        << "### Closed-loop tracking of the example robots\n\n"
        << "Task-space control along trajectory 1 for " << closed_loop_duration << " s at 10 kHz (forces held between"
        << " ticks), error dynamics critically damped at " << kNaturalFrequency << " Hz, on the Simbody plant"
        << " generated from each robot file (pose and rate measured from it); forces clipped at each joint's"
        << " effort; minimum-norm forces on the 4-RRR. Peak pose error over the run, x and y [um], theta [urad]:\n\n"
        << "| robot | computed torque | PD | computed torque, unknown payload " << payload.mass
        << " kg at (10, -5) mm | saturated ticks |\n| --- | --- | --- | --- | --- |\n";
    PoseLoopOptions loop;
    loop.duration = closed_loop_duration;
    for (const char* name : {"3-rrr", "3-rpr", "4-rrr"}) {
        const RobotDescription robot = io::exampleRobot(name);
        const Model model(robot);
        const auto peak = [&](ControlLaw law, bool with_payload, std::size_t& saturated) {
            PoseController controller(model, law, taskCriticallyDamped(kNaturalFrequency));
            validation::SimbodyPlant plant(with_payload ? withPayload(robot, payload) : robot);
            const PoseLoopResult r = runPoseLoop(controller, plant, paperTrajectory1(), loop);
            saturated += r.saturated_ticks;
            std::string cell;
            cell = text::format("%.3g, %.3g, %.3g", r.pose_peak_error(1) * 1e6, r.pose_peak_error(2) * 1e6,
                                r.pose_peak_error(0) * 1e6);
            return std::string(cell);
        };
        std::size_t saturated = 0;
        const std::string ct = peak(ControlLaw::computed_torque, false, saturated);
        const std::string pd = peak(ControlLaw::pd, false, saturated);
        const std::string loaded = peak(ControlLaw::computed_torque, true, saturated);
        summary << "| " << name << " | " << ct << " | " << pd << " | " << loaded << " | " << saturated << " |\n";
    }
    summary << "\n`nocdyn control --robot robots/NAME.yaml --trajectory paper1 [--controller pd]"
            << " [--payload-mass 0.3 --payload-inertia 2e-4 --payload-com 0.01 -0.005]` reproduces each cell.\n\n";
}
#endif

void reproduceWorkspace(const RobotDescription& robot, FileSink& out, std::ostream& summary) {
    const Model model(robot);
    const WorkspaceMap map = workspaceMap(model, {0.0, 301});
    std::vector<PlotSeries> paths;
    // trajectory 1 wide and light, trajectory 2 dashed on top: where the paths of C coincide,
    // both stay visible
    const char* styles[] = {"lines lw 7 lc rgb '#a1d99b'", "lines lw 2 dt 2 lc rgb '#6a3d9a'"};
    double peak_theta = 0.0;
    for (int k = 0; k < 2; ++k) {
        const PoseTrajectory trajectory = k == 0 ? paperTrajectory1() : paperTrajectory2();
        PlotSeries path{
            std::string("C along trajectory ") + (k == 0 ? "1 (wide, under 2)" : "2 (dashed)") + ", theta varies",
            {},
            {},
            styles[k]};
        for (const double t : sampleTimes(kPaperDuration, 2000.0)) {
            Pose p, dp, ddp;
            trajectory.evaluate(t, p, dp, ddp);
            path.x.push_back(p(1));
            path.y.push_back(p(2));
            peak_theta = std::max(peak_theta, std::abs(p(0)));
        }
        paths.push_back(std::move(path));
    }
    out.figure("workspace", render::workspaceFigure(map, model, paths));
    std::string line;
    line = text::format(" The trajectories turn the platform by up to %.3g deg as they go.\n\n",
                        peak_theta * 180.0 / std::numbers::pi);
    summary << "## Workspace\n\n"
            << render::workspaceSummary(map) << line
            << "`workspace.{png,svg}`: the outline of that region, the singularity curves where they fall in the"
            << " picture, and the paths of C along the paper's trajectories.\n\n";
}

void reproduceAnimations(FileSink& out, std::ostream& summary) {
    const Model model(io::exampleRobot("paper-3prr"));
    summary << "## Animations\n\n";
    for (const auto& [name, trajectory] :
         {std::pair<std::string, PoseTrajectory>{"paper1", paperTrajectory1()}, {"paper2", paperTrajectory2()}}) {
        const render::MotionSamples motion = render::motionFromTrajectory(model, trajectory, 0.2, 10000.0);
        const std::string file = name + "_animation.html";
        out.text(file, render::animationPage(model, motion, render::AnimationOptions{}));
        summary << "- `" << file << "`: the robot along trajectory " << name.back()
                << " (0.2 s at 10 kHz), with its actuator forces and the plots of u and tau; open it in any browser.\n";
    }
    summary << "\n`nocdyn animate --trajectory paper1 --out paper1_animation.html` writes the same page.\n\n";
}

void reproduceShake(FileSink& out, std::ostream& summary) {
    summary << "## Earthquake record: El Centro 1940 N-S on the prototype\n\n";
    const io::GroundMotionRecord record = io::parseAt2(kElCentroAt2, "data/elcentro_1940_ns.AT2");
    // the strong part only keeps the replay short
    constexpr double kWindow = 3.0;  // [s] of record time: the onset and the peak (2.1 s)
    GroundRecord r;
    r.dt = record.dt;
    const auto n = std::min(record.acceleration.size(), static_cast<std::size_t>(kWindow / record.dt) + 1);
    r.ax.assign(record.acceleration.begin(), record.acceleration.begin() + static_cast<std::ptrdiff_t>(n));
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    ShakeReplayOptions replay;
    // nocdyn's own plant keeps the replay within seconds (and under the sanitizers); `nocdyn shake`
    // plays on nocdyn's RK4 plant (nocdyn-rk4) by default, which scores the same motion alike
    replay.plant = PlantKind::nocdyn;
    // the pose-sensor controller this section has always described
    replay.controller = ShakeController::pose;
    const ShakeOutcome outcome = runShakeReplay(robot, r, replay, [&](const RobotDescription& plant_robot) {
        return makePlant(replay.plant, plant_robot, replay.accuracy);
    });
    shakeFiles(outcome, Model(robot), "elcentro", "El Centro 1940 N-S, x", out);
    std::ostringstream text;
    printShakeSummary(outcome, text, false);
    // the wall-clock time differs from run to run: on the console only, not in summary.md
    std::cout << "El Centro replay: " << outcome.loop.t.back() << " s of motion in " << outcome.seconds
              << " s of wall-clock time\n";
    summary << "The first " << kWindow << " s of the record along x, high-passed at " << replay.highpass
            << " Hz (zero-phase Butterworth, order " << kHighPassOrder
            << " run forward and backward), scaled in time to fit the actuators with a " << 100.0 * replay.margin
            << " % margin, then tracked by computed torque at " << planarRate(replay) / 1000.0
            << " kHz (f_n = " << kPoseNaturalFrequency
            << " Hz) on nocdyn's own forward dynamics (`--plant nocdyn`; `nocdyn shake` plays on its RK4 plant,"
            << " `nocdyn-rk4`, by default, and `--plant simbody` on the independent Simbody model) carrying a "
            << replay.payload_mass << " kg payload the controller does not know, with pose noise " << replay.noise_pose
            << " m (rad) and rate noise " << replay.noise_rate << " m/s (rad/s):\n\n```\n"
            << text.str() << "```\n\n"
            << "Files: `elcentro/shake.csv`, `elcentro/shake.json`, `elcentro/shake_acceleration.{png,svg}`,"
            << " `elcentro/shake_spectrum.{png,svg}`. `nocdyn shake --robot robots/paper-3prr-general.yaml --record"
            << " data/elcentro_1940_ns.AT2 --window " << kWindow << " --plant nocdyn --controller pose` reproduces"
            << " them (the pose-sensor controller; `nocdyn shake`'s default is the table controller).\n\n";
}

}  // namespace nocdyn::app
