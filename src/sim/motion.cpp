// The motion of an identification experiment from its measurements (motion.hpp).
#include "nocdyn/sim/motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/QR>

#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/sim/filter.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/detail/index.hpp"

namespace nocdyn {

namespace {

using detail::at;

/// Central differences (one-sided at the ends) of the columns of x over times t.
Eigen::MatrixXd differentiate(const Eigen::MatrixXd& x, const std::vector<double>& t) {
    const Eigen::Index N = x.rows();
    Eigen::MatrixXd dx(N, x.cols());
    for (Eigen::Index k = 0; k < N; ++k) {
        const Eigen::Index a = k == 0 ? 0 : k - 1, b = k == N - 1 ? N - 1 : k + 1;
        dx.row(k) = (x.row(b) - x.row(a)) / (t[at(static_cast<int>(b))] - t[at(static_cast<int>(a))]);
    }
    return dx;
}

/// The platform rates from the actuator rates and accelerations at the pose in `data` (position
/// stage done): least squares on du = A S(c) dp/dt and ddu = A dxi_P - (rows of
/// J_j^-1 dJ_j gamma_dot_j), exact with three actuators.
Status platformRates(const Model& model, Data& data, const Eigen::VectorXd& du, const Eigen::VectorXd& ddu) {
    // measured rates need not be consistent: any residual is accepted
    Twist t_M;
    if (const Status status = velocityFromActuatorRatesLeastSquares(model, data, ActuatorVector(du), t_M,
                                                                    std::numeric_limits<double>::infinity());
        !status) {
        return status;
    }
    const Vector2 c = data.p.tail<2>();
    Eigen::VectorXd rhs = ddu;
    for (int a = 0; a < model.actuators; ++a) {
        const LimbData& ld = data.limb[at(model.actuator_limb[at(a)])];
        const Twist dJ = ld.s_dot[1] * ld.gamma_dot(1) + ld.s_dot[2] * ld.gamma_dot(2);
        rhs(a) += ld.J_inv.row(model.actuator_joint[at(a)]).dot(dJ);
    }
    if (model.task_dimension == 2) {
        // translation: omega = 0 throughout, so dxi_P/dt = [0; a_C] and ddu = A_E a_C + ...
        // (A_E the x, y columns of A); the acceleration in x, y by least squares on them
        using TaskActuation = Eigen::Matrix<double, Eigen::Dynamic, 2, 0, kMaxActuators, 2>;
        const TaskActuation A_E = data.A.rightCols<2>();
        const Vector2 a_C = Eigen::ColPivHouseholderQR<TaskActuation>(A_E).solve(rhs);
        accelerationFromPlatform(model, data, Twist(0.0, a_C(0), a_C(1)));
        return {};
    }
    const Eigen::ColPivHouseholderQR<ActuationMatrix> qr(data.A);
    const Twist xi_P_dot = qr.solve(rhs);
    const double w = t_M(0);
    // S(c)^-1 (dxi_P/dt - dS/dt t_M)
    const Twist t_M_dot = poseRateOfPlatformTwist(c, xi_P_dot) - Twist(0.0, w * t_M(2), -w * t_M(1));
    accelerationFromPlatform(model, data, t_M_dot);
    return {};
}

}  // namespace

Motion reconstructMotion(const Model& model, const Measurements& measured, const IdentificationOptions& options) {
    const auto N = static_cast<Eigen::Index>(measured.t.size());
    const int n = model.actuators;
    if (measured.u.rows() != N || measured.tau.rows() != N || measured.u.cols() != n || measured.tau.cols() != n) {
        throw Error("measurements: expected " + std::to_string(n) + " actuator positions and forces per sample");
    }
    if (N < 10) throw Error("measurements: " + std::to_string(N) + " samples, too few to identify anything");
    for (Eigen::Index k = 1; k < N; ++k) {
        if (!(measured.t[at(static_cast<int>(k))] > measured.t[at(static_cast<int>(k - 1))])) {
            throw Error("measurements: time is not increasing at sample " + std::to_string(k + 1) + " (" +
                        text::sampleTime(measured.t[at(static_cast<int>(k))]) + " after " +
                        text::sampleTime(measured.t[at(static_cast<int>(k - 1))]) + ")");
        }
    }
    const bool given = measured.du.size() > 0 && measured.ddu.size() > 0;
    Eigen::MatrixXd u = measured.u, tau = measured.tau, du, ddu;
    Eigen::Index first = 0, last = N;
    if (options.held_forces || measured.held_forces) {
        for (Eigen::Index k = N - 1; k > 0; --k) tau.row(k) = 0.5 * (tau.row(k - 1) + tau.row(k));
        first = 1;
    }
    if (given) {
        du = measured.du;
        ddu = measured.ddu;
    } else {
        // zero-phase low-pass of u and tau alike (no lag between them), then differences
        const double duration = measured.t.back() - measured.t.front();
        const double rate = static_cast<double>(N - 1) / duration;
        for (Eigen::Index k = 1; k < N; ++k) {
            const double dt = measured.t[at(static_cast<int>(k))] - measured.t[at(static_cast<int>(k - 1))];
            if (std::abs(dt * rate - 1.0) > 0.01) {
                throw Error("measurements: sampling is not uniform at " +
                            text::sampleTime(measured.t[at(static_cast<int>(k))]) +
                            " (needed to filter u; give du and ddu columns instead)");
            }
        }
        const double cutoff = options.cutoff > 0.0 ? options.cutoff : std::min(50.0, 0.1 * rate);
        if (!(cutoff < 0.5 * rate)) throw Error("measurements: the cut-off must be below half the sampling rate");
        const ButterworthFilter low_pass = butterworth(FilterKind::low_pass, 2, cutoff, rate);
        for (Eigen::Index c = 0; c < n; ++c) {
            filterZeroPhase(low_pass, u.col(c), FilterEdges::steady_state);
            filterZeroPhase(low_pass, tau.col(c), FilterEdges::steady_state);
        }
        du = differentiate(u, measured.t);
        ddu = differentiate(du, measured.t);
        // the filter's start and end transients: drop two periods of the cut-off at each end
        const auto trim = static_cast<Eigen::Index>(std::ceil(2.0 * rate / cutoff));
        first = std::max(first, std::min(trim, N / 4));
        last = N - first;
    }
    Motion motion;
    Data data(model);
    Pose p = model.home;
    // the tracker along the samples: Newton from the pose extrapolated along the motion
    PoseTracker tracker(p);
    bool started = false;
    for (Eigen::Index k = first; k < last; ++k) {
        const double t = measured.t[at(static_cast<int>(k))];
        const ActuatorVector uk = u.row(k).transpose();
        Status status;
        if (started) {
            status = tracker.step(model, data, uk);
            p = tracker.pose();
        } else {
            // first sample: the working assembly mode nearest home
            AssemblyModes modes;
            status = directKinematics(model, data, uk, modes);
            double best = std::numeric_limits<double>::infinity();
            bool found = false;
            for (const AssemblyMode& mode : modes) {
                const double d = (mode.p - model.home).norm();
                if (mode.working && d < best) {
                    best = d;
                    p = mode.p;
                    found = true;
                }
            }
            if (status && !found) {
                throw Error(
                    "measurements: no assembly of the robot on its working branches has the actuator "
                    "positions at " +
                    text::sampleTime(t));
            }
            tracker.reset(p);
            started = true;
        }
        if (status) status = inverseDisplacement(model, data, p);
        if (status) status = platformRates(model, data, du.row(k).transpose(), ddu.row(k).transpose());
        if (!status) throw Error("measurements at " + text::sampleTime(t) + ": " + describe(status, model));
        motion.t.push_back(t);
        motion.p.push_back(p);
        motion.dp.push_back(data.t_M);
        motion.ddp.push_back(data.t_M_dot);
    }
    motion.tau = tau.middleRows(first, last - first);
    if (!given) {
        motion.rate = static_cast<double>(N - 1) / (measured.t.back() - measured.t.front());
        motion.cutoff = options.cutoff > 0.0 ? options.cutoff : std::min(50.0, 0.1 * motion.rate);
    }
    return motion;
}

Measurements sensorLog(const PoseLoopResult& run, double noise_u, double noise_tau, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    const auto N = static_cast<Eigen::Index>(run.t.size());
    const int n = run.actuators;
    const bool measured = !run.u_measured.empty();
    if (measured && run.u_measured.size() != run.t.size())
        throw Error("sensorLog: the run's encoder readings do not match its ticks");
    Measurements m;
    m.t = run.t;
    m.held_forces = true;  // the loop holds each tick's command until the next
    m.u.resize(N, n);
    m.tau.resize(N, n);
    for (Eigen::Index k = 0; k < N; ++k) {
        const std::size_t kk = at(static_cast<int>(k));
        for (int a = 0; a < n; ++a) {
            if (measured) {
                m.u(k, a) = run.u_measured[kk](a);
            } else {
                m.u(k, a) = run.u[kk](a) + (noise_u > 0.0 ? noise_u * normal(rng) : 0.0);
            }
            m.tau(k, a) = run.tau[kk](a) + (noise_tau > 0.0 ? noise_tau * normal(rng) : 0.0);
        }
    }
    return m;
}

}  // namespace nocdyn
