// A three-component ground motion on a six-DOF table (see spatial_shake.hpp).
#include "nocdyn/sim/spatial_shake.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <string>

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::spatial {

SpatialRobotDescription withSpecimen(SpatialRobotDescription description, double mass) {
    if (!(mass >= 0.0 && std::isfinite(mass))) throw Error("specimen: mass must be >= 0, got " + text::number(mass));
    if (mass == 0.0) return description;
    SpatialBodyDescription& p = description.platform;
    // the specimen a point mass at the platform frame's origin: the combined c.o.m. c and the
    // inertia about it, I = I_p + m_p S(c_p - c) + m S(-c), S(r) = |r|^2 1 - r r^T
    const double total = p.mass + mass;
    const Eigen::Vector3d c = p.mass * p.com / total;
    const auto shift = [](const Eigen::Vector3d& r) {
        return Eigen::Matrix3d(r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    };
    p.inertia = p.inertia + p.mass * shift(p.com - c) + mass * shift(-c);
    p.com = c;
    p.mass = total;
    return description;
}

namespace {

/// Folds one sample into `worst`: |u - centre| / ((1 - margin) half-stroke), |du| / ((1 -
/// margin) rate limit), |tau| / ((1 - margin) force limit), each actuator's finite limits.
void accumulate(const Model& model, double t, const Data& data, double margin, LimitUse& worst) {
    const double keep = 1.0 - margin;
    for (int a = 0; a < model.actuators; ++a) {
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a)];
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const JointLimits& lim = limb.freedoms[static_cast<std::size_t>(k)].limits;
        const auto consider = [&](double ratio, const char* which) {
            if (ratio > worst.ratio) {
                std::string what = "actuator ";
                what += std::to_string(a + 1);
                what += " (";
                what += limb.name;
                what += ") ";
                what += which;
                worst = {ratio, std::move(what), t};
            }
        };
        if (std::isfinite(lim.lower) && std::isfinite(lim.upper)) {
            const double centre = 0.5 * (lim.lower + lim.upper), half = 0.5 * (lim.upper - lim.lower);
            consider(std::abs(data.u(a) - centre) / (keep * half), "stroke");
        }
        if (std::isfinite(lim.velocity)) consider(std::abs(data.du(a)) / (keep * lim.velocity), "rate");
        if (std::isfinite(lim.effort)) consider(std::abs(data.tau(a)) / (keep * lim.effort), "force");
    }
}

bool limitCode(const Status& status) {
    return status.code == StatusCode::joint_limit_exceeded || status.code == StatusCode::effort_exceeded ||
           status.code == StatusCode::velocity_exceeded;
}

/// The fitted motion of the filtered record at time scale L and amplitudes A.
struct Scaled {
    std::vector<double> t;
    std::array<std::vector<double>, 3> a;
    Trajectory trajectory;
};

Scaled scale(const Model& model, const GroundRecord3& filtered, double L, const std::array<double, 3>& A) {
    Scaled s;
    const std::size_t n = filtered.a[0].size();
    s.t.resize(n);
    for (std::size_t i = 0; i < n; ++i) s.t[i] = static_cast<double>(i) * filtered.dt / L;
    s.trajectory.name = "record";
    s.trajectory.dimension = model.task_dimension;
    for (int i = 0; i < model.task_dimension; ++i)
        s.trajectory.axis[static_cast<std::size_t>(i)].offset = model.home(i);
    for (std::size_t axis = 0; axis < 3; ++axis) {
        std::vector<double>& out = s.a[axis];
        out.resize(n);
        for (std::size_t i = 0; i < n; ++i) out[i] = A[axis] * filtered.a[axis][i];
        const bool still = std::all_of(out.begin(), out.end(), [](double v) { return v == 0.0; });
        if (!still) {
            s.trajectory.sampled[axis] = std::make_shared<const SampledAxis>(
                baselineCorrectedAxis(s.t, out, model.home(static_cast<Eigen::Index>(axis))));
        }
    }
    s.trajectory.duration = s.t.back();
    return s;
}

}  // namespace

LimitUse limitUse(const Model& model, const Trajectory& trajectory, double duration, double step, double margin) {
    Data data(model);
    LimitUse worst;
    const auto steps = static_cast<std::size_t>(std::ceil(duration / step));
    TaskVector p, dp, ddp;
    for (std::size_t k = 0; k <= steps; ++k) {
        const double t = std::min(duration, static_cast<double>(k) * step);
        trajectory.evaluate(t, p, dp, ddp);
        const Status status = inverseDynamics(model, data, p, dp, ddp);
        if (!status.ok() && !limitCode(status))
            return {std::numeric_limits<double>::infinity(), describe(status, model), t};
        accumulate(model, t, data, margin, worst);
    }
    return worst;
}

FittedRecord3 fitRecord(const Model& model, const GroundRecord3& record, const FitOptions& options, bool per_axis) {
    if (model.task_dimension != 6) throw Error(model.name + ": a six-DOF table (motion: full) is needed");
    const std::size_t n = record.a[0].size();
    if (n < 4) throw Error("record: at least 4 samples are needed");
    for (const std::vector<double>& a : record.a) {
        if (a.size() != n) throw Error("record: the components have different lengths");
        if (!std::all_of(a.begin(), a.end(), [](double v) { return std::isfinite(v); }))
            throw Error("record: an acceleration is not finite");
    }
    if (!(options.margin >= 0.0 && options.margin < 1.0)) throw Error("record: margin must be in [0, 1)");
    if (!(options.max_time_scale >= 1.0)) throw Error("record: the largest time scale must be at least 1");
    GroundRecord3 filtered = record;
    if (options.highpass > 0.0) {
        for (std::vector<double>& a : filtered.a) a = highPassZeroPhase(a, record.dt, options.highpass);
    }
    const auto use = [&](double L, const std::array<double, 3>& A) {
        const Scaled s = scale(model, filtered, L, A);
        return limitUse(model, s.trajectory, s.t.back(), record.dt / L, options.margin);  // at each sample
    };
    const auto fits = [&](double L, const std::array<double, 3>& A) { return use(L, A).ratio <= 1.0; };
    constexpr std::array<double, 3> kOne{1.0, 1.0, 1.0};
    double L = options.time_scale.value_or(1.0);
    if (options.time_scale) {
        if (!(L >= 1e-3 && L <= 1e4)) throw Error("record: time scale " + text::number(L) + " outside [0.001, 10000]");
    } else if (!fits(1.0, kOne)) {
        // the least L that fits: doubling, then bisection to 0.1 %
        double lo = 1.0, hi = 2.0;
        while (hi < options.max_time_scale && !fits(hi, kOne)) {
            lo = hi;
            hi *= 2.0;
        }
        hi = std::min(hi, options.max_time_scale);
        if (fits(hi, kOne)) {
            for (int k = 0; k < 60 && hi - lo > 1e-3 * hi; ++k) {
                const double mid = 0.5 * (lo + hi);
                (fits(mid, kOne) ? hi : lo) = mid;
            }
        }
        L = hi;
    }
    // the largest factor c in [1e-4, 1] at which `shape` times c fits at L (geometric bisection)
    constexpr double kMinAmplitude = 1e-4;
    const auto largest = [&](const std::array<double, 3>& shape) {
        if (fits(L, shape)) return 1.0;
        const std::array<double, 3> smallest{kMinAmplitude * shape[0], kMinAmplitude * shape[1],
                                             kMinAmplitude * shape[2]};
        if (const LimitUse u = use(L, smallest); !(u.ratio <= 1.0)) {
            throw Error("record: cannot be fitted even at amplitude " + text::number(kMinAmplitude) +
                        " and time scale " + text::number(L) + ": " + u.what + " at " + text::number(100.0 * u.ratio) +
                        " % of its limit (with " + text::number(100.0 * options.margin) + " % margin) at " +
                        text::sampleTime(u.t));
        }
        double lo = kMinAmplitude, hi = 1.0;
        for (int k = 0; k < 60 && hi - lo > 1e-3 * lo; ++k) {
            const double mid = std::sqrt(lo * hi);
            (fits(L, {mid * shape[0], mid * shape[1], mid * shape[2]}) ? lo : hi) = mid;
        }
        return lo;
    };
    std::array<double, 3> A = kOne;
    if (per_axis && !fits(L, kOne)) {
        // each axis as large as it fits alone, then the three together by one factor
        for (std::size_t axis = 0; axis < 3; ++axis) {
            std::array<double, 3> alone{0.0, 0.0, 0.0};
            alone[axis] = 1.0;
            const bool moves =
                std::any_of(filtered.a[axis].begin(), filtered.a[axis].end(), [](double v) { return v != 0.0; });
            A[axis] = moves ? largest(alone) : 1.0;
        }
    }
    const double c = largest(A);
    for (double& a : A) a *= c;
    Scaled s = scale(model, filtered, L, A);
    FittedRecord3 fit;
    fit.time_scale = L;
    fit.amplitude = A;
    fit.per_axis = per_axis;
    fit.dt = record.dt / L;
    fit.use = limitUse(model, s.trajectory, s.t.back(), fit.dt, options.margin);
    fit.t = std::move(s.t);
    fit.a = std::move(s.a);
    fit.trajectory = std::move(s.trajectory);
    return fit;
}

namespace {

/// The replay's loop scored against out.fit (see the header comment): the achieved
/// accelerations, each moving axis's scores, the rotations' parasitic motion, the limits' use.
void scoreLoop(const Model& model, const LoopOptions& loop, double highpass, ShakeReplay3& out) {
    const FittedRecord3& f = out.fit;
    const LoopResult& r = out.loop;
    if (r.t.size() < 3) throw Error("replay: the record is shorter than three controller ticks");
    // the achieved accelerations: (p(t + h) - 2 p(t) + p(t - h)) / h^2 over ~0.5 ms, at f.t
    const double tick = 1.0 / loop.rate;
    std::vector<Pose> xyz(r.p.size());
    for (std::size_t k = 0; k < r.p.size(); ++k) xyz[k] = r.p[k].head<3>();
    const int span = std::max(1, static_cast<int>(std::lround(5e-4 * loop.rate)));
    out.achieved = poseAcceleration(xyz, tick, f.t, span);
    // the record's passband in replay time: [2 f_highpass (or 2 / duration), 0.4 / dt] in record time
    const double record_dt = f.dt * f.time_scale;
    const double f_lo = std::max(2.0 * highpass, 2.0 / (record_dt * static_cast<double>(f.t.size() - 1)));
    const double f_hi = 0.4 / record_dt;
    out.period_min = 1.0 / (f.time_scale * f_hi);
    out.period_max = 1.0 / (f.time_scale * f_lo);
    const std::size_t n = std::min(f.t.size(), static_cast<std::size_t>(r.t.back() / f.dt) + 1);
    for (std::size_t axis = 0; axis < 3; ++axis) {
        ShakeScore& score = out.score[axis];
        const bool still = std::all_of(f.a[axis].begin(), f.a[axis].end(), [](double v) { return v == 0.0; });
        if (still) continue;
        score = scoreShake(std::span(f.a[axis]).first(n), std::span(out.achieved[axis]).first(n), f.dt, out.period_min,
                           out.period_max);
        std::vector<double> d_target, d_achieved;
        d_target.reserve(r.t.size());
        d_achieved.reserve(r.t.size());
        for (std::size_t k = 0; k < r.t.size(); ++k) {
            d_target.push_back(r.p_d[k](static_cast<Eigen::Index>(axis)));
            d_achieved.push_back(r.p[k](static_cast<Eigen::Index>(axis)));
        }
        score.displacement_error = relativeRmsError(d_target, d_achieved, model.home(static_cast<Eigen::Index>(axis)));
    }
    // the rotations' parasitic motion, and the legs' use of their limits in the loop
    Data data(model);
    for (std::size_t k = 0; k < r.t.size(); ++k) {
        for (std::size_t i = 0; i < 3; ++i) {
            const auto c = static_cast<Eigen::Index>(3 + i);
            out.parasitic[i] = std::max(out.parasitic[i], std::abs(r.p[k](c) - model.home(c)));
        }
        data.u = r.u[k];
        data.tau = r.tau[k];
        // the rate from the neighbouring ticks (the loop keeps u, not du)
        const std::size_t a = k == 0 ? 0 : k - 1, b = std::min(k + 1, r.t.size() - 1);
        data.du = (r.u[b] - r.u[a]) / (r.t[b] - r.t[a]);
        accumulate(model, r.t[k], data, 0.0, out.achieved_use);
    }
}

/// The closed loop of `loop` along `drive` for the fit's duration, timed into out.seconds.
LoopResult playDrive(const Model& model, const Trajectory& drive, LoopOptions loop, double duration, double& seconds) {
    loop.duration = duration;
    const auto start = std::chrono::steady_clock::now();
    LoopResult result = runPoseLoop(model, drive, loop);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace

ShakeReplay3 replayRecord(const Model& model, FittedRecord3 fit, LoopOptions loop, double highpass) {
    ShakeReplay3 out;
    out.fit = std::move(fit);
    out.loop = playDrive(model, out.fit.trajectory, loop, out.fit.t.back(), out.seconds);
    scoreLoop(model, loop, highpass, out);
    return out;
}

namespace {

/// A pass's relative RMS error per axis [x, y, z] (0 on a still axis) and its worst.
double passErrors(const ShakeReplay3& r, DriveIterationPasses& passes) {
    std::array<double, 3> rms{};
    for (std::size_t axis = 0; axis < 3; ++axis) rms[axis] = r.score[axis].rms_error;
    passes.rms.push_back(rms);
    passes.worst.push_back(*std::max_element(rms.begin(), rms.end()));
    return passes.worst.back();
}

/// The drive of the next pass: d += g (a_target - a_achieved) on each moving axis over the
/// samples the last loop covered.
void correctDrive3(const ShakeReplay3& last, double gain, std::array<std::vector<double>, 3>& drive) {
    const FittedRecord3& f = last.fit;
    const std::size_t n = std::min(f.t.size(), static_cast<std::size_t>(last.loop.t.back() / f.dt) + 1);
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (last.score[axis].periods.empty()) continue;  // still
        addDriveCorrection(std::span(drive[axis]).first(n), std::span(f.a[axis]).first(n),
                           std::span(last.achieved[axis]).first(n), gain);
    }
}

}  // namespace

ShakeReplay3 iterateReplay(const Model& model, FittedRecord3 fit, const LoopOptions& loop, double highpass,
                           const DriveIterationOptions& options, DriveIterationPasses& passes) {
    if (!(options.iteration_gain > 0.0 && options.iteration_gain <= 1.0))
        throw Error("drive iteration: the gain must be in (0, 1]");
    passes = {};
    const double duration = fit.t.back();
    // the passes' progress one after the other: pass i reports i duration + t
    const auto passLoop = [&loop, duration](int pass) {
        LoopOptions l = loop;
        if (loop.progress) {
            l.progress = [&loop, offset = duration * pass](double t) { loop.progress(offset + t); };
        }
        return l;
    };
    ShakeReplay3 best = replayRecord(model, std::move(fit), passLoop(0), highpass);
    passErrors(best, passes);
    std::array<std::vector<double>, 3> drive = best.fit.a;
    ShakeReplay3 last_pass;  // the last pass when it is not the best (its achieved accelerations)
    const ShakeReplay3* last = &best;
    for (int pass = 1; pass <= options.iterations; ++pass) {
        correctDrive3(*last, options.iteration_gain, drive);
        const FittedRecord3& target = best.fit;
        GroundRecord3 next;
        next.dt = target.dt * target.time_scale;
        next.a = drive;
        const FittedRecord3 refit = fitRecord(model, next, driveFitOptions(options.fit, target.time_scale));
        if (std::any_of(refit.amplitude.begin(), refit.amplitude.end(), [](double a) { return a < 1.0; })) {
            passes.stop = driveLeavesLimits(pass);
            break;
        }
        ShakeReplay3 r;
        r.fit = target;
        r.loop = playDrive(model, refit.trajectory, passLoop(pass), duration, r.seconds);
        // scored against the target: its pose at each tick is the reference the displacement is scored on
        TaskVector p, dp, ddp;
        for (std::size_t k = 0; k < r.loop.t.size(); ++k) {
            target.trajectory.evaluate(r.loop.t[k], p, dp, ddp);
            r.loop.p_d[k] = p;
        }
        scoreLoop(model, loop, highpass, r);
        const double best_error = passes.worst[static_cast<std::size_t>(passes.best_pass)];
        const PassJudgement judged = judgePass(pass, passErrors(r, passes), best_error, options.iteration_tolerance);
        if (judged.kept) {
            r.seconds = best.seconds;  // the first pass's wall time, as the replay reports it
            best = std::move(r);
            passes.best_pass = pass;
            last = &best;
        } else {
            last_pass = std::move(r);
            last = &last_pass;
        }
        if (!judged.stop.empty()) {
            passes.stop = judged.stop;
            break;
        }
    }
    if (options.iterations > 0 && passes.stop.empty()) passes.stop = kLastPassAsked;
    return best;
}

}  // namespace nocdyn::spatial
