// Section "Identification experiment" of `nocdyn reproduce` (reproduce_identification.hpp): a
// payload bolted to the prototype's platform, shaken under computed-torque control along a
// designed excitation on the Simbody plant, read from the encoders and force sensors, and
// identified (identification.hpp), with the paper's trajectories as the naive baseline.
#include "app/reproduce_sections.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "nocdyn/error.hpp"
#include "nocdyn/sim/excitation.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/sim/shake.hpp"
#include "nocdyn/text.hpp"
#include "app/plants.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

using render::AxisUnit;
using render::axisUnit;
using render::Figure;
using render::PlotPanel;
using render::PlotSeries;

namespace {

constexpr double kRate = 1e4;               // controller and logger [Hz]
constexpr double kNaturalFrequency = 50.0;  // of the computed-torque error dynamics [Hz]
constexpr double kNoiseU = 1e-6;            // encoder noise [m RMS]
constexpr double kNoiseTau = 0.5;           // force-sensor noise [N RMS]
constexpr double kDamping = 20.0;           // plant's slider viscous damping [N s/m]
constexpr double kFriction = 2.0;           // plant's slider Coulomb friction [N]
constexpr double kPeriod = 0.2;             // the excitation's base period (5 Hz) [s]
constexpr int kDecimation = 10;             // every 10th sample in the CSV copies
constexpr unsigned kSeed = 1;
// the goal: the best published payload identification (2 % on inertia), halved
constexpr double kGoalMass = 0.005, kGoalCom = 2e-4, kGoalInertia = 0.01;

/// The payload on the plant, unknown to the controller: 0.5 kg at (12, -7) mm, 8e-4 kg m^2.
Payload truth() { return {0.5, 8e-4, Vector2(0.012, -0.007)}; }
/// What the excitation is designed with (the effort it must leave room for): a rough guess.
Payload guess() { return {0.5, 1e-3, Vector2::Zero()}; }

struct Case {
    std::string key, title;
    PoseTrajectory trajectory;
    double condition = 0.0;  // of the column-scaled stacked regressor over one period (design)
    bool friction = false;   // slider friction in the plant, identified alongside
};

struct Outcome {
    std::optional<PayloadResult> result;
    std::string failure;  // why there is no result
    std::string plant;
    Vector3 peak_error = Vector3::Zero();  // tracking [rad, m, m]
};

io::Table decimated(const io::Table& table) {
    io::Table out;
    out.columns = table.columns;
    for (std::size_t k = 0; k < table.rows.size(); k += kDecimation) out.rows.push_back(table.rows[k]);
    return out;
}

/// Held-out forces: t, tau1..taun measured, tau1..taun predicted (every kDecimation-th sample).
io::Table forcesTable(const FitReport& fit) {
    io::Table table;
    const auto n = fit.measured.cols();
    table.columns = io::columnNames(io::TableId::held_out_forces, {.actuators = static_cast<int>(n)});
    for (std::size_t k = 0; k < fit.t.size(); k += kDecimation) {
        const auto kk = static_cast<Eigen::Index>(k);
        std::vector<double> row{fit.t[k]};
        for (Eigen::Index a = 0; a < n; ++a) row.push_back(fit.measured(kk, a));
        for (Eigen::Index a = 0; a < n; ++a) row.push_back(fit.predicted(kk, a));
        table.rows.push_back(std::move(row));
    }
    return table;
}

/// One experiment: closed loop on the plant (payload, and friction when asked), the sensors'
/// log, the identification. Hands over KEY_log.csv and KEY_forces.csv in `folder`.
Outcome runCase(const RobotDescription& robot, const Model& model, const Case& c, double duration,
                const std::string& folder, FileSink& out) {
    Outcome outcome;
    RobotDescription plant_robot = withPayload(robot, truth());
    if (c.friction) {
        for (LimbDescription& limb : plant_robot.limbs) {
            for (JointDescription& joint : limb.joints) {
                if (!joint.actuated) continue;
                joint.damping = kDamping;
                joint.friction = kFriction;
            }
        }
    }
    try {
        const std::unique_ptr<RobotPlant> plant =
            makePlant(defaultPlant() == PlantKind::simbody ? PlantKind::simbody : PlantKind::nocdyn_rk4, plant_robot);
        PoseController controller(model, ControlLaw::computed_torque, taskCriticallyDamped(kNaturalFrequency));
        PoseLoopOptions loop;
        loop.rate = kRate;
        loop.duration = duration;
        loop.encoders = true;
        loop.noise_u = kNoiseU;
        loop.seed = kSeed;
        const PoseLoopResult run = runPoseLoop(controller, *plant, c.trajectory, loop);
        outcome.plant = run.plant;
        outcome.peak_error = run.pose_peak_error;
        // the encoders' readings the controller used; the force sensor's own noise
        const Measurements log = sensorLog(run, kNoiseU, kNoiseTau, kSeed + 1);
        // every kDecimation-th sample: each force is then the one at its sample's instant, not a hold
        Measurements shown = log;
        shown.held_forces = false;
        out.table(inFolder(folder, c.key + "_log.csv"), decimated(tables::toTable(shown)));
        IdentificationOptions options;
        options.held_forces = true;  // the log's forces are the commands held over each tick
        options.friction = c.friction;
        const Motion motion = reconstructMotion(model, log, options);
        outcome.result = identifyPayload(model, motion, options);
        out.table(inFolder(folder, c.key + "_forces.csv"), forcesTable(outcome.result->fit));
    } catch (const Error& e) {
        outcome.failure = e.what();
    }
    return outcome;
}

std::string format(const char* pattern, double value) { return text::format(pattern, value); }

/// "| mass [kg] | 0.5 | 0.50012 ± 0.0003 | +0.02 % | 0.5 % | yes |"
std::string row(const std::string& name, double truth_value, double value, double sd, double error,
                const std::string& error_text, double goal, const std::string& goal_text, const char* pattern) {
    return "| " + name + " | " + format(pattern, truth_value) + " | " + format(pattern, value) + " ± " +
           format("%.2g", sd) + " | " + error_text + " | " + goal_text + " | " +
           (std::abs(error) <= goal ? "yes" : "no") + " |\n";
}

void caseTable(const Case& c, const Outcome& o, std::ostream& summary) {
    summary << "**" << c.title << "**";
    if (!o.result) {
        summary << ": not identified: " << o.failure << "\n\n";
        return;
    }
    const PayloadResult& r = *o.result;
    const Payload p = truth();
    summary << " (" << o.plant << " plant; peak tracking error x " << format("%.3g", o.peak_error(1) * 1e6) << " um, y "
            << format("%.3g", o.peak_error(2) * 1e6) << " um, theta " << format("%.3g", o.peak_error(0) * 1e6)
            << " urad; condition number of the identification regressor " << format("%.3g", r.fit.condition) << ")\n\n"
            << "| parameter | truth | identified ± s.d. | error | goal | within goal |\n"
            << "| --- | --- | --- | --- | --- | --- |\n";
    const double e_m = r.mass / p.mass - 1.0;
    summary << row("mass [kg]", p.mass, r.mass, r.mass_sd, e_m, format("%+.3f %%", 100.0 * e_m), kGoalMass, "0.5 %",
                   "%.5f");
    const char* axes[] = {"x", "y"};
    for (int i = 0; i < 2; ++i) {
        const double e = r.com(i) - p.com(i);
        summary << row(std::string("c.o.m. ") + axes[i] + " [mm]", 1e3 * p.com(i), 1e3 * r.com(i), 1e3 * r.com_sd(i), e,
                       format("%+.4f mm", 1e3 * e), kGoalCom, "0.2 mm", "%.4f");
    }
    const double e_i = r.inertia / p.inertia - 1.0;
    summary << row("inertia about the c.o.m. [kg m^2]", p.inertia, r.inertia, r.inertia_sd, e_i,
                   format("%+.2f %%", 100.0 * e_i), kGoalInertia, "1 %", "%.4e");
    for (const Estimate& e : r.friction) {
        const bool damping = e.name.find("damping") != std::string::npos;
        const double t = c.friction ? (damping ? kDamping : kFriction) : 0.0;
        summary << "| " << e.name << " [" << e.unit << "] | " << format("%.3g", t) << " | " << format("%.4g", e.value)
                << " ± " << format("%.2g", e.stddev) << " | " << format("%+.2f %%", 100.0 * (e.value / t - 1.0))
                << " | | |\n";
    }
    if (r.inertia_constrained) {
        summary << "\nThe unconstrained inertia came out negative (" << format("%.3e", r.inertia_unconstrained)
                << " kg m^2): the physically consistent solution has 0.\n";
    }
    summary << "\n";
}

Figure forcesFigure(const Case& c, const FitReport& fit) {
    Figure f;
    // short enough for the canvas; the series' labels say the measured forces are filtered
    f.title = "Payload identification, " + c.title + ": measured and predicted forces (held-out data)";
    PlotPanel residual;
    residual.title = "measured minus predicted";
    residual.xlabel = "t [s]";
    residual.ylabel = "{/Symbol Dt}_j [N]";
    for (Eigen::Index a = 0; a < fit.measured.cols(); ++a) {
        const std::string j = std::to_string(a + 1);
        PlotPanel panel;
        panel.title = "actuator " + j;
        panel.xlabel = "t [s]";
        panel.ylabel = "{/Symbol t}_" + j + " [N]";
        PlotSeries measured{"measured (filtered)", {}, {}, "lines lw 4 lc rgb '#9ecae1'"};
        PlotSeries predicted{"predicted", {}, {}, "lines dt 2 lw 2 lc rgb '#d62728'"};
        PlotSeries difference{"actuator " + j, {}, {}, "lines lw 1 lc " + j};
        for (std::size_t k = 0; k < fit.t.size(); k += 2) {
            const auto kk = static_cast<Eigen::Index>(k);
            measured.x.push_back(fit.t[k]);
            measured.y.push_back(fit.measured(kk, a));
            predicted.x.push_back(fit.t[k]);
            predicted.y.push_back(fit.predicted(kk, a));
            difference.x.push_back(fit.t[k]);
            difference.y.push_back(fit.measured(kk, a) - fit.predicted(kk, a));
        }
        panel.series = {std::move(measured), std::move(predicted)};
        f.panels.push_back(std::move(panel));
        residual.series.push_back(std::move(difference));
    }
    f.panels.push_back(std::move(residual));
    return f;
}

}  // namespace

void reproduceIdentification(FileSink& out, std::ostream& summary, double duration) {
    const std::string folder = "identification";
    out.folder(folder);
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    const Model model(robot);
    const Model guessed(withPayload(robot, guess()));

    // designed excitations (one base period, repeated), for the payload and for payload and friction
    ExcitationOptions design;
    design.seed = kSeed;
    std::vector<Case> cases;
    cases.reserve(4);
    for (const bool friction : {false, true}) {
        design.friction = friction;
        const ExcitationResult excitation = designExcitation(guessed, kPeriod, design);
        Case c{friction ? "designed_friction" : "designed",
               friction ? "designed excitation, slider friction unknown to the robot file" : "designed excitation",
               excitation.trajectory, excitation.assessment.condition, friction};
        c.trajectory.duration = duration;
        cases.push_back(std::move(c));
    }
    design.friction = false;
    for (int k = 1; k <= 2; ++k) {
        const PoseTrajectory paper = aboutHome(model, k == 1 ? paperTrajectory1() : paperTrajectory2());
        const ExcitationAssessment a =
            assessExcitation(guessed, paper, paper.duration.value_or(kPeriod), design.check_samples, design);
        Case c{"paper" + std::to_string(k), "paper trajectory " + std::to_string(k) + " (naive baseline)", paper,
               a.condition, false};
        c.trajectory.duration = duration;
        cases.push_back(std::move(c));
    }

    std::vector<Outcome> outcomes;
    outcomes.reserve(cases.size());
    for (const Case& c : cases) outcomes.push_back(runCase(robot, model, c, duration, folder, out));
    if (const auto& first = outcomes.front().result) {
        out.figure(inFolder(folder, "forces"), forcesFigure(cases.front(), first->fit));
    }

    const Payload p = truth();
    summary << "## Identification experiment (simulated)\n\n"
            << "The paper's prototype (`robots/paper-3prr-general.yaml`) on the Simbody plant generated from its file,"
            << " carrying a payload unknown to the controller: " << p.mass << " kg, c.o.m. at ("
            << format("%g", 1e3 * p.com.x()) << ", " << format("%g", 1e3 * p.com.y()) << ") mm in the platform frame, "
            << format("%g", p.inertia) << " kg m^2 about it. Computed-torque control at " << kRate / 1000
            << " kHz (f_n = " << kNaturalFrequency << " Hz) measuring through the encoders (1 um RMS noise; the pose"
            << " by the direct-kinematics tracker), force sensors with 0.5 N RMS noise, " << duration
            << " s of data, fixed seeds. The log (`nocdyn control --measure encoders --log` writes the same) is"
            << " identified by `nocdyn identify --payload --held-forces` (last 20 % held out). The friction case adds"
            << " viscous damping " << kDamping << " N s/m and Coulomb friction " << kFriction
            << " N to every slider of the plant only, identified alongside (`--friction`). Excitations: designed by"
            << " `nocdyn excite` (4 harmonics of 5 Hz, one period repeated; payload guess 0.5 kg at C, 1e-3 kg m^2),"
            << " and the paper's trajectories 1 and 2 moved to home as the naive baseline.\n\n"
            << "Condition number of the column-scaled stacked regressor over one period (as `nocdyn excite`"
            << " reports it; the friction design also has the six friction columns):\n\n"
            << "| excitation | condition number |\n| --- | --- |\n";
    for (const Case& c : cases) summary << "| " << c.title << " | " << format("%.4g", c.condition) << " |\n";
    summary << "\n";
    for (std::size_t k = 0; k < cases.size(); ++k) caseTable(cases[k], outcomes[k], summary);
    summary << "Files: `identification/{designed,designed_friction,paper1,paper2}_log.csv` (the sensors' log"
            << " t,u1..u3,tau1..tau3, every " << kDecimation << "th sample), `identification/*_forces.csv` (held-out"
            << " measured and predicted forces, every " << kDecimation
            << "th sample), `identification/forces.{png,svg}`"
            << " (the designed case). `nocdyn reproduce --identification-duration S` sets the length of each run.\n\n";
}

}  // namespace nocdyn::app
