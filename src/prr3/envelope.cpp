// Operating envelope: bisection on the sinusoid amplitude with the inverse dynamics (eq. 20).
#include "nocdyn/prr3/envelope.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "nocdyn/error.hpp"
#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"

namespace nocdyn::prr3 {

const char* axisName(Axis axis) {
    switch (axis) {
        case Axis::theta:
            return "theta";
        case Axis::x:
            return "x";
        case Axis::y:
            return "y";
    }
    return "?";
}

const char* limitName(BindingLimit limit) {
    switch (limit) {
        case BindingLimit::stroke:
            return "stroke";
        case BindingLimit::force:
            return "force";
        case BindingLimit::workspace:
            return "workspace";
    }
    return "?";
}

namespace {

/// Bisection passes at most (2^-200 of the initial interval is far below any tolerance).
constexpr int kMaxBisections = 200;

/// Requires a frequency in [kEnvelopeMinFrequency, kEnvelopeMaxFrequency].
void checkFrequency(double frequency, const char* what) {
    if (frequency >= kEnvelopeMinFrequency && frequency <= kEnvelopeMaxFrequency) return;
    std::ostringstream msg;
    msg << "envelope: " << what << " must be in [" << kEnvelopeMinFrequency << ", " << kEnvelopeMaxFrequency
        << "] Hz, got " << frequency;
    throw Error(msg.str());
}

/// One period of A sin(2 pi f t) along `axis`. With `forces`, the inverse dynamics and the
/// force check; else positions (and conditioning) and the stroke check only. Returns the
/// first violation; peaks of |u| and |tau| in `peak_stroke` and `peak_force`.
Status checkPeriod(const Model& model, Data& data, Axis axis, double frequency, double amplitude, int samples,
                   bool forces, double& peak_stroke, double& peak_force) {
    const double w = 2.0 * std::numbers::pi * frequency;
    const int index = static_cast<int>(axis);
    peak_stroke = peak_force = 0.0;
    for (int k = 0; k < samples; ++k) {
        const double phase = 2.0 * std::numbers::pi * k / samples;
        Pose p = Pose::Zero();
        Twist dp = Twist::Zero(), ddp = Twist::Zero();
        p(index) = amplitude * std::sin(phase);
        dp(index) = amplitude * w * std::cos(phase);
        ddp(index) = -amplitude * w * w * std::sin(phase);
        if (const Status status = inverseDynamics(model, data, p, dp, ddp); !status) return status;
        peak_stroke = std::max(peak_stroke, data.u.cwiseAbs().maxCoeff());
        if (const Status status = checkStroke(model, data); !status) return status;
        if (!forces) continue;
        peak_force = std::max(peak_force, data.tau.cwiseAbs().maxCoeff());
        if (const Status status = checkForce(model, data); !status) return status;
    }
    return {};
}

/// Largest feasible amplitude in [lo, hi] (lo feasible, hi not); the status at the final hi.
double bisect(const Model& model, Data& data, Axis axis, double frequency, double lo, double hi, bool forces,
              const EnvelopeOptions& options, Status& failure) {
    double stroke = 0.0, force = 0.0;
    // Each pass halves [lo, hi]: kMaxBisections passes end any interval of doubles.
    for (int pass = 0; pass < kMaxBisections && hi - lo > options.relative_tolerance * hi; ++pass) {
        const double mid = 0.5 * (lo + hi);
        const Status status =
            checkPeriod(model, data, axis, frequency, mid, options.samples_per_period, forces, stroke, force);
        if (status) {
            lo = mid;
        } else {
            hi = mid;
            failure = status;
        }
    }
    return lo;
}

}  // namespace

EnvelopePoint maximumAmplitude(const Model& model, Axis axis, double frequency, const EnvelopeOptions& options) {
    checkFrequency(frequency, "frequency");
    if (options.samples_per_period < 8 || options.samples_per_period > 65536) {
        throw Error("envelope: samples_per_period must be in [8, 65536]");
    }
    if (!(options.relative_tolerance >= 1e-15 && options.relative_tolerance <= 0.5)) {
        throw Error("envelope: relative_tolerance must be in [1e-15, 0.5]");
    }
    Data data;
    EnvelopePoint point;
    point.axis = axis;
    point.frequency = frequency;
    double stroke = 0.0, force = 0.0;

    // Kinematic limit: an amplitude far beyond any stroke must fail (1 rad, or the link length).
    const double upper = axis == Axis::theta ? 1.0 : model.l;
    Status kinematic =
        checkPeriod(model, data, axis, frequency, upper, options.samples_per_period, false, stroke, force);
    if (kinematic)
        throw Error(std::string("envelope: amplitude ") + std::to_string(upper) + " along " + axisName(axis) +
                    " is not limited by the stroke");
    point.kinematic_amplitude = bisect(model, data, axis, frequency, 0.0, upper, false, options, kinematic);

    Status failure;
    if (checkPeriod(model, data, axis, frequency, point.kinematic_amplitude, options.samples_per_period, true, stroke,
                    force)) {
        point.amplitude = point.kinematic_amplitude;
        failure = kinematic;
        point.limit = kinematic.code == StatusCode::stroke_exceeded ? BindingLimit::stroke : BindingLimit::workspace;
    } else {
        point.amplitude = bisect(model, data, axis, frequency, 0.0, point.kinematic_amplitude, true, options, failure);
        point.limit = failure.code == StatusCode::force_exceeded    ? BindingLimit::force
                      : failure.code == StatusCode::stroke_exceeded ? BindingLimit::stroke
                                                                    : BindingLimit::workspace;
    }
    point.limb = failure.limb;
    (void)checkPeriod(model, data, axis, frequency, point.amplitude, options.samples_per_period, true,
                      point.peak_stroke, point.peak_force);
    return point;
}

std::vector<EnvelopePoint> operatingEnvelope(const Model& model, const EnvelopeOptions& options) {
    checkFrequency(options.min_frequency, "min_frequency");
    checkFrequency(options.max_frequency, "max_frequency");
    if (options.max_frequency < options.min_frequency) throw Error("envelope: max_frequency is below min_frequency");
    if (options.frequencies < 1 || options.frequencies > kEnvelopeMaxPoints) {
        throw Error("envelope: the number of frequencies must be in [1, " + std::to_string(kEnvelopeMaxPoints) +
                    "], got " + std::to_string(options.frequencies));
    }
    std::vector<EnvelopePoint> points;
    for (const Axis axis : {Axis::theta, Axis::x, Axis::y}) {
        for (int k = 0; k < options.frequencies; ++k) {
            const double s = options.frequencies > 1 ? static_cast<double>(k) / (options.frequencies - 1) : 0.0;
            const double f = options.min_frequency * std::pow(options.max_frequency / options.min_frequency, s);
            points.push_back(maximumAmplitude(model, axis, f, options));
        }
    }
    return points;
}

}  // namespace nocdyn::prr3
