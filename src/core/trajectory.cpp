// Pose trajectories (see trajectory.hpp): harmonic (eqs. 33-34 of the paper) and sampled.
#include "nocdyn/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

void AxisMotion::evaluate(double t, double& q, double& dq, double& ddq) const {
    q = offset;
    dq = 0.0;
    ddq = 0.0;
    for (const Harmonic& h : harmonics) {
        const double w = 2.0 * std::numbers::pi * h.frequency;
        const double s = std::sin(w * t + h.phase);
        const double c = std::cos(w * t + h.phase);
        q += h.amplitude * s;
        dq += h.amplitude * w * c;
        ddq -= h.amplitude * w * w * s;
    }
}

void SampledAxis::evaluate(double t, double& q, double& dq, double& ddq) const {
    // Outside [t_0, t_last]: continued at the end rate with zero acceleration (q and dq/dt
    // stay continuous).
    const double t_first = times.front();
    const double t_last = times.back();
    const double tc = std::clamp(t, t_first, t_last);
    const auto it = std::upper_bound(times.begin(), times.end(), tc);
    std::size_t i = static_cast<std::size_t>(it - times.begin());
    i = std::min(i == 0 ? 0 : i - 1, pieces.size() - 1);
    const std::array<double, 6>& c = pieces[i];
    const double s = tc - times[i];
    // Horner on q = sum c_k s^k and its two derivatives
    q = ((((c[5] * s + c[4]) * s + c[3]) * s + c[2]) * s + c[1]) * s + c[0];
    dq = (((5.0 * c[5] * s + 4.0 * c[4]) * s + 3.0 * c[3]) * s + 2.0 * c[2]) * s + c[1];
    ddq = ((20.0 * c[5] * s + 12.0 * c[4]) * s + 6.0 * c[3]) * s + 2.0 * c[2];
    if (t != tc) {
        q += dq * (t - tc);
        ddq = 0.0;
    }
}

namespace {

void checkSamples(const std::vector<double>& t, const std::vector<double>& v, const char* what) {
    if (t.size() != v.size()) throw Error(std::string(what) + ": as many times as values are needed");
    if (t.size() < 2) throw Error(std::string(what) + ": at least 2 samples are needed");
    for (std::size_t i = 0; i < t.size(); ++i) {
        if (!std::isfinite(t[i]) || !std::isfinite(v[i])) {
            throw Error(std::string(what) + ": sample " + std::to_string(i) + " is not finite");
        }
        if (i > 0 && !(t[i] > t[i - 1])) {
            throw Error(std::string(what) + ": time " + text::precise(t[i]) + " s of sample " + std::to_string(i) +
                        " is not after " + text::precise(t[i - 1]) + " s");
        }
    }
}

/// Second derivatives M_i of the not-a-knot cubic spline through (t_i, y_i): the continuity
/// of the first derivative at the inner knots,
///   h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} = 6 (d_i - d_{i-1}), d_i = (y_{i+1} - y_i) / h_i,
/// with M_0 and M_{n-1} eliminated by the continuity of the third derivative at t_1 and t_{n-2};
/// the tridiagonal system is solved by the Thomas algorithm.
std::vector<double> notAKnotCurvatures(const std::vector<double>& t, const std::vector<double>& y) {
    const std::size_t n = t.size();
    std::vector<double> m(n, 0.0);
    if (n == 2) return m;
    std::vector<double> h(n - 1), d(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) {
        h[i] = t[i + 1] - t[i];
        d[i] = (y[i + 1] - y[i]) / h[i];
    }
    if (n == 3) {  // one parabola: M constant
        std::fill(m.begin(), m.end(), 2.0 * (d[1] - d[0]) / (h[0] + h[1]));
        return m;
    }
    const std::size_t k = n - 2;  // unknowns M_1 .. M_{n-2}
    std::vector<double> sub(k), diag(k), sup(k), rhs(k);
    for (std::size_t r = 0; r < k; ++r) {
        const std::size_t i = r + 1;
        sub[r] = h[i - 1];
        diag[r] = 2.0 * (h[i - 1] + h[i]);
        sup[r] = h[i];
        rhs[r] = 6.0 * (d[i] - d[i - 1]);
    }
    // M_0 = (1 + h_0/h_1) M_1 - (h_0/h_1) M_2
    const double r0 = h[0] / h[1];
    diag[0] += h[0] * (1.0 + r0);
    sup[0] -= h[0] * r0;
    // M_{n-1} = (1 + h_{n-2}/h_{n-3}) M_{n-2} - (h_{n-2}/h_{n-3}) M_{n-3}
    const double r1 = h[n - 2] / h[n - 3];
    diag[k - 1] += h[n - 2] * (1.0 + r1);
    sub[k - 1] -= h[n - 2] * r1;
    for (std::size_t r = 1; r < k; ++r) {
        const double w = sub[r] / diag[r - 1];
        diag[r] -= w * sup[r - 1];
        rhs[r] -= w * rhs[r - 1];
    }
    m[k] = rhs[k - 1] / diag[k - 1];
    for (std::size_t r = k - 1; r-- > 0;) m[r + 1] = (rhs[r] - sup[r] * m[r + 2]) / diag[r];
    m[0] = (1.0 + r0) * m[1] - r0 * m[2];
    m[n - 1] = (1.0 + r1) * m[n - 2] - r1 * m[n - 3];
    return m;
}

/// The spline's value and two derivatives at every knot must be finite: extreme values or
/// time steps (finite each) can overflow the divided differences or the integration.
void checkFinite(const SampledAxis& axis, const char* what) {
    for (std::size_t i = 0; i < axis.times.size(); ++i) {
        double q = 0.0;
        double dq = 0.0;
        double ddq = 0.0;
        axis.evaluate(axis.times[i], q, dq, ddq);
        if (!(std::isfinite(q) && std::isfinite(dq) && std::isfinite(ddq))) {
            throw Error(std::string(what) + ": the spline through the samples is not finite at time " +
                        text::precise(axis.times[i]) + " s (values or time steps out of range)");
        }
    }
}

/// Cubic pieces y_i + b s + (M_i / 2) s^2 + (M_{i+1} - M_i) / (6 h) s^3 of the spline.
std::vector<std::array<double, 4>> cubicPieces(const std::vector<double>& t, const std::vector<double>& y) {
    const std::vector<double> m = notAKnotCurvatures(t, y);
    std::vector<std::array<double, 4>> pieces(t.size() - 1);
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const double h = t[i + 1] - t[i];
        const double b = (y[i + 1] - y[i]) / h - h * (2.0 * m[i] + m[i + 1]) / 6.0;
        pieces[i] = {y[i], b, 0.5 * m[i], (m[i + 1] - m[i]) / (6.0 * h)};
    }
    return pieces;
}

}  // namespace

SampledAxis splineOfPositions(const std::vector<double>& t, const std::vector<double>& q) {
    checkSamples(t, q, "sampled positions");
    SampledAxis axis;
    axis.times.assign(t.begin(), t.end());
    for (const auto& c : cubicPieces(t, q)) axis.pieces.push_back({c[0], c[1], c[2], c[3], 0.0, 0.0});
    checkFinite(axis, "sampled positions");
    return axis;
}

SampledAxis splineOfAccelerations(const std::vector<double>& t, const std::vector<double>& a, double v0, double q0) {
    checkSamples(t, a, "sampled accelerations");
    SampledAxis axis;
    axis.times.assign(t.begin(), t.end());
    double v = v0;
    double q = q0;
    for (const auto& c : cubicPieces(t, a)) {
        // a(s) = c0 + c1 s + c2 s^2 + c3 s^3, integrated twice from (q_i, v_i)
        const std::array<double, 6> p = {q, v, c[0] / 2.0, c[1] / 6.0, c[2] / 12.0, c[3] / 20.0};
        const std::size_t i = axis.pieces.size();
        const double h = t[i + 1] - t[i];
        q = ((((p[5] * h + p[4]) * h + p[3]) * h + p[2]) * h + p[1]) * h + p[0];
        v = (((5.0 * p[5] * h + 4.0 * p[4]) * h + 3.0 * p[3]) * h + 2.0 * p[2]) * h + p[1];
        axis.pieces.push_back(p);
    }
    checkFinite(axis, "sampled accelerations");
    return axis;
}

void PoseTrajectory::evaluate(double t, Pose& p, Pose& dp, Pose& ddp) const {
    const SampledPose* s = sampled.get();
    if (s && s->theta) {
        s->theta->evaluate(t, p(0), dp(0), ddp(0));
    } else {
        theta.evaluate(t, p(0), dp(0), ddp(0));
    }
    if (s && s->x) {
        s->x->evaluate(t, p(1), dp(1), ddp(1));
    } else {
        x.evaluate(t, p(1), dp(1), ddp(1));
    }
    if (s && s->y) {
        s->y->evaluate(t, p(2), dp(2), ddp(2));
    } else {
        y.evaluate(t, p(2), dp(2), ddp(2));
    }
}

namespace {

PoseTrajectory paperTranslation(const char* name) {
    constexpr double pi = std::numbers::pi;
    PoseTrajectory traj;
    traj.name = name;
    traj.duration = 0.2;
    // eqs. 33-34: x = -2 sin(20 pi t + pi/6) + 1 mm, y = 4 sin(20 pi t - pi/6) + 2 mm
    traj.x = {0.001, {{-0.002, 10.0, pi / 6.0}}};
    traj.y = {0.002, {{0.004, 10.0, -pi / 6.0}}};
    return traj;
}

}  // namespace

PoseTrajectory paperTrajectory1() {
    PoseTrajectory traj = paperTranslation("paper1");
    // eq. 33: theta_1 = (3/180) pi sin(20 pi t)
    traj.theta = {0.0, {{3.0 * std::numbers::pi / 180.0, 10.0, 0.0}}};
    return traj;
}

PoseTrajectory paperTrajectory2() {
    PoseTrajectory traj = paperTranslation("paper2");
    // eq. 34: theta_2 = (3/180) pi sin(10 pi t)
    traj.theta = {0.0, {{3.0 * std::numbers::pi / 180.0, 5.0, 0.0}}};
    return traj;
}

}  // namespace nocdyn
