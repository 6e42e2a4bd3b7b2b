// Operating envelope of a spatial robot: bracketing and bisection on the sinusoid's amplitude,
// the period checked with the spatial inverse dynamics and every freedom's limits.
#include "nocdyn/analysis/spatial_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <string>

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::spatial {

namespace {

/// Bracketing steps (each doubles or halves A) and bisection passes at most.
constexpr int kMaxBracketSteps = 80;
constexpr int kMaxBisections = 200;
/// The search bound: no translation beyond 10 m; no rotation beyond 1.5 rad (pitch = +-90
/// degrees is singular for the Euler angles).
constexpr double kMaxTranslation = 10.0, kMaxRotation = 1.5;
/// Where the bracketing starts without a hint [m or rad].
constexpr double kFirstAmplitude = 1e-3;

/// The share of a range used by q (q = 0 at home): q / upper on the upper side, q / lower on
/// the lower (0 for an unbounded side).
double rangeUse(double q, const JointLimits& limits) {
    const double bound = q > 0.0 ? limits.upper : limits.lower;
    if (q == 0.0 || !std::isfinite(bound)) return 0.0;
    if (q * bound <= 0.0) return std::numeric_limits<double>::infinity();  // home on that side's bound
    return q / bound;
}

/// |value| / limit, 0 for an unlimited one.
double share(double value, double limit) { return std::isfinite(limit) ? std::abs(value) / limit : 0.0; }

/// Keeps the larger term of the ratio with where it comes from.
void consider(EnvelopePoint& use, double ratio, EnvelopeLimit limit, int limb, const Freedom& f) {
    if (!(ratio > use.peak_ratio)) return;
    use.peak_ratio = ratio;
    use.limit = limit;
    use.limb = limb;
    use.joint = f.joint;
    use.actuator = limit == EnvelopeLimit::effort || f.actuator >= 0 ? f.actuator : -1;
}

void checkFrequency(double frequency, const char* what) {
    if (frequency >= kEnvelopeMinFrequency && frequency <= kEnvelopeMaxFrequency) return;
    throw Error(text::format("envelope: %s must be in [%g, %g] Hz, got %g", what, kEnvelopeMinFrequency,
                             kEnvelopeMaxFrequency, frequency));
}

}  // namespace

EnvelopePoint limitUse(const Model& model, Data& data, int axis, double frequency, double amplitude,
                       int samples_per_period, bool dynamic) {
    EnvelopePoint use;
    use.axis = axis;
    use.frequency = frequency;
    use.amplitude = amplitude;
    const double w = 2.0 * std::numbers::pi * frequency;
    // every period is traced from home, as a fresh Data would: a period that failed far away
    // must not leave the next one's first solve a far previous solution (a revolute joint's
    // Newton could close a turn away from home)
    for (LimbData& ld : data.limb) {
        ld.closed = false;
        ld.q.setZero();
    }
    TaskVector p = model.home, dp = TaskVector::Zero(model.task_dimension), ddp = dp;
    for (int k = 0; k < samples_per_period; ++k) {
        const double phase = 2.0 * std::numbers::pi * k / samples_per_period;
        // p_a = home_a + A sin(w t), dp_a = A w cos(w t), ddp_a = -A w^2 sin(w t)
        p(axis) = model.home(axis) + amplitude * std::sin(phase);
        if (dynamic) {
            dp(axis) = amplitude * w * std::cos(phase);
            ddp(axis) = -amplitude * w * w * std::sin(phase);
        }
        const Status status = inverseDynamics(model, data, p, dp, ddp);
        if (!status.ok()) {  // out of reach or singular: beyond the workspace
            use.peak_ratio = std::numeric_limits<double>::infinity();
            use.limit = EnvelopeLimit::workspace;
            use.limb = status.limb;
            use.joint = use.actuator = -1;
            return use;
        }
        for (int j = 0; j < model.limbs(); ++j) {
            const Limb& limb = model.limb[static_cast<std::size_t>(j)];
            const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
            for (int i = 0; i < limb.size(); ++i) {
                const Freedom& f = limb.freedoms[static_cast<std::size_t>(i)];
                consider(use, rangeUse(ld.q(i), f.limits), EnvelopeLimit::range, j, f);
                if (!dynamic) continue;
                consider(use, share(ld.gd(i), f.limits.velocity), EnvelopeLimit::velocity, j, f);
                if (f.actuator < 0) continue;
                const double effort = share(data.tau(f.actuator), f.limits.effort);
                use.peak_effort_ratio = std::max(use.peak_effort_ratio, effort);
                consider(use, effort, EnvelopeLimit::effort, j, f);
            }
        }
        for (int a = 0; a < model.actuators; ++a) {
            use.peak_u = std::max(use.peak_u, std::abs(data.u(a)));
            use.peak_tau = std::max(use.peak_tau, std::abs(data.tau(a)));
        }
    }
    return use;
}

namespace {

/// The largest A in (0, bound] with limit use at most 1 (see the header): bracketing from
/// `start`, then bisection to (hi - lo) <= tolerance hi. The point at the answer, its limit the
/// one that passes first above it (none when the bound is within every limit).
EnvelopePoint largestWithin(const Model& model, Data& data, int axis, double frequency, double start,
                            const nocdyn::EnvelopeOptions& options, bool dynamic) {
    const double bound = axis < 3 ? kMaxTranslation : kMaxRotation;
    const auto use = [&](double a) {
        if (options.poll) options.poll();
        return limitUse(model, data, axis, frequency, a, options.samples_per_period, dynamic);
    };
    double lo = 0.0, hi = 0.0;
    EnvelopePoint at_lo = use(0.0), at_hi;
    double a = std::clamp(start, 1e-12, bound);
    for (int step = 0; step < kMaxBracketSteps; ++step) {
        EnvelopePoint u = use(a);
        if (u.peak_ratio <= 1.0) {
            lo = a, at_lo = u;
            if (hi > 0.0 || a >= bound) break;  // bracketed, or within every limit up to the bound
            a = std::min(2.0 * a, bound);
        } else {
            hi = a, at_hi = u;
            if (lo > 0.0) break;
            a *= 0.5;
        }
    }
    if (hi == 0.0) {  // nothing binds up to the bound
        at_lo.limit = EnvelopeLimit::none;
        at_lo.limb = at_lo.joint = at_lo.actuator = -1;
        return at_lo;
    }
    for (int pass = 0; pass < kMaxBisections && hi - lo > options.relative_tolerance * hi; ++pass) {
        const double mid = 0.5 * (lo + hi);
        EnvelopePoint u = use(mid);
        if (u.peak_ratio <= 1.0)
            lo = mid, at_lo = u;
        else
            hi = mid, at_hi = u;
    }
    EnvelopePoint out = at_lo;
    out.limit = at_hi.limit;
    out.limb = at_hi.limb;
    out.joint = at_hi.joint;
    out.actuator = at_hi.actuator;
    return out;
}

}  // namespace

EnvelopePoint maximumAmplitude(const Model& model, int axis, double frequency, const nocdyn::EnvelopeOptions& options,
                               double hint) {
    checkFrequency(frequency, "frequency");
    if (axis < 0 || axis >= model.task_dimension) {
        throw Error("envelope: the robot " + model.name + " has no pose coordinate " + std::to_string(axis + 1));
    }
    if (options.samples_per_period < 8) throw Error("envelope: samples_per_period must be at least 8");
    if (!(options.relative_tolerance > 0.0 && options.relative_tolerance < 1.0)) {
        throw Error("envelope: relative_tolerance must be in (0, 1)");
    }
    Data data(model);
    const EnvelopePoint home = limitUse(model, data, axis, frequency, 0.0, 1, true);
    if (!(home.peak_ratio <= 1.0)) {
        throw Error("envelope: the home posture of " + model.name + " is not within its limits at rest (" +
                    limitName(home.limit) + ", limb " + std::to_string(home.limb + 1) + ")");
    }
    // ranges and workspace alone (independent of f), then every limit below them
    const EnvelopePoint kinematic = largestWithin(model, data, axis, frequency, kFirstAmplitude, options, false);
    const double start = hint > 0.0 ? std::min(hint, kinematic.amplitude) : kinematic.amplitude;
    EnvelopePoint out = largestWithin(model, data, axis, frequency, start, options, true);
    out.kinematic_amplitude = kinematic.amplitude;
    return out;
}

std::vector<EnvelopePoint> operatingEnvelope(const Model& model, const nocdyn::EnvelopeOptions& options) {
    checkFrequency(options.min_frequency, "min_frequency");
    checkFrequency(options.max_frequency, "max_frequency");
    if (options.max_frequency < options.min_frequency) throw Error("envelope: max_frequency is below min_frequency");
    if (options.points < 1 || options.points > kEnvelopeMaxPoints) {
        throw Error("envelope: the number of frequencies must be in [1, " + std::to_string(kEnvelopeMaxPoints) +
                    "], got " + std::to_string(options.points));
    }
    std::vector<EnvelopePoint> points;
    const int total = model.task_dimension * options.points;
    for (int axis = 0; axis < model.task_dimension; ++axis) {
        double hint = 0.0;
        for (int k = 0; k < options.points; ++k) {
            const double s = options.points > 1 ? static_cast<double>(k) / (options.points - 1) : 0.0;
            const double f = options.min_frequency * std::pow(options.max_frequency / options.min_frequency, s);
            points.push_back(maximumAmplitude(model, axis, f, options, hint));
            hint = points.back().amplitude;
            if (options.progress) options.progress(static_cast<int>(points.size()), total);
        }
    }
    return points;
}

}  // namespace nocdyn::spatial
