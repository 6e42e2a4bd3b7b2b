// The animation page and static frames (animation.hpp).
#include "render/animation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "nocdyn/drawing.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/printable.hpp"
#include "nocdyn/text.hpp"
#include "render/page_data.hpp"

namespace nocdyn::render {

namespace {

std::string secondsText(double t) {
    std::string text;
    text = text::format("%.9g", t);
    return text;
}

/// "t = ... s: reason" for a pose that cannot be drawn.
Error poseError(const std::string& where, double t, const Status& status, const Model& model) {
    return Error(where + "t = " + secondsText(t) + " s: " + describe(status, model));
}

/// The drawable points of one frame, flattened: per limb, per joint, its position and (P) its
/// rail ends; then C. Integers in micrometres keep the page small and exact to well under a pixel.
void appendPoints(const RobotDrawing& d, std::vector<long long>& out) {
    const auto um = [&](const Vector2& x) {
        out.push_back(std::llround(x.x() * 1e6));
        out.push_back(std::llround(x.y() * 1e6));
    };
    for (int j = 0; j < d.limbs; ++j) {
        for (const JointDrawing& joint : d.limb[static_cast<std::size_t>(j)].joint) {
            um(joint.position);
            if (joint.type == JointType::prismatic) {
                um(joint.rail_start);
                um(joint.rail_end);
            }
        }
    }
    um(d.C);
}

}  // namespace

namespace detail {

std::string scriptSafe(const std::string& json) {
    std::string out;
    out.reserve(json.size());
    for (const char c : json) {
        if (c == '<') {
            out += "\\u003c";
        } else if (c == '>') {
            out += "\\u003e";
        } else if (c == '&') {
            out += "\\u0026";
        } else {
            out += c;
        }
    }
    return out;
}

std::string plotsJson(const std::vector<double>& t, const std::vector<double>& u, const std::vector<double>& tau, int n,
                      std::vector<double>& peak_tau) {
    const std::size_t N = t.size(), nn = static_cast<std::size_t>(n);
    const std::size_t B = std::min(N, kMaxPlotBuckets);
    std::vector<double> bucket_t(B);
    std::vector<std::vector<double>> u_lo(nn), u_hi(nn), f_lo(nn), f_hi(nn);
    peak_tau.assign(nn, 0.0);
    for (std::size_t b = 0; b < B; ++b) {
        const std::size_t k0 = b * N / B, k1 = (b + 1) * N / B;
        bucket_t[b] = t[k0];
        for (std::size_t a = 0; a < nn; ++a) {
            double ul = std::numeric_limits<double>::infinity(), uh = -ul, fl = ul, fh = -ul;
            for (std::size_t k = k0; k < k1; ++k) {
                ul = std::min(ul, u[k * nn + a]);
                uh = std::max(uh, u[k * nn + a]);
                fl = std::min(fl, tau[k * nn + a]);
                fh = std::max(fh, tau[k * nn + a]);
            }
            u_lo[a].push_back(ul);
            u_hi[a].push_back(uh);
            f_lo[a].push_back(fl);
            f_hi[a].push_back(fh);
            peak_tau[a] = std::max({peak_tau[a], std::abs(fl), std::abs(fh)});
        }
    }
    std::string json = "{\"t\":";
    detail::appendArray(json, bucket_t, 9);
    for (const bool forces : {false, true}) {
        json += forces ? ",\"tau\":[" : ",\"u\":[";
        for (std::size_t a = 0; a < nn; ++a) {
            json += a ? ",{\"name\":\"" : "{\"name\":\"";
            json += forces ? "tau" : "u";
            json += std::to_string(a + 1);
            json += "\",\"lo\":";
            detail::appendArray(json, forces ? f_lo[a] : u_lo[a], 6);
            json += ",\"hi\":";
            detail::appendArray(json, forces ? f_hi[a] : u_hi[a], 6);
            json += '}';
        }
        json += ']';
    }
    json += '}';
    return json;
}

}  // namespace detail

// The page around its data (render/animation.html with render/animation.js in its script),
// embedded at build time (render/CMakeLists.txt): the page is kPageHead, the data's JSON, kPageTail.
extern const char* const kPageHead;
extern const char* const kPageTail;

MotionSamples motionFromTrajectory(const Model& model, const PoseTrajectory& trajectory, double duration, double rate) {
    const SampleGrid grid = sampleGrid(duration, rate);
    if (grid.count > kMaxAnimationSamples) {
        throw Error("--duration " + secondsText(duration) + " s at --rate " + secondsText(rate) + " Hz gives " +
                    std::to_string(grid.count) + " samples; animate holds at most " +
                    std::to_string(kMaxAnimationSamples));
    }
    requireRateAboveNyquist(trajectory, grid.rate);
    MotionSamples motion;
    motion.source = trajectory.name.empty() ? "trajectory" : trajectory.name;
    const int n = model.actuators;
    motion.actuators = n;
    motion.t.reserve(grid.count);
    motion.p.reserve(grid.count);
    motion.u.reserve(grid.count * static_cast<std::size_t>(n));
    motion.tau.reserve(grid.count * static_cast<std::size_t>(n));
    const LimitSummary summary =
        streamInverseDynamics(model, trajectory, grid, LimitPolicy::record, [&](const InverseDynamicsSample& s) {
            motion.t.push_back(s.t);
            motion.p.push_back(s.p);
            for (int a = 0; a < n; ++a) {
                motion.u.push_back(s.u(a));
                motion.tau.push_back(s.tau(a));
            }
        });
    motion.warnings = summary.limit_violations;
    return motion;
}

namespace {

/// A recorded motion (a file: nothing in it names its robot) against this robot's limits: each
/// actuator whose recorded force or position leaves its effort or range, and, when every
/// actuator's force does, the likely cause (another robot's motion: its forces scaled against
/// the wrong limits).
std::vector<std::string> recordedLimitWarnings(const Model& model, const MotionSamples& motion) {
    std::vector<std::string> warnings;
    const int n = motion.actuators;
    const std::size_t N = motion.t.size();
    int over_effort = 0, limited = 0;
    for (int a = 0; a < n; ++a) {
        const JointDescription& joint = model.description.limbs[static_cast<std::size_t>(model.actuator_limb[a])]
                                            .joints[static_cast<std::size_t>(model.actuator_joint[a])];
        const bool revolute = joint.type == JointType::revolute;
        double peak = 0.0, u_min = std::numeric_limits<double>::infinity(), u_max = -u_min;
        for (std::size_t k = 0; k < N; ++k) {
            const std::size_t at = k * static_cast<std::size_t>(n) + static_cast<std::size_t>(a);
            peak = std::max(peak, std::abs(motion.tau[at]));
            u_min = std::min(u_min, motion.u[at]);
            u_max = std::max(u_max, motion.u[at]);
        }
        const std::string name = text::format("tau%d", a + 1);
        if (std::isfinite(joint.limits.effort)) {
            ++limited;
            if (peak > joint.limits.effort) {
                ++over_effort;
                warnings.push_back(text::format(
                    "actuator %d: the recorded %s peaks at %.4g %s, beyond its effort "
                    "limit %.4g %s",
                    a + 1, name.c_str(), peak, revolute ? "N m" : "N", joint.limits.effort, revolute ? "N m" : "N"));
            }
        }
        if (u_min < joint.limits.lower || u_max > joint.limits.upper) {
            warnings.push_back(text::format(
                "actuator %d: the recorded motion takes u%d to [%.4g, %.4g] %s, beyond "
                "its range [%.4g, %.4g]",
                a + 1, a + 1, u_min, u_max, revolute ? "rad" : "m", joint.limits.lower, joint.limits.upper));
        }
    }
    if (limited > 0 && over_effort == limited) {
        warnings.push_back(
            "every actuator's recorded force is beyond its effort limit: is the motion another "
            "robot's? (the file does not name its robot; its forces are drawn against " +
            text::printable(model.description.name) + "'s limits)");
    }
    return warnings;
}

/// Whether a recorded motion's own actuator columns (u1..un, as every command writes them) are not
/// this robot's actuator positions at the recorded poses, or the file has more actuators: then
/// the motion is another robot's. A replay's u may trail its poses by the tracking error, so only
/// a difference of a fifth of the motion's own span or more counts. Empty when nothing says so.
std::string otherRobotsMotion(const Model& model, const io::Table& table, const MotionSamples& motion,
                              const std::string& path) {
    const int n = motion.actuators;
    const std::string name = text::printable(model.description.name);
    if (table.has(text::format("tau%d", n + 1)) || table.has(text::format("u%d", n + 1))) {
        return text::format("%s holds more than %d actuators: is the motion another robot's? (%s has %d)", path.c_str(),
                            n, name.c_str(), n);
    }
    const std::size_t N = motion.t.size();
    for (int a = 0; a < n; ++a) {
        const std::string column = text::format("u%d", a + 1);
        if (!table.has(column)) return {};
        const std::size_t c = table.column(column);
        double lo_file = std::numeric_limits<double>::infinity(), hi_file = -lo_file, lo = lo_file, hi = hi_file,
               difference = 0.0;
        for (std::size_t k = 0; k < N; ++k) {
            const double recorded = table.rows[k][c];
            const double here = motion.u[k * static_cast<std::size_t>(n) + static_cast<std::size_t>(a)];
            lo_file = std::min(lo_file, recorded);
            hi_file = std::max(hi_file, recorded);
            lo = std::min(lo, here);
            hi = std::max(hi, here);
            difference = std::max(difference, std::abs(recorded - here));
        }
        if (!std::isfinite(difference)) continue;
        if (difference > 0.2 * std::max(hi_file - lo_file, hi - lo) + 1e-9) {
            return text::format(
                "%s: its %s is not %s's actuator %d at its poses (they differ by up to %.4g, the "
                "motion spans %.4g): is the motion another robot's? (the file does not name its "
                "robot)",
                path.c_str(), column.c_str(), name.c_str(), a + 1, difference, hi_file - lo_file);
        }
    }
    return {};
}

}  // namespace

MotionSamples motionFromCsv(const Model& model, const std::string& path) {
    MotionSamples motion = motionFromTable(model, io::readCsvFile(path), path);
    motion.source = std::filesystem::path(path).filename().string();
    return motion;
}

MotionSamples motionFromTable(const Model& model, const io::Table& table, const std::string& path) {
    if (table.rows.empty()) throw Error(path + ": no rows");
    if (table.rows.size() > kMaxAnimationSamples) {
        throw Error(path + ": " + std::to_string(table.rows.size()) + " rows; animate holds at most " +
                    std::to_string(kMaxAnimationSamples));
    }
    const int n = model.actuators;
    // a two-DOF robot's pose is [x, y]: theta stays at home(0), and a theta column, when there is
    // one, must hold that value
    const bool two_dof = model.task_dimension == 2;
    // a replay: the achieved pose is the motion, the target (x, y, theta) its ghost
    const bool replay = table.has("x_achieved") && table.has("y_achieved") && (two_dof || table.has("theta_achieved"));
    const std::size_t ct = table.column("t"), cx = table.column(replay ? "x_achieved" : "x"),
                      cy = table.column(replay ? "y_achieved" : "y");
    const char* const theta_name = replay ? "theta_achieved" : "theta";
    const bool theta_given = !two_dof || table.has(theta_name), target_theta_given = !two_dof || table.has("theta");
    const std::size_t ctheta = theta_given ? table.column(theta_name) : 0;
    const std::size_t gtheta = target_theta_given ? table.column("theta") : 0, gx = table.column("x"),
                      gy = table.column("y");
    const auto thetaOf = [&](const std::vector<double>& row, bool given, std::size_t column, const char* name,
                             const std::string& where) {
        if (!two_dof) return row[column];
        if (given && row[column] != model.home(0)) {
            throw Error(where + "column '" + name + "': " + secondsText(row[column]) +
                        ", but a two-DOF robot (motion: translation) has no theta: it stays at " +
                        secondsText(model.home(0)));
        }
        return model.home(0);
    };
    std::vector<std::size_t> ctau;
    for (int a = 1; a <= n; ++a) {
        const std::string name = "tau" + std::to_string(a);
        if (!table.has(name)) {
            throw Error(path + ": no column '" + name + "' (the robot has " + std::to_string(n) +
                        " actuators; animate reads " + (two_dof ? "t,x,y" : "t,x,y,theta") + ",tau1..tau" +
                        std::to_string(n) + ")");
        }
        ctau.push_back(table.column(name));
    }
    MotionSamples motion;
    motion.source = path;
    motion.actuators = n;
    Data data(model);
    RobotDrawing drawing;
    for (std::size_t k = 0; k < table.rows.size(); ++k) {
        const auto& row = table.rows[k];
        const std::string where = path + ":" + std::to_string(k < table.lines.size() ? table.lines[k] : k + 2) + ": ";
        const double t = row[ct];
        if (!motion.t.empty() && !(t > motion.t.back())) {
            throw Error(where + "t = " + secondsText(t) + " s does not follow the previous row's " +
                        secondsText(motion.t.back()) + " s");
        }
        const Pose p(thetaOf(row, theta_given, ctheta, theta_name, where), row[cx], row[cy]);
        if (const Status status = drawRobot(model, data, p, drawing); !status) throw poseError(where, t, status, model);
        if (replay) {
            const Pose target(thetaOf(row, target_theta_given, gtheta, "theta", where), row[gx], row[gy]);
            if (const Status status = drawRobot(model, data, target, drawing); !status)
                throw poseError(where + "the target: ", t, status, model);
            // u of the achieved pose below
            if (const Status status = drawRobot(model, data, p, drawing); !status)
                throw poseError(where, t, status, model);
            motion.ghost.push_back(target);
        }
        motion.t.push_back(t);
        motion.p.push_back(p);
        for (int a = 0; a < n; ++a) {
            motion.u.push_back(data.u(a));
            motion.tau.push_back(row[ctau[static_cast<std::size_t>(a)]]);
        }
    }
    motion.warnings = recordedLimitWarnings(model, motion);
    if (const std::string other = otherRobotsMotion(model, table, motion, path); !other.empty())
        motion.warnings.push_back(other);
    return motion;
}

std::string animationPage(const Model& model, const MotionSamples& motion, const AnimationOptions& options) {
    const std::size_t N = motion.t.size();
    if (N == 0) throw Error("no samples to animate");
    const int n = motion.actuators;
    const auto nn = static_cast<std::size_t>(n);
    const double t_end = motion.t.back();
    const double duration = N > 1 ? t_end - motion.t.front() : 0.0;
    double slow = options.slow_motion;
    if (!(slow > 0.0)) slow = std::max(1.0, std::round(10.0 / std::max(duration, 1e-9)));

    // frames: evenly spread samples, the first and the last included
    const std::size_t F = std::min(N, kMaxAnimationFrames);
    std::vector<std::size_t> frame_sample(F);
    for (std::size_t i = 0; i < F; ++i) frame_sample[i] = F > 1 ? (i * (N - 1) + (F - 1) / 2) / (F - 1) : 0;
    Data data(model);
    RobotDrawing drawing;
    std::vector<long long> points, ghost;
    std::vector<double> frame_t, frame_tau;
    const bool ghosted = motion.ghost.size() == N;
    for (const std::size_t k : frame_sample) {
        if (ghosted) {
            if (const Status status = drawRobot(model, data, motion.ghost[k], drawing); !status) {
                throw poseError(motion.source + ": the target: ", motion.t[k], status, model);
            }
            appendPoints(drawing, ghost);
        }
        if (const Status status = drawRobot(model, data, motion.p[k], drawing); !status) {
            throw poseError(motion.source + ": ", motion.t[k], status, model);
        }
        appendPoints(drawing, points);
        frame_t.push_back(motion.t[k]);
        for (std::size_t a = 0; a < nn; ++a) frame_tau.push_back(motion.tau[k * nn + a]);
    }
    const std::size_t stride = points.size() / F;

    // the mean pose: the centre of the magnified displacements (the first frame if out of reach)
    Pose mean = Pose::Zero();
    for (const Pose& p : motion.p) mean += p / static_cast<double>(N);
    std::vector<long long> reference;
    if (drawRobot(model, data, mean, drawing)) {
        appendPoints(drawing, reference);
    } else {
        reference.assign(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(stride));
    }

    // plots: min and max of every bucket of samples, so that no peak is lost
    std::vector<double> peak_tau;
    const std::string plots = detail::plotsJson(motion.t, motion.u, motion.tau, n, peak_tau);

    // what comes from files (names) goes through nlohmann::json, then scriptSafe
    nlohmann::json meta;
    meta["robot"] = model.description.name;
    meta["source"] = motion.source;
    meta["samples"] = N;
    meta["duration"] = duration;
    meta["tEnd"] = t_end;
    meta["slowMotion"] = slow;
    meta["magnify"] = options.magnify;
    meta["warnings"] = motion.warnings;
    nlohmann::json layout = nlohmann::json::array(), actuators = nlohmann::json::array();
    std::size_t offset = 0;
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        nlohmann::json joints = nlohmann::json::array();
        for (int k = 0; k < 3; ++k) {
            const bool prismatic = limb.type[static_cast<std::size_t>(k)] == JointType::prismatic;
            joints.push_back({{"pos", offset},
                              {"rail", prismatic ? static_cast<long long>(offset + 2) : -1LL},
                              {"actuator", limb.actuator[static_cast<std::size_t>(k)]}});
            offset += prismatic ? 6 : 2;
        }
        layout.push_back(joints);
    }
    for (int a = 0; a < n; ++a) {
        const auto j = static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)]);
        const auto k = static_cast<std::size_t>(model.actuator_joint[static_cast<std::size_t>(a)]);
        const bool prismatic = model.limb[j].type[k] == JointType::prismatic;
        const double effort = model.limb[j].limits[k].effort;
        nlohmann::json entry = {{"limb", model.description.limbs[j].name},
                                {"joint", k + 1},
                                {"unit", prismatic ? "m" : "rad"},
                                {"forceUnit", prismatic ? "N" : "N m"},
                                {"peakTau", peak_tau[static_cast<std::size_t>(a)]}};
        entry["effort"] = std::isfinite(effort) ? nlohmann::json(effort) : nlohmann::json(nullptr);
        actuators.push_back(entry);
    }
    meta["layout"] = layout;
    meta["actuators"] = actuators;
    meta["stride"] = stride;

    std::string json =
        detail::scriptSafe(meta.dump(-1, ' ', /*ensure_ascii=*/true, nlohmann::json::error_handler_t::replace));
    json.pop_back();  // the closing brace: the numeric arrays follow
    json += ",\"reference\":";
    detail::appendArray(json, reference, 0);
    json += ",\"frames\":{\"t\":";
    detail::appendArray(json, frame_t, 9);
    json += ",\"points\":";
    detail::appendArray(json, points, 0);
    json += ",\"tau\":";
    detail::appendArray(json, frame_tau, 6);
    if (ghosted) {
        json += ",\"ghost\":";
        detail::appendArray(json, ghost, 0);
    }
    json += "},\"plots\":";
    json += plots;
    json += '}';
    return std::string(kPageHead) + json + kPageTail;
}

Figure frameFigure(const Model& model, const MotionSamples& motion, double t) {
    if (motion.t.empty()) throw Error("no samples to draw");
    const auto at = std::lower_bound(motion.t.begin(), motion.t.end(), t);
    std::size_t k = static_cast<std::size_t>(at - motion.t.begin());
    if (k == motion.t.size() || (k > 0 && t - motion.t[k - 1] < motion.t[k] - t)) --k;
    Data data(model);
    RobotDrawing d;
    if (const Status status = drawRobot(model, data, motion.p[k], d); !status) {
        throw poseError(motion.source + ": ", motion.t[k], status, model);
    }
    PlotPanel panel;
    panel.title = literalText(model.description.name + " at t = " + secondsText(motion.t[k]) + " s");
    panel.xlabel = "x [mm]";  // millimetres, as every other figure
    panel.ylabel = "y [mm]";
    panel.equal_axes = true;
    PlotSeries rails{"rails (stroke)", {}, {}, "lines lw 6 lc rgb '#999999'"};
    PlotSeries links{"links", {}, {}, "linespoints lw 3 pt 7 ps 0.8 lc rgb '#1f4e9c'"};
    PlotSeries platform{"platform", {}, {}, "lines lw 2 lc rgb '#c77800'"};
    PlotSeries c{"C", {}, {}, "points pt 7 ps 1.5 lc rgb '#ff0000'"};
    PlotSeries ghost{"target (ghost)", {}, {}, "lines dt 2 lw 1.5 lc rgb '#888888'"};
    const auto add = [](PlotSeries& s, const Vector2& x) {
        s.x.push_back(1e3 * x.x());
        s.y.push_back(1e3 * x.y());
    };
    const auto gap = [](PlotSeries& s) {  // a blank row: gnuplot breaks the line there
        s.x.push_back(std::numeric_limits<double>::quiet_NaN());
        s.y.push_back(std::numeric_limits<double>::quiet_NaN());
    };
    for (int j = 0; j < d.limbs; ++j) {
        const LimbDrawing& limb = d.limb[static_cast<std::size_t>(j)];
        for (const JointDrawing& joint : limb.joint) {
            if (joint.type != JointType::prismatic) continue;
            add(rails, joint.rail_start);
            add(rails, joint.rail_end);
            gap(rails);
        }
        for (const JointDrawing& joint : limb.joint) add(links, joint.position);
        gap(links);
        add(platform, d.platform[static_cast<std::size_t>(j)]);
    }
    add(platform, d.platform[0]);
    add(c, d.C);
    if (motion.ghost.size() == motion.t.size()) {
        RobotDrawing g;
        if (const Status status = drawRobot(model, data, motion.ghost[k], g); !status) {
            throw poseError(motion.source + ": the target: ", motion.t[k], status, model);
        }
        for (int j = 0; j < g.limbs; ++j) {
            for (const JointDrawing& joint : g.limb[static_cast<std::size_t>(j)].joint) add(ghost, joint.position);
            gap(ghost);
        }
        for (int j = 0; j < g.limbs; ++j) add(ghost, g.platform[static_cast<std::size_t>(j)]);
        add(ghost, g.platform[0]);
    }
    if (!rails.x.empty()) panel.series.push_back(rails);
    panel.series.push_back(links);
    panel.series.push_back(platform);
    panel.series.push_back(c);
    if (!ghost.x.empty()) panel.series.push_back(ghost);
    Figure figure{literalText("nocdyn: " + model.description.name), {panel}, 800, 760};
    return figure;
}

}  // namespace nocdyn::render
