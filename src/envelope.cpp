// Operating envelope of any robot: bisection on the sinusoid amplitude with the inverse
// dynamics (eq. 20) and every joint's limits.
#include "nocdyn/envelope.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"

namespace nocdyn {

const char* axisName(EnvelopeAxis axis) {
    switch (axis) {
        case EnvelopeAxis::theta:
            return "theta";
        case EnvelopeAxis::x:
            return "x";
        case EnvelopeAxis::y:
            return "y";
    }
    return "?";
}

const char* limitName(EnvelopeLimit limit) {
    switch (limit) {
        case EnvelopeLimit::range:
            return "range";
        case EnvelopeLimit::velocity:
            return "velocity";
        case EnvelopeLimit::effort:
            return "effort";
        case EnvelopeLimit::workspace:
            return "workspace";
        case EnvelopeLimit::none:
            return "none";
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

/// The limit a failed Status stands for.
EnvelopeLimit limitOf(const Status& status) {
    switch (status.code) {
        case StatusCode::joint_limit_exceeded:
            return EnvelopeLimit::range;
        case StatusCode::velocity_exceeded:
            return EnvelopeLimit::velocity;
        case StatusCode::effort_exceeded:
            return EnvelopeLimit::effort;
        case StatusCode::ok:
            return EnvelopeLimit::none;
        default:
            return EnvelopeLimit::workspace;
    }
}

/// max_a |tau_a| / effort_a over the actuators with an effort limit.
double effortRatio(const Model& model, const Data& data) {
    double ratio = 0.0;
    for (int a = 0; a < model.actuators; ++a) {
        const auto j = static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)]);
        const auto k = static_cast<std::size_t>(model.actuator_joint[static_cast<std::size_t>(a)]);
        const double effort = model.limb[j].limits[k].effort;
        if (std::isfinite(effort)) ratio = std::max(ratio, std::abs(data.tau(a)) / effort);
    }
    return ratio;
}

/// The sinusoid's samples over one period, checked in order.
class Period {
public:
    Period(const Model& model, EnvelopeAxis axis, double frequency, int samples)
        : model_(model),
          data_(model),
          index_(static_cast<int>(axis)),
          w_(2.0 * std::numbers::pi * frequency),
          samples_(samples) {}

    /// First violation of one period at amplitude A; dynamic: rates, accelerations and the
    /// effort check, else poses at rest (ranges and the workspace only).
    Status check(double amplitude, bool dynamic) {
        peak_effort_ratio = 0.0;
        peak_u = 0.0;
        peak_tau = 0.0;
        for (int k = 0; k < samples_; ++k) {
            const double phase = 2.0 * std::numbers::pi * k / samples_;
            Pose p = model_.home;
            Twist dp = Twist::Zero(), ddp = Twist::Zero();
            p(index_) += amplitude * std::sin(phase);
            if (dynamic) {
                dp(index_) = amplitude * w_ * std::cos(phase);
                ddp(index_) = -amplitude * w_ * w_ * std::sin(phase);
            }
            if (const Status status = inverseDynamics(model_, data_, p, dp, ddp); !status) return status;
            if (const Status status = checkJointLimits(model_, data_); !status) return status;
            if (!dynamic) continue;
            peak_effort_ratio = std::max(peak_effort_ratio, effortRatio(model_, data_));
            peak_u = std::max(peak_u, data_.u.cwiseAbs().maxCoeff());
            peak_tau = std::max(peak_tau, data_.tau.cwiseAbs().maxCoeff());
            if (const Status status = checkEffort(model_, data_); !status) return status;
        }
        return {};
    }

    /// Largest feasible amplitude in [lo, hi] (lo feasible, hi not); `failure` = the status at
    /// the final hi.
    double bisect(double lo, double hi, bool dynamic, double tolerance, Status& failure) {
        // Each pass halves [lo, hi]: kMaxBisections passes end any interval of doubles.
        for (int pass = 0; pass < kMaxBisections && hi - lo > tolerance * hi; ++pass) {
            const double mid = 0.5 * (lo + hi);
            if (const Status status = check(mid, dynamic); status) {
                lo = mid;
            } else {
                hi = mid;
                failure = status;
            }
        }
        return lo;
    }

    double peak_effort_ratio = 0.0;
    double peak_u = 0.0, peak_tau = 0.0;  ///< max |u_a| and |tau_a| over the last dynamic check

private:
    const Model& model_;
    Data data_;
    int index_;
    double w_;
    int samples_;
};

}  // namespace

EnvelopePoint maximumAmplitude(const Model& model, EnvelopeAxis axis, double frequency,
                               const EnvelopeOptions& options) {
    checkFrequency(frequency, "frequency");
    if (options.samples_per_period < 8 || options.samples_per_period > 65536) {
        throw Error("envelope: samples_per_period must be in [8, 65536]");
    }
    if (!(options.relative_tolerance >= 1e-15 && options.relative_tolerance <= 0.5)) {
        throw Error("envelope: relative_tolerance must be in [1e-15, 0.5]");
    }
    Period period(model, axis, frequency, options.samples_per_period);
    EnvelopePoint point;
    point.axis = axis;
    point.frequency = frequency;

    // Kinematic limit, searched up to half a turn, or ten times the robot's size.
    const double upper = axis == EnvelopeAxis::theta ? std::numbers::pi : 10.0 * model.length_scale;
    Status kinematic = period.check(upper, false);
    if (!kinematic) {
        if (const Status home = period.check(0.0, false); !home) {
            throw Error("envelope: the robot's home posture is not feasible: " + describe(home, model));
        }
        point.kinematic_amplitude = period.bisect(0.0, upper, false, options.relative_tolerance, kinematic);
    } else {
        point.kinematic_amplitude = upper;
    }

    Status failure;
    if (period.check(point.kinematic_amplitude, true)) {
        point.amplitude = point.kinematic_amplitude;
        failure = kinematic;
    } else {
        if (const Status home = period.check(0.0, true); !home) {
            throw Error("envelope: the robot cannot hold its home posture: " + describe(home, model));
        }
        point.amplitude = period.bisect(0.0, point.kinematic_amplitude, true, options.relative_tolerance, failure);
    }
    point.limit = limitOf(failure);
    point.limb = failure.limb;
    point.joint = failure.joint;
    if (point.limb >= 0 && point.joint >= 0) {
        point.actuator =
            model.limb[static_cast<std::size_t>(point.limb)].actuator[static_cast<std::size_t>(point.joint)];
    }
    (void)period.check(point.amplitude, true);
    point.peak_effort_ratio = period.peak_effort_ratio;
    point.peak_u = period.peak_u;
    point.peak_tau = period.peak_tau;
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
    for (const EnvelopeAxis axis : {EnvelopeAxis::theta, EnvelopeAxis::x, EnvelopeAxis::y}) {
        for (int k = 0; k < options.frequencies; ++k) {
            const double s = options.frequencies > 1 ? static_cast<double>(k) / (options.frequencies - 1) : 0.0;
            const double f = options.min_frequency * std::pow(options.max_frequency / options.min_frequency, s);
            points.push_back(maximumAmplitude(model, axis, f, options));
            if (options.progress) options.progress(static_cast<int>(points.size()), 3 * options.frequencies);
        }
    }
    return points;
}

}  // namespace nocdyn
