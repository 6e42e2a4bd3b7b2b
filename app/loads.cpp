#include "app/loads.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <utility>

#include "app/loads_spatial.hpp"
#include "app/pose_spatial.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/drawing.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/text.hpp"
#include "render/plot.hpp"

namespace nocdyn::app {

namespace {

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
    trajectory.name = std::string(axisName(point.axis)) + " at " + text::format("%f", point.frequency) + " Hz";
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
    std::string text;
    text = text::format("%.4g", v);
    return text;
}

const char* jointTypeName(JointType type) { return type == JointType::revolute ? "R" : "P"; }

io::Table loadsTable(const Model& model, const JointLoads& loads, const std::vector<double>& frequency) {
    io::Table t;
    t.columns =
        io::columnNames(io::TableId::loads, {.optional = !frequency.empty(), .task_dimension = model.task_dimension});
    for (int j = 0; j < model.limbs; ++j) {
        for (int k = 0; k < 3; ++k) {
            const JointLoad& l = loads.joint[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
            std::vector<double> row{
                static_cast<double>(j + 1), static_cast<double>(k + 1), l.peak_force, l.peak_force_t,
                l.peak_force_pose(1),       l.peak_force_pose(2)};
            if (model.task_dimension == 3) row.push_back(l.peak_force_pose(0));  // a two-DOF robot has no theta
            row.insert(row.end(), {l.rmsForce(), l.peak_moment, l.peak_moment_t});
            if (!frequency.empty())
                row.push_back(frequency[(3 * static_cast<std::size_t>(j)) + static_cast<std::size_t>(k)]);
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
render::Figure worstPoseFigure(const Model& model, const Pose& pose, const Reactions& reactions) {
    Data data(model);
    RobotDrawing drawing;
    if (const Status status = drawRobot(model, data, pose, drawing); !status) {
        throw Error("the worst pose cannot be drawn: " + describe(status, model));
    }
    render::PlotPanel panel{"Joint reaction forces at the worst pose", "x [mm]", "y [mm]", {}, false, false, true};
    double size = 0.0, peak = 0.0;
    Vector2 lower = Vector2::Constant(std::numeric_limits<double>::infinity());
    for (int j = 0; j < model.limbs; ++j) {
        const LimbDrawing& limb = drawing.limb[static_cast<std::size_t>(j)];
        render::PlotSeries line{j == 0 ? "limbs" : "", {}, {}, "linespoints lw 2 pt 7 ps 0.8 lc rgb '#404040'"};
        for (const JointDrawing& joint : limb.joint) {
            line.x.push_back(joint.position.x() * 1e3);
            line.y.push_back(joint.position.y() * 1e3);
            size = std::max(size, joint.position.norm());
            lower = lower.cwiseMin(joint.position);
        }
        panel.series.push_back(std::move(line));
        for (const Vector3& r : reactions.joint[static_cast<std::size_t>(j)]) peak = std::max(peak, r.head<2>().norm());
    }
    render::PlotSeries platform{"platform", {}, {}, "lines lw 3 lc rgb '#1f77b4'"};
    for (int j = 0; j <= model.limbs; ++j) {
        const Vector2& v = drawing.platform[static_cast<std::size_t>(j % model.limbs)];
        platform.x.push_back(v.x() * 1e3);
        platform.y.push_back(v.y() * 1e3);
    }
    panel.series.push_back(std::move(platform));
    const char* arrow = "vectors head filled size screen 0.014,22 lw 2 lc rgb '#d62728'";
    const double per_10mm = peak > 0.0 ? roundUp125(peak * 0.01 / (size / 3.0)) : 0.0;  // N drawn 10 mm long
    const double scale = peak > 0.0 ? 0.01 / per_10mm : 0.0;                            // m per N
    render::PlotSeries forces{"reaction force (largest " + shortNumber(peak) + " N)", {}, {}, arrow, {{}, {}}};
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
    render::Figure f;
    f.title = render::literalText(model.description.name) + ": joint reactions at the pose of the largest peak force";
    f.panels = {panel};
    f.width = 820;  // a map: about as wide as high, the legend in rows under it
    f.height = 900;
    return f;
}

JointLoad& at(JointLoads& loads, int i) {
    return loads.joint[static_cast<std::size_t>(i / 3)][static_cast<std::size_t>(i % 3)];
}

std::string reportText(const Model& model, const LoadsResult& r, bool envelope) {
    const bool theta = model.task_dimension == 3;  // a two-DOF robot's pose is [x, y]
    std::string text = theta
                           ? "joint              peak |f| [N]  at t [s]   pose x, y [mm], theta [deg]     RMS |f| [N]  "
                             "peak |m| [N m]\n"
                           : "joint              peak |f| [N]  at t [s]   pose x, y [mm]         RMS |f| [N]  "
                             "peak |m| [N m]\n";
    std::string line;
    for (int j = 0; j < model.limbs; ++j) {
        for (int k = 0; k < 3; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            const JointLoad& l = r.loads.joint[static_cast<std::size_t>(j)][kk];
            const std::string name = "limb " + std::to_string(j + 1) + " joint " + std::to_string(k + 1) + " (" +
                                     jointTypeName(model.limb[static_cast<std::size_t>(j)].type[kk]) + ")";
            line = theta ? text::format("%-18s %12.4g  %8.4f   %8.3f, %8.3f, %8.3f   %11.4g  %14.4g\n", name.c_str(),
                                        l.peak_force, l.peak_force_t, l.peak_force_pose(1) * 1e3,
                                        l.peak_force_pose(2) * 1e3, l.peak_force_pose(0) * 180.0 / std::numbers::pi,
                                        l.rmsForce(), l.peak_moment)
                         : text::format("%-18s %12.4g  %8.4f   %8.3f, %8.3f   %11.4g  %14.4g\n", name.c_str(),
                                        l.peak_force, l.peak_force_t, l.peak_force_pose(1) * 1e3,
                                        l.peak_force_pose(2) * 1e3, l.rmsForce(), l.peak_moment);
            text += line;
        }
    }
    const JointLoad& w =
        r.loads.joint[static_cast<std::size_t>(r.worst_limb - 1)][static_cast<std::size_t>(r.worst_joint - 1)];
    line = text::format("largest: limb %d joint %d, %.4g N%s\n", r.worst_limb, r.worst_joint, w.peak_force,
                        envelope ? " (over the operating envelope's motions)" : "");
    text += line;
    if (r.beyond_resonance > 0) {
        line = text::format(
            "left out: %d envelope motions beyond the band's third bound (limit resonance: the dynamic "
            "amplification leaves [1/%.4g, %.4g]; first natural frequency %.6g Hz): the platform does not follow the "
            "rigid model there\n",
            r.beyond_resonance, r.resonance.amplification, r.resonance.amplification, r.resonance.frequency);
        text += line;
    }
    return text;
}

}  // namespace

void validate(const LoadsOptions& options) {
    validate(static_cast<const SamplingOptions&>(options));
    requireIn(options.min_frequency, kEnvelopeFrequencyRange, "min_frequency");
    requireIn(options.max_frequency, kEnvelopeFrequencyRange, "max_frequency");
    requireIn(options.points, kEnvelopePointsRange, "points");
    if (options.envelope) {
        if (options.max_frequency < options.min_frequency) {
            throw OptionError("max_frequency", "must be at least min_frequency");
        }
        if (!options.trajectory.empty()) throw OptionError("trajectory", "not with envelope (its motions are given)");
    } else if (options.trajectory.empty()) {
        throw OptionError("trajectory", "is required (or give envelope)");
    }
    // an option set where it has no effect is refused, naming the option it goes with
    const LoadsOptions defaults;
    const std::pair<bool, const char*> envelope_only[] = {
        {options.min_frequency != defaults.min_frequency, "min_frequency"},
        {options.max_frequency != defaults.max_frequency, "max_frequency"},
        {options.points != defaults.points, "points"}};
    for (const auto& [set, field] : envelope_only) {
        if (set && !options.envelope)
            throw OptionError(field, "does not apply to a trajectory: it goes with `envelope`");
    }
    const std::pair<bool, const char*> trajectory_only[] = {{options.duration.has_value(), "duration"},
                                                            {options.rate != defaults.rate, "rate"}};
    for (const auto& [set, field] : trajectory_only) {
        if (set && options.envelope)
            throw OptionError(field, "does not apply to the envelope's motions: it goes with `trajectory`");
    }
}

LoadsResult runLoads(const LoadsOptions& options, Observer& observer) {
    if (isSpatialRobot(options.robot)) return runSpatialLoads(options, observer);
    validate(options);
    LoadsResult out;
    out.model = std::make_shared<const Model>(loadRobot(options.robot));
    const Model& model = *out.model;
    JointLoads& loads = out.loads;
    loads.limbs = model.limbs;
    if (options.envelope && model.task_dimension == 2) {
        throw OptionError("envelope",
                          "not for a two-DOF robot (motion: translation, pose [x, y]): the operating "
                          "envelope moves theta too; give a trajectory keyed x, y");
    }
    if (options.envelope) {
        nocdyn::EnvelopeOptions envelope{options.min_frequency, options.max_frequency, options.points, 256, 1e-6};
        envelope.progress = [&observer](int done, int total) {
            observer.progress(done, total, "points");
            stopIfRequested(observer);
        };
        out.frequency.assign(3 * static_cast<std::size_t>(model.limbs), 0.0);
        const std::vector<EnvelopePoint> points = operatingEnvelope(model, envelope);
        // beyond the band's third bound the platform does not follow the rigid model's motion
        // (the limit `resonance`): its loads there are not the machine's
        int moving = 0;
        for (const EnvelopePoint& point : points) {
            if (point.limit == EnvelopeLimit::resonance) {
                ++out.beyond_resonance;
            } else {
                out.points.push_back(point);
                moving += point.amplitude > 0.0 ? 1 : 0;
            }
        }
        if (out.beyond_resonance > 0) out.resonance = envelopeResonance(model);
        if (moving == 0 && out.beyond_resonance > 0) {
            throw OptionError("min_frequency",
                              text::format("every envelope frequency is beyond the band's third bound (limit "
                                           "resonance: the dynamic amplification beyond %.4g; first natural frequency "
                                           "%.6g Hz), where the rigid model's loads do not hold: choose a lower one",
                                           out.resonance.amplification, out.resonance.frequency));
        }
        for (const EnvelopePoint& point : out.points) {
            if (!(point.amplitude > 0.0)) continue;
            const double rate = point.frequency * envelope.samples_per_period;
            const JointLoads run = loadsAlong(model, envelopeMotion(model, point),
                                              sampleGrid(1.0 / point.frequency, rate), LimitPolicy::record);
            for (int i = 0; i < 3 * model.limbs; ++i) {
                const JointLoad& theirs = run.joint[static_cast<std::size_t>(i / 3)][static_cast<std::size_t>(i % 3)];
                if (at(loads, i).samples == 0 || theirs.peak_force > at(loads, i).peak_force)
                    out.frequency[static_cast<std::size_t>(i)] = point.frequency;
            }
            loads.merge(run);
            stopIfRequested(observer);
        }
    } else {
        const PoseTrajectory trajectory =
            trajectoryFor(model, io::trajectoryByNameOrFile(options.trajectory), options.trajectory);
        const SampleGrid grid = sampleGrid(chooseDuration(options.duration, trajectory), options.rate);
        loads = loadsAlong(model, trajectory, grid, LimitPolicy::error);
    }
    out.table = loadsTable(model, loads, out.frequency);
    // the worst joint: where the largest peak force of any joint occurs
    int worst = 0;
    for (int i = 1; i < 3 * model.limbs; ++i) {
        if (at(loads, i).peak_force > at(loads, worst).peak_force) worst = i;
    }
    out.worst_limb = worst / 3 + 1;
    out.worst_joint = worst % 3 + 1;
    out.text = reportText(model, out, options.envelope);
    return out;
}

void requireLoadsFigure(const LoadsOptions& options) {
    if (isSpatialRobot(options.robot)) {
        throw OptionError("figure", "is drawn for planar robots only, not for a spatial robot (space: spatial)");
    }
}

render::Figure loadsResultFigure(const LoadsOptions& options, const LoadsResult& result) {
    if (!result.model) {
        requireLoadsFigure(options);
        throw Error("loads: no planar robot to draw");
    }
    const Model& model = *result.model;
    const int worst = 3 * (result.worst_limb - 1) + result.worst_joint - 1;
    const JointLoad& w = result.loads.joint[static_cast<std::size_t>(worst / 3)][static_cast<std::size_t>(worst % 3)];
    Data data(model);
    Reactions reactions;
    // rates and accelerations of the worst sample are not kept: the figure shows the
    // reactions there recomputed from the motion that produced them
    Pose p = w.peak_force_pose, dp = Pose::Zero(), ddp = Pose::Zero();
    if (!options.envelope) {
        trajectoryFor(model, io::trajectoryByNameOrFile(options.trajectory)).evaluate(w.peak_force_t, p, dp, ddp);
    } else {
        for (const EnvelopePoint& point : result.points) {
            if (point.frequency != result.frequency[static_cast<std::size_t>(worst)] || !(point.amplitude > 0.0))
                continue;
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
    return worstPoseFigure(model, p, reactions);
}

}  // namespace nocdyn::app
