// Recorded ground motion on a robot (see shake.hpp).
#include "nocdyn/sim/shake.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include <Eigen/LU>
#include <unsupported/Eigen/FFT>
#include <unsupported/Eigen/MatrixFunctions>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/closed_loop.hpp"
#include "nocdyn/sim/filter.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/kinematics.hpp"

namespace nocdyn {

namespace {

constexpr double kPi = std::numbers::pi;

}  // namespace

std::vector<double> highPassZeroPhase(std::span<const double> x, double dt, double cutoff) {
    if (!(dt > 0.0 && std::isfinite(dt)))
        throw Error("high-pass: the time step must be positive, got " + text::number(dt));
    const double fs = 1.0 / dt;
    if (!(cutoff > 0.0 && cutoff < 0.5 * fs)) {
        throw Error("high-pass: cutoff " + text::number(cutoff) +
                    " Hz must be above 0 and below the Nyquist frequency " + text::number(0.5 * fs) + " Hz");
    }
    std::vector<double> y(x.begin(), x.end());
    filterZeroPhase(butterworth(FilterKind::high_pass, kHighPassOrder, cutoff, fs),
                    Eigen::Map<Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size())),
                    FilterEdges::odd_reflection);
    return y;
}

void accumulateLimitUse(const Model& model, double t, const ActuatorVector& u, const ActuatorVector* du,
                        const ActuatorVector& tau, double margin, LimitUse& worst) {
    const double keep = 1.0 - margin;
    for (int a = 0; a < model.actuators; ++a) {
        const auto ia = static_cast<std::size_t>(a);
        const int limb = model.actuator_limb[ia];
        const JointLimits& lim =
            model.limb[static_cast<std::size_t>(limb)].limits[static_cast<std::size_t>(model.actuator_joint[ia])];
        const auto consider = [&](double ratio, const char* which) {
            if (ratio > worst.ratio) {
                worst = {ratio, "actuator " + std::to_string(a + 1) + " (" + model.limbName(limb) + ") " + which, t};
            }
        };
        if (std::isfinite(lim.lower) && std::isfinite(lim.upper)) {
            const double centre = 0.5 * (lim.lower + lim.upper);
            const double half = 0.5 * (lim.upper - lim.lower);
            consider(std::abs(u(a) - centre) / (keep * half), "range");
        }
        if (du != nullptr && std::isfinite(lim.velocity)) {
            consider(std::abs((*du)(a)) / (keep * lim.velocity), "velocity");
        }
        if (std::isfinite(lim.effort)) consider(std::abs(tau(a)) / (keep * lim.effort), "effort");
    }
}

LimitUse limitUse(const Model& model, const PoseTrajectory& trajectory, double duration, double step, double margin) {
    Data data(model);
    LimitUse worst;
    const auto steps = static_cast<std::size_t>(std::ceil(duration / step));
    Pose p;
    Twist dp, ddp;
    for (std::size_t k = 0; k <= steps; ++k) {
        const double t = std::min(duration, static_cast<double>(k) * step);
        trajectory.evaluate(t, p, dp, ddp);
        const Status status = inverseDynamicsFast(model, data, p, dp, ddp);
        if (!status.ok() && status.code != StatusCode::joint_limit_exceeded &&
            status.code != StatusCode::effort_exceeded && status.code != StatusCode::velocity_exceeded) {
            return {std::numeric_limits<double>::infinity(), describe(status, model), t};
        }
        accumulateLimitUse(model, t, data.u, &data.du, data.tau, margin, worst);
    }
    return worst;
}

namespace {

/// The motion of the filtered record at scales (L, A).
struct Scaled {
    std::vector<double> t, ax, ay, alpha;
    PoseTrajectory trajectory;
};

/// max_i (d_i + v t_i) - min_i (d_i + v t_i): the stroke of the displacement d + v t.
double strokeWithRate(const std::vector<double>& t, const std::vector<double>& d, double v) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < t.size(); ++i) {
        lo = std::min(lo, d[i] + v * (t[i] - t.front()));
        hi = std::max(hi, d[i] + v * (t[i] - t.front()));
    }
    return hi - lo;
}

}  // namespace

SampledAxis baselineCorrectedAxis(const std::vector<double>& t, const std::vector<double>& a, double home) {
    const SampledAxis rest = splineOfAccelerations(t, a);
    std::vector<double> d(t.size());
    double dq = 0.0, ddq = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) rest.evaluate(t[i], d[i], dq, ddq);
    // the stroke is convex in v0 (a maximum minus a minimum of functions linear in v0); a v0
    // that does not widen it obeys |v0| <= 2 stroke(0) / T: golden-section search there
    const double T = t.back() - t.front();
    const double bound = T > 0.0 ? 2.0 * strokeWithRate(t, d, 0.0) / T : 0.0;
    double lo = -bound, hi = bound;
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = strokeWithRate(t, d, x1), f2 = strokeWithRate(t, d, x2);
    for (int k = 0; k < 200 && hi - lo > 1e-12 * bound; ++k) {
        if (f1 <= f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = strokeWithRate(t, d, x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = strokeWithRate(t, d, x2);
        }
    }
    // keep v0 = 0 (the motion from rest) unless a rate strictly narrows the stroke
    double v0 = 0.5 * (lo + hi);
    if (!(strokeWithRate(t, d, v0) < strokeWithRate(t, d, 0.0))) v0 = 0.0;
    double d_lo = std::numeric_limits<double>::infinity(), d_hi = -d_lo;
    for (std::size_t i = 0; i < t.size(); ++i) {
        d_lo = std::min(d_lo, d[i] + v0 * (t[i] - t.front()));
        d_hi = std::max(d_hi, d[i] + v0 * (t[i] - t.front()));
    }
    return splineOfAccelerations(t, a, v0, home - 0.5 * (d_lo + d_hi));
}

namespace {

Scaled scaleRecord(const Model& model, const GroundRecord& filtered, double L, double A) {
    Scaled s;
    const std::size_t n = std::max({filtered.ax.size(), filtered.ay.size(), filtered.alpha.size()});
    s.t.resize(n);
    for (std::size_t i = 0; i < n; ++i) s.t[i] = static_cast<double>(i) * filtered.dt / L;
    auto sampled = std::make_shared<SampledPose>();
    const auto axis = [&](const std::vector<double>& a, std::vector<double>& out, std::optional<SampledAxis>& slot,
                          double home) {
        if (a.empty()) return;
        out.resize(n);
        for (std::size_t i = 0; i < n; ++i) out[i] = A * a[i];
        slot = baselineCorrectedAxis(s.t, out, home);
    };
    axis(filtered.alpha, s.alpha, sampled->theta, model.home(0));
    axis(filtered.ax, s.ax, sampled->x, model.home(1));
    axis(filtered.ay, s.ay, sampled->y, model.home(2));
    // axes not driven stay at home
    s.trajectory.theta.offset = model.home(0);
    s.trajectory.x.offset = model.home(1);
    s.trajectory.y.offset = model.home(2);
    s.trajectory.name = "record";
    s.trajectory.duration = s.t.back();
    s.trajectory.sampled = std::move(sampled);
    return s;
}

LimitUse useAt(const Model& model, const Scaled& s, double dt, double margin) {
    // two checks per sample interval
    return limitUse(model, s.trajectory, s.t.back(), 0.5 * dt, margin);
}

}  // namespace

FittedRecord fitRecord(const Model& model, const GroundRecord& record, const FitOptions& options) {
    const std::size_t n = std::max({record.ax.size(), record.ay.size(), record.alpha.size()});
    if (n < 4) throw Error("record: at least 4 samples of some axis are needed");
    for (const auto* a : {&record.ax, &record.ay, &record.alpha}) {
        if (!a->empty() && a->size() != n) {
            throw Error("record: the axes have different lengths (" + std::to_string(a->size()) + " and " +
                        std::to_string(n) + " samples)");
        }
        for (double v : *a) {
            if (!std::isfinite(v)) throw Error("record: an acceleration is not finite");
        }
    }
    if (!(options.margin >= 0.0 && options.margin < 1.0)) throw Error("record: margin must be in [0, 1)");
    if (!(options.max_time_scale >= 1.0)) throw Error("record: the largest time scale must be at least 1");
    GroundRecord filtered = record;
    if (options.highpass > 0.0) {
        for (auto* a : {&filtered.ax, &filtered.ay, &filtered.alpha}) {
            if (!a->empty()) *a = highPassZeroPhase(*a, record.dt, options.highpass);
        }
    }
    const auto fits = [&](double L, double A, LimitUse* use = nullptr) {
        const Scaled s = scaleRecord(model, filtered, L, A);
        const LimitUse u = useAt(model, s, record.dt / L, options.margin);
        if (use) *use = u;
        return u.ratio <= 1.0;
    };
    double L = options.time_scale.value_or(1.0);
    double A = 1.0;
    if (options.time_scale) {
        if (!(L >= 1e-3 && L <= 1e4)) throw Error("record: time scale " + text::number(L) + " outside [0.001, 10000]");
    } else if (!fits(1.0, 1.0)) {
        double lo = 1.0, hi = 2.0;
        while (hi < options.max_time_scale && !fits(hi, 1.0)) {
            lo = hi;
            hi *= 2.0;
        }
        hi = std::min(hi, options.max_time_scale);
        if (fits(hi, 1.0)) {
            for (int k = 0; k < 60 && hi - lo > 1e-3 * hi; ++k) {
                const double mid = 0.5 * (lo + hi);
                (fits(mid, 1.0) ? hi : lo) = mid;
            }
        }
        L = hi;
    }
    LimitUse use;
    if (!fits(L, 1.0, &use)) {
        // amplitude fallback at L: the largest A that fits
        LimitUse smallest;
        constexpr double kMinAmplitude = 1e-4;
        if (!fits(L, kMinAmplitude, &smallest)) {
            throw Error("record: cannot be fitted even at amplitude " + text::number(kMinAmplitude) +
                        " and time scale " + text::number(L) + ": " + smallest.what + " at " +
                        text::number(100.0 * smallest.ratio) + " % of its limit (with " +
                        text::number(100.0 * options.margin) + " % margin) at " + text::sampleTime(smallest.t));
        }
        double lo = kMinAmplitude, hi = 1.0;
        for (int k = 0; k < 60 && hi - lo > 1e-3 * lo; ++k) {
            const double mid = std::sqrt(lo * hi);
            (fits(L, mid) ? lo : hi) = mid;
        }
        A = lo;
    }
    Scaled s = scaleRecord(model, filtered, L, A);
    FittedRecord fit;
    fit.time_scale = L;
    fit.amplitude_scale = A;
    fit.dt = record.dt / L;
    fit.use = useAt(model, s, fit.dt, options.margin);
    fit.t = std::move(s.t);
    fit.ax = std::move(s.ax);
    fit.ay = std::move(s.ay);
    fit.alpha = std::move(s.alpha);
    fit.trajectory = std::move(s.trajectory);
    return fit;
}

double peakOscillatorDisplacement(std::span<const double> a, double dt, double period, double zeta) {
    if (!(period > 0.0 && dt > 0.0 && zeta >= 0.0 && zeta < 1.0)) {
        throw Error("response spectrum: period and time step must be positive, damping in [0, 1)");
    }
    const double w = 2.0 * kPi / period;
    // Exact recurrence for an excitation linear between samples (Nigam-Jennings): the state
    // z = [u, u', a, a'] obeys z' = M z over a step, so z(t + dt) = exp(M dt) z(t).
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    m(0, 1) = 1.0;
    m(1, 0) = -w * w;
    m(1, 1) = -2.0 * zeta * w;
    m(1, 2) = -1.0;
    m(2, 3) = 1.0;
    const Eigen::Matrix4d phi = (m * dt).exp();
    double u = 0.0, v = 0.0, peak = 0.0;
    for (std::size_t i = 0; i + 1 < a.size(); ++i) {
        const double slope = (a[i + 1] - a[i]) / dt;
        const double un = phi(0, 0) * u + phi(0, 1) * v + phi(0, 2) * a[i] + phi(0, 3) * slope;
        const double vn = phi(1, 0) * u + phi(1, 1) * v + phi(1, 2) * a[i] + phi(1, 3) * slope;
        u = un;
        v = vn;
        peak = std::max(peak, std::abs(u));
    }
    return peak;
}

std::vector<double> responseSpectrum(std::span<const double> a, double dt, std::span<const double> periods,
                                     double zeta) {
    std::vector<double> sa;
    sa.reserve(periods.size());
    for (double T : periods) {
        const double w = 2.0 * kPi / T;
        sa.push_back(w * w * peakOscillatorDisplacement(a, dt, T, zeta));
    }
    return sa;
}

std::array<std::vector<double>, 3> poseAcceleration(const std::vector<Pose>& p, double tick,
                                                    std::span<const double> times, int span) {
    if (p.size() < 3 || !(tick > 0.0) || span < 1) throw Error("pose acceleration: too few poses or a bad step");
    const auto n = static_cast<std::ptrdiff_t>(p.size());
    const std::ptrdiff_t m = std::min<std::ptrdiff_t>(span, (n - 1) / 2);
    const double h = static_cast<double>(m) * tick;
    const auto at = [&](std::ptrdiff_t k, int axis) {
        const std::ptrdiff_t c = std::clamp(k, m, n - 1 - m);
        const auto i = [&](std::ptrdiff_t j) { return p[static_cast<std::size_t>(j)](axis); };
        return (i(c + m) - 2.0 * i(c) + i(c - m)) / (h * h);
    };
    std::array<std::vector<double>, 3> out;
    for (int axis = 0; axis < 3; ++axis) {
        auto& v = out[static_cast<std::size_t>(axis)];
        v.reserve(times.size());
        for (double t : times) {
            const double x = std::clamp(t / tick, 0.0, static_cast<double>(n - 1));
            const auto k = static_cast<std::ptrdiff_t>(std::floor(x));
            const std::ptrdiff_t k1 = std::min(k + 1, n - 1);
            const double w = x - static_cast<double>(k);
            v.push_back((1.0 - w) * at(k, axis) + w * at(k1, axis));
        }
    }
    return out;
}

ShakeScore scoreShake(std::span<const double> target, std::span<const double> achieved, double dt, double t_min,
                      double t_max, int n_periods) {
    if (target.size() != achieved.size() || target.empty()) throw Error("score: target and achieved differ in length");
    if (!(t_min > 0.0 && t_max > t_min && n_periods >= 2)) throw Error("score: bad period range");
    ShakeScore score;
    double se = 0.0, st = 0.0, pt = 0.0, pa = 0.0;
    for (std::size_t i = 0; i < target.size(); ++i) {
        se += (achieved[i] - target[i]) * (achieved[i] - target[i]);
        st += target[i] * target[i];
        pt = std::max(pt, std::abs(target[i]));
        pa = std::max(pa, std::abs(achieved[i]));
    }
    score.rms_error = st > 0.0 ? std::sqrt(se / st) : 0.0;
    score.peak_error = pt > 0.0 ? (pa - pt) / pt : 0.0;
    for (int k = 0; k < n_periods; ++k) {
        score.periods.push_back(t_min * std::pow(t_max / t_min, static_cast<double>(k) / (n_periods - 1)));
    }
    score.target_sa = responseSpectrum(target, dt, score.periods);
    score.achieved_sa = responseSpectrum(achieved, dt, score.periods);
    const double peak_sa = *std::max_element(score.target_sa.begin(), score.target_sa.end());
    int outside = 0;
    for (std::size_t k = 0; k < score.periods.size(); ++k) {
        if (!(score.target_sa[k] > 0.0 && score.target_sa[k] >= 0.1 * peak_sa)) continue;
        ++score.counted;
        if (std::abs(score.achieved_sa[k] / score.target_sa[k] - 1.0) > 0.1) ++outside;
    }
    score.share_outside = score.counted > 0 ? static_cast<double>(outside) / score.counted : 0.0;
    return score;
}

double relativeRmsError(std::span<const double> target, std::span<const double> achieved, double reference) {
    if (target.size() != achieved.size()) throw Error("score: target and achieved differ in length");
    double se = 0.0, st = 0.0;
    for (std::size_t i = 0; i < target.size(); ++i) {
        se += (achieved[i] - target[i]) * (achieved[i] - target[i]);
        st += (target[i] - reference) * (target[i] - reference);
    }
    return st > 0.0 ? std::sqrt(se / st) : 0.0;
}

DriveInverse driveInverse(DriveModel model, const ShakeLoopLinearization& loop, double dt, std::size_t samples,
                          double band, const std::array<bool, 3>& driven) {
    if (samples < 4) throw Error("drive correction: at least 4 samples are needed");
    if (!(dt > 0.0 && std::isfinite(dt))) throw Error("drive correction: the sample step must be positive");
    if (!(band > 0.0 && std::isfinite(band))) throw Error("drive correction: the band must be positive");
    if (!(driven[0] || driven[1] || driven[2])) throw Error("drive correction: no axis is driven");
    DriveInverse out;
    out.dt = dt;
    out.samples = samples;
    out.band = band;
    out.driven = driven;
    out.fft_size = 1;
    while (out.fft_size < 2 * samples) out.fft_size *= 2;
    const std::size_t bins = out.fft_size / 2 + 1;
    out.inverse.assign(bins, Eigen::Matrix3cd::Zero());
    std::array<int, 3> axes{};
    int m = 0;
    for (int i = 0; i < 3; ++i) {
        if (driven[static_cast<std::size_t>(i)]) axes[static_cast<std::size_t>(m++)] = i;
    }
    // the mean as is: the pose feedback makes H(0) = 1
    for (int i = 0; i < m; ++i)
        out.inverse[0](axes[static_cast<std::size_t>(i)], axes[static_cast<std::size_t>(i)]) = 1.0;
    const double nyquist = model == DriveModel::identity ? std::numeric_limits<double>::infinity() : 0.5 / loop.dt;
    for (std::size_t k = 1; k < bins; ++k) {
        const double f = static_cast<double>(k) / (static_cast<double>(out.fft_size) * dt);
        if (f > band || !(f < nyquist)) continue;  // no correction beyond the band or the controller's Nyquist
        Eigen::Matrix3cd& inv = out.inverse[k];
        if (model == DriveModel::identity) {
            for (int i = 0; i < m; ++i) inv(axes[static_cast<std::size_t>(i)], axes[static_cast<std::size_t>(i)]) = 1.0;
            continue;
        }
        const Eigen::Matrix3cd H = shakeLoopResponse(loop, f).closed_loop;
        Eigen::MatrixXcd block(m, m);
        for (int i = 0; i < m; ++i) {
            for (int j = 0; j < m; ++j) {
                block(i, j) = H(axes[static_cast<std::size_t>(i)], axes[static_cast<std::size_t>(j)]);
            }
        }
        const Eigen::FullPivLU<Eigen::MatrixXcd> lu(block);
        if (!lu.isInvertible() || !(std::abs(lu.determinant()) > 1e-12)) {
            throw Error("drive correction: the closed loop is singular at " + text::format("%g", f) + " Hz");
        }
        const Eigen::MatrixXcd block_inverse = lu.inverse();
        for (int i = 0; i < m; ++i) {
            for (int j = 0; j < m; ++j) {
                inv(axes[static_cast<std::size_t>(i)], axes[static_cast<std::size_t>(j)]) = block_inverse(i, j);
            }
        }
    }
    return out;
}

Status correctDrive(const DriveInverse& inverse, const std::array<std::vector<double>, 3>& error, double gain,
                    std::array<std::vector<double>, 3>& drive) {
    if (!(gain > 0.0 && gain <= 1.0)) throw Error("drive correction: the gain must be in (0, 1]");
    const std::size_t n = inverse.samples, N = inverse.fft_size;
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!inverse.driven[axis]) continue;
        if (error[axis].size() != n || drive[axis].size() != n) {
            throw Error("drive correction: " + std::to_string(error[axis].size()) + " errors and " +
                        std::to_string(drive[axis].size()) + " drive samples, expected " + std::to_string(n));
        }
        for (double e : error[axis]) {
            if (!std::isfinite(e)) return {StatusCode::not_finite, -1, e};
        }
    }
    Eigen::FFT<double> fft;
    std::array<std::vector<std::complex<double>>, 3> spectrum;
    for (std::size_t axis = 0; axis < 3; ++axis) {
        spectrum[axis].assign(N, 0.0);
        if (!inverse.driven[axis]) continue;
        std::vector<std::complex<double>> padded(N, 0.0);
        for (std::size_t i = 0; i < n; ++i) padded[i] = error[axis][i];
        fft.fwd(spectrum[axis], padded);
    }
    // C_k = H^-1(f_k) E_k on k = 0 .. N / 2, the conjugate mirror above (a real correction)
    std::array<std::vector<std::complex<double>>, 3> corrected;
    for (auto& c : corrected) c.assign(N, 0.0);
    for (std::size_t k = 0; k <= N / 2; ++k) {
        const Eigen::Vector3cd e(spectrum[0][k], spectrum[1][k], spectrum[2][k]);
        const Eigen::Vector3cd c = inverse.inverse[k] * e;
        for (std::size_t axis = 0; axis < 3; ++axis) {
            corrected[axis][k] = c(static_cast<Eigen::Index>(axis));
            if (k > 0 && k < N - k) corrected[axis][N - k] = std::conj(c(static_cast<Eigen::Index>(axis)));
        }
    }
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!inverse.driven[axis]) continue;
        std::vector<std::complex<double>> back;
        fft.inv(back, corrected[axis]);
        for (std::size_t i = 0; i < n; ++i) drive[axis][i] += gain * back[i].real();
    }
    return {};
}

FitOptions driveFitOptions(FitOptions target, double time_scale) {
    target.time_scale = time_scale;
    target.margin *= 0.5;
    target.highpass = 0.0;
    return target;
}

void addDriveCorrection(std::span<double> drive, std::span<const double> target, std::span<const double> achieved,
                        double gain) {
    if (target.size() != drive.size() || achieved.size() != drive.size())
        throw Error("drive correction: the drive, target and achieved accelerations differ in length");
    for (std::size_t i = 0; i < drive.size(); ++i) drive[i] += gain * (target[i] - achieved[i]);
}

PassJudgement judgePass(int pass, double rms, double best, double tolerance) {
    PassJudgement out;
    out.kept = rms < best;
    if (!(rms < (1.0 - tolerance) * best)) {
        out.stop = "pass ";
        out.stop += std::to_string(pass);
        out.stop += text::format(" improved the RMS error by less than %g %%", 100.0 * tolerance);
    }
    return out;
}

std::string driveLeavesLimits(int pass) {
    std::string out = "pass ";
    out += std::to_string(pass);
    out += "'s drive would leave the limits";
    return out;
}

}  // namespace nocdyn
