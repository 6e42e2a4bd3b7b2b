// nocdyn loads: every joint's design loads (reactions.hpp) over a trajectory, or over the
// operating envelope's motions: peak and RMS reaction force, peak couple, and where the peaks
// occur; a table, a CSV and a figure of the robot at the worst pose with its joint forces.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/drawing.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "plot.hpp"

namespace nocdyn::cli {

namespace {

struct LoadsOptions : TrajectoryOptions {
    bool envelope = false;
    EnvelopeOptions envelope_options{1.0, 100.0, 9, 256, 1e-6};
    std::string figure;
};

/// The loads over one run of the trajectory's grid.
JointLoads loadsAlong(const Model& model, const PoseTrajectory& trajectory, const SampleGrid& grid,
                      LimitPolicy policy) {
    JointLoads loads;
    loads.limbs = model.limbs;
    (void)streamInverseDynamicsWithReactions(
        model, trajectory, grid, policy,
        [&](const InverseDynamicsSample& s, const Reactions& r) { loads.add(s.t, s.p, r); });
    return loads;
}

/// p(t) = home + A sin(2 pi f t) e_axis: one period of an envelope point's motion.
PoseTrajectory envelopeMotion(const Model& model, const EnvelopePoint& point) {
    PoseTrajectory trajectory;
    trajectory.name = std::string(axisName(point.axis)) + " at " + std::to_string(point.frequency) + " Hz";
    trajectory.theta.offset = model.home(0);
    trajectory.x.offset = model.home(1);
    trajectory.y.offset = model.home(2);
    AxisMotion& axis = point.axis == EnvelopeAxis::theta ? trajectory.theta
                       : point.axis == EnvelopeAxis::x   ? trajectory.x
                                                         : trajectory.y;
    axis.harmonics.push_back({point.amplitude, point.frequency, 0.0});
    return trajectory;
}

std::string shortNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v);
    return text;
}

const char* jointTypeName(JointType type) { return type == JointType::revolute ? "R" : "P"; }

io::Table table(const Model& model, const JointLoads& loads, const std::vector<double>& frequency) {
    io::Table t;
    t.columns = io::columnNames(io::TableId::loads, {.optional = !frequency.empty()});
    for (int j = 0; j < model.limbs; ++j) {
        for (int k = 0; k < 3; ++k) {
            const JointLoad& l = loads.joint[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
            std::vector<double> row{static_cast<double>(j + 1),
                                    static_cast<double>(k + 1),
                                    l.peak_force,
                                    l.peak_force_t,
                                    l.peak_force_pose(1),
                                    l.peak_force_pose(2),
                                    l.peak_force_pose(0),
                                    l.rmsForce(),
                                    l.peak_moment,
                                    l.peak_moment_t};
            if (!frequency.empty()) row.push_back(frequency[static_cast<std::size_t>(3 * j + k)]);
            t.rows.push_back(std::move(row));
        }
    }
    return t;
}

/// The largest of 1, 2, 5 times a power of ten that is at most `v` (> 0): a reference arrow's value.
double roundDown125(double v) {
    const double decade = std::pow(10.0, std::floor(std::log10(v)));
    for (const double m : {5.0, 2.0}) {
        if (m * decade <= v) return m * decade;
    }
    return decade;
}

/// The smallest of 1, 2, 5 times a power of ten that is at least `v` (> 0): a round scale.
double roundUp125(double v) {
    const double decade = std::pow(10.0, std::floor(std::log10(v)));
    for (const double m : {1.0, 2.0, 5.0}) {
        if (m * decade >= v) return m * decade;
    }
    return 10.0 * decade;
}

/// The robot at the pose of the largest peak force, each joint's force drawn as an arrow
/// from the joint (a round scale, 10 mm for 1, 2 or 5 times a power of ten newtons, that draws
/// the largest at most a third of the drawing's size), with a reference arrow of a round force
/// under the drawing and the scale in the panel's title.
Figure worstPoseFigure(const Model& model, const Pose& pose, const Reactions& reactions) {
    Data data(model);
    RobotDrawing drawing;
    if (const Status status = drawRobot(model, data, pose, drawing); !status) {
        throw Error("the worst pose cannot be drawn: " + describe(status, model));
    }
    PlotPanel panel{"Joint reaction forces at the worst pose", "x [mm]", "y [mm]", {}, false, false, true};
    double size = 0.0, peak = 0.0;
    Vector2 lower = Vector2::Constant(std::numeric_limits<double>::infinity());
    for (int j = 0; j < model.limbs; ++j) {
        const LimbDrawing& limb = drawing.limb[static_cast<std::size_t>(j)];
        PlotSeries line{j == 0 ? "limbs" : "", {}, {}, "linespoints lw 2 pt 7 ps 0.8 lc rgb '#404040'"};
        for (const JointDrawing& joint : limb.joint) {
            line.x.push_back(joint.position.x() * 1e3);
            line.y.push_back(joint.position.y() * 1e3);
            size = std::max(size, joint.position.norm());
            lower = lower.cwiseMin(joint.position);
        }
        panel.series.push_back(std::move(line));
        for (const Vector3& r : reactions.joint[static_cast<std::size_t>(j)]) peak = std::max(peak, r.head<2>().norm());
    }
    PlotSeries platform{"platform", {}, {}, "lines lw 3 lc rgb '#1f77b4'"};
    for (int j = 0; j <= model.limbs; ++j) {
        const Vector2& v = drawing.platform[static_cast<std::size_t>(j % model.limbs)];
        platform.x.push_back(v.x() * 1e3);
        platform.y.push_back(v.y() * 1e3);
    }
    panel.series.push_back(std::move(platform));
    const char* arrow = "vectors head filled size screen 0.014,22 lw 2 lc rgb '#d62728'";
    const double per_10mm = peak > 0.0 ? roundUp125(peak * 0.01 / (size / 3.0)) : 0.0;  // N drawn 10 mm long
    const double scale = peak > 0.0 ? 0.01 / per_10mm : 0.0;                            // m per N
    PlotSeries forces{"reaction force (largest " + shortNumber(peak) + " N)", {}, {}, arrow, {{}, {}}};
    for (int j = 0; j < model.limbs; ++j) {
        for (std::size_t k = 0; k < 3; ++k) {
            const Vector2 from = drawing.limb[static_cast<std::size_t>(j)].joint[k].position;
            const Vector2 f = scale * reactions.joint[static_cast<std::size_t>(j)][k].head<2>();
            forces.x.push_back(from.x() * 1e3);
            forces.y.push_back(from.y() * 1e3);
            forces.extra[0].push_back(f.x() * 1e3);
            forces.extra[1].push_back(f.y() * 1e3);
            lower = lower.cwiseMin(from + f);
        }
    }
    panel.series.push_back(std::move(forces));
    if (peak > 0.0) {
        // the reference: a round force drawn to the same scale, below the lowest joint or arrow tip
        const double reference = roundDown125(peak);
        panel.series.push_back({"reference arrow (lower left): " + shortNumber(reference) + " N",
                                {lower.x() * 1e3},
                                {(lower.y() - 0.06 * size) * 1e3},
                                "vectors head filled size screen 0.014,22 lw 3 lc rgb '#000000'",
                                {{scale * reference * 1e3}, {0.0}}});
        panel.title += "; arrows: 10 mm = " + shortNumber(per_10mm) + " N";
    }
    Figure f;
    f.title = literalText(model.description.name) + ": joint reactions at the pose of the largest peak force";
    f.panels = {panel};
    f.width = 820;  // a map: about as wide as high, the legend in rows under it
    f.height = 900;
    return f;
}

void run(const LoadsOptions& options) {
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    JointLoads loads;
    loads.limbs = model.limbs;
    std::vector<double> frequency;  // per joint: the envelope motion of its peak force
    if (options.envelope) {
        if (options.envelope_options.max_frequency < options.envelope_options.min_frequency) {
            throw CLI::ValidationError("--max-frequency", "must be at least --min-frequency");
        }
        frequency.assign(static_cast<std::size_t>(3 * model.limbs), 0.0);
        for (const EnvelopePoint& point : operatingEnvelope(model, options.envelope_options)) {
            if (!(point.amplitude > 0.0)) continue;
            const double rate = point.frequency * options.envelope_options.samples_per_period;
            const JointLoads run = loadsAlong(model, envelopeMotion(model, point),
                                              sampleGrid(1.0 / point.frequency, rate), LimitPolicy::record);
            for (int i = 0; i < 3 * model.limbs; ++i) {
                const JointLoad& mine = loads.joint[static_cast<std::size_t>(i / 3)][static_cast<std::size_t>(i % 3)];
                const JointLoad& theirs = run.joint[static_cast<std::size_t>(i / 3)][static_cast<std::size_t>(i % 3)];
                if (mine.samples == 0 || theirs.peak_force > mine.peak_force)
                    frequency[static_cast<std::size_t>(i)] = point.frequency;
            }
            loads.merge(run);
        }
    } else {
        if (options.trajectory.empty()) throw CLI::ValidationError("--trajectory", "is required (or give --envelope)");
        const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
        const SampleGrid grid = sampleGrid(chooseDuration(options.duration, trajectory), options.rate);
        loads = loadsAlong(model, trajectory, grid, LimitPolicy::error);
    }
    if (!options.output.empty()) writeTable(table(model, loads, frequency), options.output);
    // the worst pose: where the largest peak force of any joint occurs
    int worst = 0;
    for (int i = 1; i < 3 * model.limbs; ++i) {
        if (loads.joint[static_cast<std::size_t>(i / 3)][static_cast<std::size_t>(i % 3)].peak_force >
            loads.joint[static_cast<std::size_t>(worst / 3)][static_cast<std::size_t>(worst % 3)].peak_force)
            worst = i;
    }
    const JointLoad& w = loads.joint[static_cast<std::size_t>(worst / 3)][static_cast<std::size_t>(worst % 3)];
    std::printf(
        "joint              peak |f| [N]  at t [s]   pose x, y [mm], theta [deg]     RMS |f| [N]  peak |m| [N m]\n");
    for (int j = 0; j < model.limbs; ++j) {
        for (int k = 0; k < 3; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            const JointLoad& l = loads.joint[static_cast<std::size_t>(j)][kk];
            const std::string name = "limb " + std::to_string(j + 1) + " joint " + std::to_string(k + 1) + " (" +
                                     jointTypeName(model.limb[static_cast<std::size_t>(j)].type[kk]) + ")";
            std::printf("%-18s %12.4g  %8.4f   %8.3f, %8.3f, %8.3f   %11.4g  %14.4g\n", name.c_str(), l.peak_force,
                        l.peak_force_t, l.peak_force_pose(1) * 1e3, l.peak_force_pose(2) * 1e3,
                        l.peak_force_pose(0) * 180.0 / std::numbers::pi, l.rmsForce(), l.peak_moment);
        }
    }
    std::printf("largest: limb %d joint %d, %.4g N%s\n", worst / 3 + 1, worst % 3 + 1, w.peak_force,
                options.envelope ? " (over the operating envelope's motions)" : "");
    if (!options.figure.empty()) {
        Data data(model);
        Reactions reactions;
        // rates and accelerations of the worst sample are not kept: the figure shows the
        // reactions there recomputed from the motion that produced them
        Pose p = w.peak_force_pose, dp = Pose::Zero(), ddp = Pose::Zero();
        if (!options.envelope) {
            io::trajectoryByNameOrFile(options.trajectory).evaluate(w.peak_force_t, p, dp, ddp);
        } else {
            for (const EnvelopePoint& point : operatingEnvelope(model, options.envelope_options)) {
                if (point.frequency != frequency[static_cast<std::size_t>(worst)] || !(point.amplitude > 0.0)) continue;
                Pose q, dq, ddq;
                envelopeMotion(model, point).evaluate(w.peak_force_t, q, dq, ddq);
                if ((q - p).cwiseAbs().maxCoeff() == 0.0) {
                    dp = dq;
                    ddp = ddq;
                    break;
                }
            }
        }
        if (const Status status = inverseDynamicsWithReactions(model, data, p, dp, ddp, reactions); !status) {
            throw Error("the worst pose: " + describe(status, model));
        }
        renderFigure(worstPoseFigure(model, p, reactions), options.figure);
    }
}

}  // namespace

void addLoadsCommand(CLI::App& app) {
    auto options = std::make_shared<LoadsOptions>();
    CLI::App* command = app.add_subcommand(
        "loads",
        "Design loads of every joint (the bearing loads a designer sizes parts by): along a trajectory, or\n"
        "with --envelope over the operating envelope's motions (each axis at log-spaced frequencies, at the\n"
        "largest amplitude within every limit), each joint's peak and RMS reaction force |(fx, fy)| [N] and\n"
        "peak couple |m| [N m], with the time and pose of the peak. Reactions as in `inverse-dynamics\n"
        "--reactions`. Prints a table; --output writes it as CSV (limb and joint 1-based), --figure draws\n"
        "the robot at the worst pose with each joint's force.\n"
        "Example: nocdyn loads --robot robots/3-rrr.yaml --trajectory paper1 --figure loads");
    command->add_option("--trajectory", options->trajectory,
                        "paper1, paper2 (eqs. 33-34), a trajectory file (YAML, harmonics) or samples (.csv)");
    addRobotOption(*command, options->robot);
    command->add_option("--duration", options->duration, "Seconds to sample [default: the file's duration, else 0.2]")
        ->check(finiteIn(kMinDuration, kMaxDuration, "s"));
    command->add_option("--rate", options->rate, "Samples per second")
        ->check(finiteIn(kMinRate, kMaxRate, "Hz"))
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV file to write [default: none]")->check(nonEmptyPath());
    command->add_option("--figure", options->figure, "Figure stem (STEM.png, STEM.svg) [default: none]")
        ->check(nonEmptyPath());
    command->add_flag("--envelope", options->envelope, "Over the operating envelope's motions instead of a trajectory")
        ->excludes("--trajectory");
    command->add_option("--min-frequency", options->envelope_options.min_frequency, "--envelope: [Hz]")
        ->check(finiteIn(kEnvelopeMinFrequency, kEnvelopeMaxFrequency, "Hz"))
        ->capture_default_str();
    command->add_option("--max-frequency", options->envelope_options.max_frequency, "--envelope: [Hz]")
        ->check(finiteIn(kEnvelopeMinFrequency, kEnvelopeMaxFrequency, "Hz"))
        ->capture_default_str();
    command->add_option("--points", options->envelope_options.frequencies, "--envelope: frequencies per axis")
        ->check(CLI::Range(1, kEnvelopeMaxPoints))
        ->capture_default_str();
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
