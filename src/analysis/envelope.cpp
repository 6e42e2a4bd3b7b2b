// Operating envelope of any robot: bisection on the sinusoid amplitude with the inverse
// dynamics (eq. 20) and every joint's limits; the first natural frequency at home bounds it.
#include "nocdyn/analysis/envelope.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/batch.hpp"
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
        case EnvelopeLimit::resonance:
            return "resonance";
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

/// An actuated joint and its limits, in checkJointLimits' order (limb j, then joint k).
struct ActuatedJoint {
    int limb = -1, joint = -1, actuator = -1;
    JointLimits limits;
};

/// The sinusoid's samples over one period, checked in order.
///
/// Two ways to check a period, the same tests in the same order on the same numbers (to
/// rounding), so the same verdict and first violation:
///   full  per sample the full path (inverseDynamics), checkJointLimits and checkEffort; it
///         also keeps the peaks of u, tau and the effort ratio (the reported numbers);
///   batch the lean kernel four samples at a time (inverseDynamicsBatch: u, du, ddu, tau
///         equal to the full path's to rounding, and the full path's Status for a sample it
///         rejects), a chunk of the period per call so that a violation ends the check
///         early, then the range, velocity and effort tests on u, du and tau; about five
///         times faster. It needs every limited joint to be actuated (u and du are then every
///         limited q and gamma_dot): the bisections use it when they are, the full path
///         otherwise.
class Period {
public:
    Period(const Model& model, EnvelopeAxis axis, double frequency, int samples)
        : model_(model),
          data_(model),
          index_(static_cast<int>(axis)),
          w_(2.0 * std::numbers::pi * frequency),
          samples_(samples),
          sin_(static_cast<std::size_t>(samples)),
          cos_(static_cast<std::size_t>(samples)),
          batch_(limitsOnActuatedJointsOnly(model)) {
        // sin and cos of each sample's phase, once for every check of the period
        for (int k = 0; k < samples_; ++k) {
            const double phase = 2.0 * std::numbers::pi * k / samples_;
            sin_[static_cast<std::size_t>(k)] = std::sin(phase);
            cos_[static_cast<std::size_t>(k)] = std::cos(phase);
        }
        if (!batch_) return;
        for (int j = 0; j < model.limbs; ++j) {
            const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
            for (int k = 0; k < 3; ++k) {
                const int a = limb.actuator[static_cast<std::size_t>(k)];
                if (a >= 0) actuated_.push_back({j, k, a, limb.limits[static_cast<std::size_t>(k)]});
            }
        }
        const Eigen::Index rows = std::min(kChunk, samples_);
        const Eigen::Index n = model.actuators;
        p_.resize(rows, 3);
        dp_.resize(rows, 3);
        ddp_.resize(rows, 3);
        u_.resize(rows, n);
        du_.resize(rows, n);
        ddu_.resize(rows, n);
        tau_.resize(rows, n);
    }

    /// First violation of one period at amplitude A; dynamic: rates, accelerations and the
    /// effort check, else poses at rest (ranges and the workspace only). By the batch when
    /// the robot allows it (the peaks below are then not kept), else as checkFull.
    Status check(double amplitude, bool dynamic) {
        return batch_ ? checkBatch(amplitude, dynamic) : checkFull(amplitude, dynamic);
    }

    /// check on the full path, keeping the peaks below (of a dynamic check).
    Status checkFull(double amplitude, bool dynamic) {
        peak_effort_ratio = 0.0;
        peak_u = 0.0;
        peak_tau = 0.0;
        for (int k = 0; k < samples_; ++k) {
            const double s = sin_[static_cast<std::size_t>(k)];
            Pose p = model_.home;
            Twist dp = Twist::Zero(), ddp = Twist::Zero();
            p(index_) += amplitude * s;
            if (dynamic) {
                dp(index_) = amplitude * w_ * cos_[static_cast<std::size_t>(k)];
                ddp(index_) = -amplitude * w_ * w_ * s;
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
    double bisect(double lo, double hi, bool dynamic, double tolerance, Status& failure,
                  const std::function<void()>& poll) {
        // Each pass halves [lo, hi]: kMaxBisections passes end any interval of doubles.
        for (int pass = 0; pass < kMaxBisections && hi - lo > tolerance * hi; ++pass) {
            if (poll) poll();
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
    double peak_u = 0.0, peak_tau = 0.0;  ///< max |u_a| and |tau_a| over the last checkFull (dynamic)

private:
    /// Samples per call of the batch: short enough that a violation near the start of the
    /// period (the velocity's peak at phase 0, the displacement's and force's at a quarter)
    /// ends the check soon, long enough to keep the kernel's lanes busy.
    static constexpr int kChunk = 32;

    Status checkBatch(double amplitude, bool dynamic) {
        for (int first = 0; first < samples_; first += kChunk) {
            const int rows = std::min(kChunk, samples_ - first);
            for (int i = 0; i < rows; ++i) {
                const auto k = static_cast<std::size_t>(first) + static_cast<std::size_t>(i);
                const double s = sin_[k];
                for (int c = 0; c < 3; ++c) {
                    p_(i, c) = model_.home(c);
                    dp_(i, c) = 0.0;
                    ddp_(i, c) = 0.0;
                }
                p_(i, index_) += amplitude * s;
                if (dynamic) {
                    dp_(i, index_) = amplitude * w_ * cos_[k];
                    ddp_(i, index_) = -amplitude * w_ * w_ * s;
                }
            }
            const BatchResult result =
                inverseDynamicsBatch(model_, p_.topRows(rows), dp_.topRows(rows), ddp_.topRows(rows), u_.topRows(rows),
                                     du_.topRows(rows), ddu_.topRows(rows), tau_.topRows(rows));
            for (int i = 0; i < rows; ++i) {
                if (i == result.first_failure) return result.status;
                if (const Status status = limitsOf(i, dynamic); !status) return status;
            }
        }
        return {};
    }

    /// checkJointLimits and (dynamic) checkEffort of batch row i, from u, du and tau.
    [[nodiscard]] Status limitsOf(int i, bool dynamic) const {
        for (const ActuatedJoint& joint : actuated_) {
            const double q = u_(i, joint.actuator), dq = du_(i, joint.actuator);
            if (!(q >= joint.limits.lower && q <= joint.limits.upper)) {
                Status s{StatusCode::joint_limit_exceeded, joint.limb, q};
                s.joint = joint.joint;
                return s;
            }
            if (!(std::abs(dq) <= joint.limits.velocity)) {
                Status s{StatusCode::velocity_exceeded, joint.limb, dq};
                s.joint = joint.joint;
                return s;
            }
        }
        if (!dynamic) return {};
        for (int a = 0; a < model_.actuators; ++a) {
            const auto aa = static_cast<std::size_t>(a);
            const int j = model_.actuator_limb[aa];
            const int k = model_.actuator_joint[aa];
            const double limit = model_.limb[static_cast<std::size_t>(j)].limits[static_cast<std::size_t>(k)].effort;
            if (!(std::abs(tau_(i, a)) <= limit)) {
                Status s{StatusCode::effort_exceeded, j, tau_(i, a)};
                s.joint = k;
                return s;
            }
        }
        return {};
    }

    const Model& model_;
    Data data_;
    int index_;
    double w_;
    int samples_;
    std::vector<double> sin_, cos_;  ///< of each sample's phase 2 pi k / samples
    bool batch_;
    std::vector<ActuatedJoint> actuated_;  ///< in checkJointLimits' order
    Eigen::ArrayXXd p_, dp_, ddp_;         ///< a chunk's samples, one per row
    Eigen::ArrayXXd u_, du_, ddu_, tau_;   ///< and their inverse dynamics
};

}  // namespace

EnvelopePoint maximumAmplitude(const Model& model, EnvelopeAxis axis, double frequency,
                               const EnvelopeOptions& options) {
    checkFrequency(frequency, "frequency");
    if (!hasAxis(model.task_dimension, axis)) {
        throw Error("envelope: a two-DOF robot (motion: translation) has no theta axis: its pose is [x, y]");
    }
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
        if (const Status home = period.checkFull(0.0, false); !home) {
            throw Error("envelope: the robot's home posture is not feasible: " + describe(home, model));
        }
        point.kinematic_amplitude =
            period.bisect(0.0, upper, false, options.relative_tolerance, kinematic, options.poll);
    } else {
        point.kinematic_amplitude = upper;
    }

    Status failure;
    if (period.check(point.kinematic_amplitude, true)) {
        point.amplitude = point.kinematic_amplitude;
        failure = kinematic;
    } else {
        if (const Status home = period.checkFull(0.0, true); !home) {
            throw Error("envelope: the robot cannot hold its home posture: " + describe(home, model));
        }
        point.amplitude =
            period.bisect(0.0, point.kinematic_amplitude, true, options.relative_tolerance, failure, options.poll);
    }
    point.limit = limitOf(failure);
    point.limb = failure.limb;
    point.joint = failure.joint;
    if (point.limb >= 0 && point.joint >= 0) {
        point.actuator =
            model.limb[static_cast<std::size_t>(point.limb)].actuator[static_cast<std::size_t>(point.joint)];
    }
    // the reported peaks on the full path
    (void)period.checkFull(point.amplitude, true);
    point.peak_effort_ratio = period.peak_effort_ratio;
    point.peak_u = period.peak_u;
    point.peak_tau = period.peak_tau;
    return point;
}

double dynamicAmplification(const EnvelopeResonance& resonance, EnvelopeAxis axis, double frequency) {
    if (!resonance.known) return 1.0;
    const auto a = static_cast<Eigen::Index>(axis);
    const double w = 2.0 * std::numbers::pi * frequency, zeta = resonance.damping_ratio;
    // H_aa = sum_i phi_i(a) (phi_i^T M x_a) w_i^2 / (w_i^2 - w^2 + 2 j zeta w_i w)
    std::complex<double> h = 0.0;
    for (Eigen::Index i = 0; i < resonance.modal_frequency.size(); ++i) {
        const double wi = 2.0 * std::numbers::pi * resonance.modal_frequency(i);
        const double participation = resonance.modal_shape(a, i) * resonance.modal_participation(i, a);
        h += participation * wi * wi / std::complex<double>(wi * wi - w * w, 2.0 * zeta * wi * w);
    }
    return std::abs(h);
}

EnvelopeResonance envelopeResonance(const Model& model, double amplification) {
    if (!(amplification >= kMinAmplification && amplification <= kMaxAmplification)) {
        throw Error("envelope: the amplification limit must be in [" + std::to_string(kMinAmplification) + ", " +
                    std::to_string(kMaxAmplification) + "]");
    }
    EnvelopeResonance out;
    out.amplification = amplification;
    out.damping_ratio = model.description.damping_ratio;
    out.task_dimension = model.task_dimension;
    out.band_end.fill(std::numeric_limits<double>::infinity());
    const StiffnessModel compliance(model);
    if (!compliance.any) {
        out.reason = "the robot file declares no compliance";
        return out;
    }
    out.declared = true;
    if (model.task_dimension == 2 && model.description.hasElasticBody()) {
        out.reason = "the elastic links of a two-DOF robot are not modelled (joint and drive stiffness are)";
        return out;
    }
    Data data(model);
    StiffnessData stiffness;
    LumpedModes modes;
    if (const Status status = stiffnessAndModes(model, compliance, data, model.home, stiffness, modes); !status) {
        out.reason = "at home: " + describe(status, model);
        return out;
    }
    // a two-DOF robot's theta is always free (a rotation about C loads no limb): x, y are its
    // coordinates, and its modes the task's, K_t v = w^2 M_t v (taskModes)
    const bool task = model.task_dimension == 2;
    if (stiffness.free_directions > (task ? 1 : 0)) {
        out.reason = "the declared compliance leaves the platform free at home (" +
                     describeDirection(stiffness.free.col(task ? 1 : 0)) + ")";
        return out;
    }
    out.known = true;
    out.modes = modes;
    if (task) {
        // the pose-order shapes E v_i and participations v_i^T M_t E^T (theta's row and column zero)
        TaskModes t;
        taskModes(model, data, stiffness, modes, t);
        out.modal_frequency = t.frequency;
        out.modal_shape = Eigen::MatrixXd::Zero(3, 2);
        out.modal_shape.bottomRows(2) = t.shape;
        out.modal_participation = Eigen::MatrixXd::Zero(2, 3);
        out.modal_participation.rightCols(2) = t.shape.transpose() * t.M;
        out.frequency = t.frequency(0);
    } else {
        out.frequency = modes.frequency(0);
        out.modal_frequency = modes.frequency;
        out.modal_shape = modes.shape;
        out.modal_participation = modes.shape.transpose() * modes.M;  // (phi_i^T M)(a)
    }
    // ascending: the first resonance; where the lumped model does not hold at home, the
    // elastodynamic model's, and the amplification sums over its modes
    if (ElastodynamicModes elastic; !task && lumpedFailsAt(model, compliance, data, modes, elastic)) {
        out.model = FrequencyModel::elastodynamic;
        out.warning = lumpedMismatchWarning(modes, elastic, true);
        out.frequency = elastic.frequency(0);
        if (elastic.participation.cols() == 3) {
            out.modal_frequency = elastic.frequency;
            out.modal_shape = elastic.platform_shape;
            out.modal_participation = elastic.participation;
        } else {
            out.warning +=
                "; the band's ends are the lumped model's (a locked joint leaves the elastodynamic model no rigid "
                "image of the drives' motion)";
        }
    }
    // per axis: scan a log grid from f_1 / 1000 to 10 f_last for the first frequency out of
    // [1 / limit, limit] (H rises monotonically from H(0) = 1 until then), then bisect
    const auto outside = [&](EnvelopeAxis axis, double f) {
        const double h = dynamicAmplification(out, axis, f);
        return h > amplification || h < 1.0 / amplification;
    };
    const double f_lo = 1e-3 * out.frequency, f_hi = 10.0 * out.modal_frequency.maxCoeff();
    constexpr int kGrid = 4000;
    for (const EnvelopeAxis axis : kEnvelopeAxes) {
        if (!hasAxis(model.task_dimension, axis)) continue;
        double below = f_lo;
        for (int k = 1; k <= kGrid; ++k) {
            const double f = f_lo * std::pow(f_hi / f_lo, static_cast<double>(k) / kGrid);
            if (!outside(axis, f)) {
                below = f;
                continue;
            }
            double above = f;
            for (int i = 0; i < 60 && above - below > 1e-12 * above; ++i) {
                const double mid = 0.5 * (below + above);
                (outside(axis, mid) ? above : below) = mid;
            }
            // the lowest frequency out of the band, to bisection precision
            out.band_end[static_cast<std::size_t>(axis)] = below;
            break;
        }
    }
    return out;
}

std::vector<EnvelopePoint> operatingEnvelope(const Model& model, const EnvelopeOptions& options) {
    checkFrequency(options.min_frequency, "min_frequency");
    checkFrequency(options.max_frequency, "max_frequency");
    if (options.max_frequency < options.min_frequency) throw Error("envelope: max_frequency is below min_frequency");
    if (options.points < 1 || options.points > kEnvelopeMaxPoints) {
        throw Error("envelope: the number of frequencies must be in [1, " + std::to_string(kEnvelopeMaxPoints) +
                    "], got " + std::to_string(options.points));
    }
    std::vector<EnvelopePoint> points;
    for (const EnvelopeAxis axis : kEnvelopeAxes) {
        if (!hasAxis(model.task_dimension, axis)) continue;  // a two-DOF robot: x and y
        for (int k = 0; k < options.points; ++k) {
            const double s = options.points > 1 ? static_cast<double>(k) / (options.points - 1) : 0.0;
            const double f = options.min_frequency * std::pow(options.max_frequency / options.min_frequency, s);
            points.push_back(maximumAmplitude(model, axis, f, options));
            if (options.progress)
                options.progress(static_cast<int>(points.size()), model.task_dimension * options.points);
        }
    }
    // at and beyond the axis' band end the machine's own dynamics bind, whatever the joints allow
    if (const EnvelopeResonance resonance = envelopeResonance(model, options.amplification); resonance.known) {
        for (EnvelopePoint& p : points) {
            if (p.frequency < resonance.band_end[static_cast<std::size_t>(p.axis)]) continue;
            p.limit = EnvelopeLimit::resonance;
            p.limb = p.joint = p.actuator = -1;
        }
    }
    return points;
}

}  // namespace nocdyn
