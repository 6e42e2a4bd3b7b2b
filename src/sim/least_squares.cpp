// Least-squares identification of a payload or of the base parameters (least_squares.hpp).
#include "nocdyn/sim/least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "nocdyn/detail/eigen_instances.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/printable.hpp"
#include "nocdyn/sim/base_parameters.hpp"
#include "nocdyn/sim/filter.hpp"
#include "nocdyn/sim/regressor.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/detail/index.hpp"

namespace nocdyn {

namespace {

using detail::at;

/// Weighted least squares x of b = A x on the fit rows, with per-actuator weights from the
/// residuals of a first unweighted fit; the covariance from the weighted residuals, counting
/// their correlation along the samples (residualCovariance).
struct LeastSquares {
    Eigen::VectorXd x;
    Eigen::MatrixXd covariance;
    double condition = 0.0;
    double correlation_samples = 1.0;  ///< tau_int of the residuals [samples]
    int block_samples = 1;             ///< L of the batch means
    double effective_samples = 0.0;    ///< T / tau_int
    /// The weighted residual's quadratic form about x: |W (b - A x')|^2 = |W (b - A x)|^2 +
    /// |U (x' - x)|^2, U = R P^T D from the QR (W A D^-1) P = Q R of the scaled columns.
    Eigen::MatrixXd U;
};

/// The plausible size of each unknown, the scale against which identifiability is judged:
/// M, M L and M L^2 for a mass, a first and a second moment of mass (M the robot's moving
/// mass, L its length scale); 0 (judged by the force it explains) for friction.
Eigen::VectorXd plausibleSizes(const Model& model, const std::vector<int>& columns) {
    double M = model.description.platform.mass;
    for (const LimbDescription& limb : model.description.limbs)
        for (const BodyDescription& body : limb.bodies) M += body.mass;
    if (!(M > 0.0)) M = 1.0;
    const double L = model.length_scale;
    Eigen::VectorXd s(static_cast<Eigen::Index>(columns.size()));
    for (std::size_t c = 0; c < columns.size(); ++c) {
        const std::string unit = parameterUnit(model, columns[c]);
        s(static_cast<Eigen::Index>(c)) = unit == "kg"       ? M
                                          : unit == "kg m"   ? M * L
                                          : unit == "kg m^2" ? M * L * L
                                                             : 0.0;
    }
    return s;
}

/// What the motion determines, decided on the unscaled regressor Aw against the
/// data's own noise: each column is multiplied by its unknown's plausible size (plausibleSizes;
/// a friction column is scaled to the rms of the forces), so that it holds the forces such a
/// value would cause. A combination of unknowns whose standard deviation, sigma / s_i (s_i a
/// singular value, sigma the rms residual, at least 1e-9 of the rms force: the
/// precision of exact data), exceeds a plausible size is not determined; nor is one the motion
/// excites a thousand times less than its best (s_i < 1e-3 s_1) unless it is still known to
/// 0.1 % of a plausible size (exact data determine even a weak combination; a filtered log's
/// noise, or a model error, does not). Scaling the columns to unit norm instead would make a
/// column of rounding noise count as full size.
/// Throws nocdyn::Error naming the unknowns such combinations involve, and the values of the
/// others fitted alone.
void requireDetermined(const Model& model, const Eigen::MatrixXd& Aw, const Eigen::VectorXd& bw,
                       const Eigen::VectorXd& sizes, const std::vector<int>& columns,
                       const std::vector<std::string>& names) {
    const Eigen::Index rows = Aw.rows(), k = Aw.cols();
    // the least-squares residual (a rank-revealing solve: columns without effect are fine here)
    const Eigen::VectorXd residual_w = bw - Aw * Aw.colPivHouseholderQr().solve(bw);
    const double force_rms = bw.norm() / std::sqrt(static_cast<double>(std::max<Eigen::Index>(rows, 1)));
    Eigen::VectorXd scale = sizes;
    for (Eigen::Index c = 0; c < k; ++c) {
        if (!(scale(c) > 0.0)) {
            const double column_rms = Aw.col(c).norm() / std::sqrt(static_cast<double>(rows));
            scale(c) = column_rms > 0.0 ? force_rms / column_rms : 0.0;
        }
    }
    const Eigen::MatrixXd As = Aw * scale.asDiagonal();
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(As);
    const Eigen::MatrixXd R = qr.matrixQR().topLeftCorner(k, k).template triangularView<Eigen::Upper>();
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(R, Eigen::ComputeFullV);
    const double dof = static_cast<double>(std::max<Eigen::Index>(rows - k, 1));
    const double sigma = std::max(std::sqrt(residual_w.squaredNorm() / dof), 1e-9 * force_rms);
    const Eigen::VectorXd& sv = svd.singularValues();
    std::vector<bool> involved(at(static_cast<int>(k)), false);
    bool any = false;
    for (Eigen::Index i = 0; i < k; ++i) {
        const double relative_sd = sv(i) > 0.0 ? sigma / sv(i) : std::numeric_limits<double>::infinity();
        const bool weak = sv(i) < 1e-3 * sv(0);
        if (relative_sd <= 1.0 && !(weak && relative_sd > 1e-3)) continue;
        any = true;
        for (Eigen::Index c = 0; c < k; ++c)
            if (std::abs(svd.matrixV()(c, i)) > 0.1) involved[at(static_cast<int>(c))] = true;
    }
    if (!any) return;
    std::string unknown, known;
    std::vector<Eigen::Index> keep;
    for (Eigen::Index c = 0; c < k; ++c) {
        if (involved[at(static_cast<int>(c))]) {
            unknown += (unknown.empty() ? "" : ", ") + text::printable(names[at(static_cast<int>(c))]);
        } else {
            keep.push_back(c);
        }
    }
    if (!keep.empty()) {
        Eigen::MatrixXd Ak(rows, static_cast<Eigen::Index>(keep.size()));
        for (std::size_t j = 0; j < keep.size(); ++j) Ak.col(static_cast<Eigen::Index>(j)) = Aw.col(keep[j]);
        const Eigen::VectorXd xk = Ak.colPivHouseholderQr().solve(bw);
        for (std::size_t j = 0; j < keep.size(); ++j) {
            std::string buffer;
            buffer = text::format(" %.6g ", xk(static_cast<Eigen::Index>(j)));
            known += (known.empty() ? "" : ", ") + text::printable(names[at(static_cast<int>(keep[j]))]) + buffer +
                     parameterUnit(model, columns[at(static_cast<int>(keep[j]))]);
        }
    }
    throw Error("identification: " + unknown +
                " not identifiable from this motion (its effect on the actuator forces is below the data's noise: "
                "a standard deviation above a plausible value, or a combination excited a thousand times less than the "
                "best and not known to 0.1 %); the motion determines " +
                (known.empty() ? std::string("nothing else") : known) +
                ": excite the robot more (rotation, and translation along x and y)");
}

/// The residuals' integrated autocorrelation time tau_int = 1 + 2 sum_(l >= 1) rho(l) [samples],
/// rho the autocorrelation of the weighted residual e_a(t) averaged over the actuators, summed
/// up to the first window W >= 5 tau_int(W) (Sokal's automatic window; at most T / 10). A log
/// low-pass filtered at f_c and sampled at f_s has tau_int about f_s / (2 B), B the filter's
/// equivalent noise bandwidth (0.83 f_c for the zero-phase Butterworth): 120 samples at 10 kHz
/// and 50 Hz, the factor by which white-noise standard deviations are too small squared.
double integratedAutocorrelation(const Eigen::VectorXd& rw, int n) {
    const Eigen::Index T = rw.size() / n;
    if (T < 20) return 1.0;
    std::vector<double> variance(at(n), 0.0);
    for (int a = 0; a < n; ++a) {
        for (Eigen::Index t = 0; t < T; ++t) variance[at(a)] += rw(t * n + a) * rw(t * n + a);
    }
    double tau = 1.0;
    const Eigen::Index max_lag = T / 10;
    for (Eigen::Index l = 1; l <= max_lag; ++l) {
        double rho = 0.0;
        int counted = 0;
        for (int a = 0; a < n; ++a) {
            if (!(variance[at(a)] > 0.0)) continue;
            double sum = 0.0;
            for (Eigen::Index t = 0; t + l < T; ++t) sum += rw(t * n + a) * rw((t + l) * n + a);
            rho += sum / variance[at(a)];
            ++counted;
        }
        if (counted == 0) return 1.0;
        tau += 2.0 * rho / counted;
        if (static_cast<double>(l) >= 5.0 * tau) break;
    }
    return std::max(tau, 1.0);
}

/// The covariance of the score sum_t g_t, g_t = sum_a Aw_(t,a)^T e_(t,a) (t the samples, a the
/// actuators), when the residuals are correlated along the samples: overlapping batch means of
/// L = 10 tau_int samples (at least 1, at most T / 8), the long-run covariance
///   S = T / (L (T - L + 1)) sum_i B_i B_i^T / (1 - L / T),   B_i = g_i + ... + g_(i+L-1),
/// (the score sums to zero at the solution, so no mean is subtracted; 1 - L / T undoes the bias
/// that costs), times T / (T - k) for the k fitted parameters. L = 1 is the white-noise sandwich.
/// The parameters' covariance is then N^-1 S N^-1, N = Aw^T Aw.
struct ScoreCovariance {
    Eigen::MatrixXd S;
    double tau = 1.0;
    int block = 1;
};

ScoreCovariance scoreCovariance(const Eigen::MatrixXd& Aw, const Eigen::VectorXd& rw, int n) {
    const Eigen::Index T = Aw.rows() / n, k = Aw.cols();
    ScoreCovariance out;
    out.tau = integratedAutocorrelation(rw, n);
    const Eigen::Index L = std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::ceil(10.0 * out.tau)), 1,
                                                    std::max<Eigen::Index>(T / 8, 1));
    out.block = static_cast<int>(L);
    // prefix sums of the scores
    Eigen::MatrixXd prefix = Eigen::MatrixXd::Zero(k, T + 1);
    for (Eigen::Index t = 0; t < T; ++t) {
        Eigen::VectorXd g = Eigen::VectorXd::Zero(k);
        for (int a = 0; a < n; ++a) g += Aw.row(t * n + a).transpose() * rw(t * n + a);
        prefix.col(t + 1) = prefix.col(t) + g;
    }
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(k, k);
    for (Eigen::Index i = 0; i + L <= T; ++i) {
        const Eigen::VectorXd B = prefix.col(i + L) - prefix.col(i);
        S.selfadjointView<Eigen::Lower>().rankUpdate(B);
    }
    S = S.selfadjointView<Eigen::Lower>();
    const double Td = static_cast<double>(T), Ld = static_cast<double>(L);
    const double scale =
        Td / (Ld * (Td - Ld + 1.0)) / std::max(1.0 - Ld / Td, 0.5) * Td / std::max(Td - static_cast<double>(k), 1.0);
    out.S = scale * S;
    return out;
}

LeastSquares solveWeighted(const Model& model, const Eigen::MatrixXd& A, const Eigen::VectorXd& b, int n,
                           const std::vector<std::string>& names, const std::vector<int>* columns = nullptr) {
    const Eigen::Index rows = A.rows(), k = A.cols();
    if (columns) requireDetermined(model, A, b, plausibleSizes(model, *columns), *columns, names);
    const Eigen::VectorXd norms = A.colwise().norm();
    for (Eigen::Index c = 0; c < k; ++c) {
        if (!(norms(c) > 0.0)) {
            throw Error("identification: " + text::printable(names[at(static_cast<int>(c))]) +
                        " has no effect on the actuator forces along this motion: it cannot be identified");
        }
    }
    Eigen::VectorXd weight = Eigen::VectorXd::Ones(n);
    LeastSquares result;
    for (int pass = 0; pass < 2; ++pass) {
        Eigen::MatrixXd Aw(rows, k);
        Eigen::VectorXd bw(rows);
        for (Eigen::Index r = 0; r < rows; ++r) {
            const double w = weight(r % n);
            Aw.row(r) = w * A.row(r).cwiseQuotient(norms.transpose());
            bw(r) = w * b(r);
        }
        // V names the weakest direction when the regressor is ill-conditioned
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Aw.transpose() * Aw, Eigen::ComputeFullV);
        const Eigen::VectorXd& sv = svd.singularValues();
        result.condition = std::sqrt(sv(0) / sv(k - 1));
        if (!(result.condition < 1e7)) {
            // the weakest direction names the parameter(s) it involves
            const Eigen::VectorXd v = svd.matrixV().col(k - 1);
            Eigen::Index worst = 0;
            v.cwiseAbs().maxCoeff(&worst);
            throw Error("identification: " + text::printable(names[at(static_cast<int>(worst))]) +
                        " is not identifiable from this motion (condition number of the regressor " +
                        std::to_string(result.condition) + ", above 1e7): excite the robot more");
        }
        const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Aw);
        const Eigen::VectorXd xs = qr.solve(bw);
        result.x = xs.cwiseQuotient(norms);
        const Eigen::VectorXd residual = b - A * result.x;
        if (pass == 0) {
            // per-actuator rms residual: weights 1/sigma_a
            for (int a = 0; a < n; ++a) {
                double sum = 0.0;
                Eigen::Index count = 0;
                for (Eigen::Index r = a; r < rows; r += n, ++count) sum += residual(r) * residual(r);
                const double sigma = std::sqrt(sum / static_cast<double>(std::max<Eigen::Index>(count, 1)));
                weight(a) = sigma > 0.0 ? 1.0 / sigma : 1.0;
            }
            // equal weights when the data are exact (no residual to weigh by)
            if (!(weight.maxCoeff() < 1e300) || residual.norm() <= 1e-12 * b.norm()) weight.setOnes();
            weight /= weight.maxCoeff();
        } else {
            Eigen::VectorXd rw(rows);
            for (Eigen::Index r = 0; r < rows; ++r) rw(r) = weight(r % n) * residual(r);
            const Eigen::MatrixXd N = Aw.transpose() * Aw;
            const Eigen::MatrixXd N_inv = N.ldlt().solve(Eigen::MatrixXd::Identity(k, k));
            const Eigen::VectorXd inv_norms = norms.cwiseInverse();
            const ScoreCovariance score = scoreCovariance(Aw, rw, n);
            result.covariance = inv_norms.asDiagonal() * N_inv * score.S * N_inv * inv_norms.asDiagonal();
            result.correlation_samples = score.tau;
            result.block_samples = score.block;
            result.effective_samples = static_cast<double>(rows) / static_cast<double>(n) / score.tau;
            const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(k, k).template triangularView<Eigen::Upper>();
            result.U = (R * qr.colsPermutation().transpose()) * norms.asDiagonal();
        }
    }
    return result;
}

/// rms per actuator of rows [begin, end) of a stacked residual.
std::vector<double> rmsPerActuator(const Eigen::VectorXd& r, int n) {
    std::vector<double> rms(at(n), 0.0);
    const Eigen::Index samples = r.size() / n;
    if (samples == 0) return rms;
    for (int a = 0; a < n; ++a) {
        double sum = 0.0;
        for (Eigen::Index s = 0; s < samples; ++s) sum += r(s * n + a) * r(s * n + a);
        rms[at(a)] = std::sqrt(sum / static_cast<double>(samples));
    }
    return rms;
}

/// Stacked regressor columns `columns` and the known part Y pi_known over the motion.
struct Stacked {
    Eigen::MatrixXd A;
    Eigen::VectorXd known, tau;
};

/// True for a joint's Coulomb friction parameter (the regressor column sign q').
bool isCoulomb(const Model& model, int index) {
    const int body_end = kBodyParameters * model.bodies;
    return index >= body_end && (index - body_end) % kJointParameters == 1;
}

/// Parallel filtering: the motion's tau went through the zero-phase low-pass, which smooths the
/// step of each Coulomb force at a reversal, while sign q' of the filtered motion still steps.
/// The Coulomb columns of s.A and the Coulomb part of s.known go through the same filter, per
/// actuator along the samples, so that both sides of tau = Y pi are filtered alike (otherwise
/// the friction comes out low and the difference leaks into the other parameters).
void filterCoulombColumns(const Model& model, const Motion& motion, const std::vector<int>& columns,
                          const ParameterVector& pi, bool subtract_known, const Calibration* calibration, Stacked& s) {
    const int n = model.actuators;
    const auto N = static_cast<Eigen::Index>(motion.t.size());
    Eigen::VectorXd series(N);
    const ButterworthFilter low_pass = butterworth(FilterKind::low_pass, 2, motion.cutoff, motion.rate);
    const auto filterRows = [&](Eigen::VectorXd& x) {
        for (int a = 0; a < n; ++a) {
            for (Eigen::Index k = 0; k < N; ++k) series(k) = x(k * n + a);
            filterZeroPhase(low_pass, series, FilterEdges::steady_state);
            for (Eigen::Index k = 0; k < N; ++k) x(k * n + a) = series(k);
        }
    };
    Eigen::VectorXd column(N * n);
    for (std::size_t c = 0; c < columns.size(); ++c) {
        if (!isCoulomb(model, columns[c])) continue;
        column = s.A.col(static_cast<Eigen::Index>(c));
        filterRows(column);
        s.A.col(static_cast<Eigen::Index>(c)) = column;
    }
    if (!subtract_known) return;
    // the known Coulomb part, recomputed from the motion, replaced by its filtered self
    Eigen::VectorXd coulomb = Eigen::VectorXd::Zero(N * n);
    Data data(model);
    RegressorMatrix Y;
    bool any = false;
    for (Eigen::Index k = 0; k < N; ++k) {
        const std::size_t kk = at(static_cast<int>(k));
        if (!inverseDynamicsRegressor(model, data, motion.p[kk], motion.dp[kk], motion.ddp[kk], Y)) continue;
        if (calibration != nullptr) {
            for (std::size_t c = 0; c < calibration->independent.size(); ++c) {
                const int index = calibration->independent[c];
                if (!isCoulomb(model, index)) continue;
                coulomb.segment(k * n, n) += Y.col(index) * calibration->beta(static_cast<Eigen::Index>(c));
                any = true;
            }
        } else {
            for (int index = kBodyParameters * model.bodies; index < static_cast<int>(pi.size()); ++index) {
                if (!isCoulomb(model, index) || pi(index) == 0.0) continue;
                coulomb.segment(k * n, n) += Y.col(index) * pi(index);
                any = true;
            }
        }
    }
    if (!any) return;
    s.known -= coulomb;
    filterRows(coulomb);
    s.known += coulomb;
}

Stacked stack(const Model& model, const Motion& motion, const std::vector<int>& columns, bool subtract_known,
              const Calibration* calibration = nullptr) {
    const int n = model.actuators;
    const auto N = static_cast<Eigen::Index>(motion.t.size());
    Stacked s;
    s.A.resize(N * n, static_cast<Eigen::Index>(columns.size()));
    s.known = Eigen::VectorXd::Zero(N * n);
    s.tau.resize(N * n);
    ParameterVector pi = standardParameters(model);
    for (const int c : columns) pi(c) = 0.0;
    Data data(model);
    RegressorMatrix Y;
    for (Eigen::Index k = 0; k < N; ++k) {
        const std::size_t kk = at(static_cast<int>(k));
        const Status status = inverseDynamicsRegressor(model, data, motion.p[kk], motion.dp[kk], motion.ddp[kk], Y);
        if (!status)
            throw Error("identification at " + text::sampleTime(motion.t[kk]) + ": " + describe(status, model));
        for (std::size_t c = 0; c < columns.size(); ++c)
            s.A.block(k * n, static_cast<Eigen::Index>(c), n, 1) = Y.col(columns[c]);
        if (subtract_known && calibration) {
            // Y pi = Y_b beta: the calibrated robot
            for (std::size_t c = 0; c < calibration->independent.size(); ++c)
                s.known.segment(k * n, n) +=
                    Y.col(calibration->independent[c]) * calibration->beta(static_cast<Eigen::Index>(c));
        } else if (subtract_known) {
            s.known.segment(k * n, n) = Y * pi;
        }
        s.tau.segment(k * n, n) = motion.tau.row(k).transpose();
    }
    if (motion.cutoff > 0.0) filterCoulombColumns(model, motion, columns, pi, subtract_known, calibration, s);
    return s;
}

void fillFit(const Model& model, const Motion& motion, const Stacked& s, const Eigen::VectorXd& x,
             Eigen::Index fit_samples, FitReport& fit) {
    const int n = model.actuators;
    const Eigen::Index N = static_cast<Eigen::Index>(motion.t.size());
    const Eigen::VectorXd predicted = s.known + s.A * x;
    const Eigen::VectorXd residual = s.tau - predicted;
    fit.fit_samples = static_cast<int>(fit_samples);
    fit.holdout_samples = static_cast<int>(N - fit_samples);
    fit.rms_fit = rmsPerActuator(residual.head(fit_samples * n), n);
    fit.rms_holdout = rmsPerActuator(residual.tail((N - fit_samples) * n), n);
    fit.rms_measured = rmsPerActuator(s.tau.tail((N - fit_samples) * n), n);
    fit.t.assign(motion.t.begin() + fit_samples, motion.t.end());
    fit.measured.resize(N - fit_samples, n);
    fit.predicted.resize(N - fit_samples, n);
    for (Eigen::Index k = fit_samples; k < N; ++k) {
        fit.measured.row(k - fit_samples) = s.tau.segment(k * n, n).transpose();
        fit.predicted.row(k - fit_samples) = predicted.segment(k * n, n).transpose();
    }
}

// Bounded payload. The bounds are on the physical parameters z = [m, c_x, c_y, I, friction..]
// while the residual is quadratic in the linear ones x(z) = [m, m c_x, m c_y, I + m |c|^2,
// friction..]: a box in z is no box in x (c = h / m, and I = I_O - |h|^2 / m <= I_max is not
// even convex in x), so a box-constrained least squares in x would be wrong. Instead
//   minimise |U (x(z) - x_ls)|^2 over z in the box,
// which is the weighted residual up to a constant (LeastSquares::U), by Gauss-Newton in z:
// each step solves the linearised problem |U (x(z) + J dz - x_ls)|^2 exactly within the box (a
// convex quadratic: its minimiser is the unconstrained minimiser on one face of the box, so the
// best feasible one of the 3^4 faces, each of m, c_x, c_y, I free or on either bound, is it),
// then halves the step until the residual decreases. The friction parameters stay free.
constexpr int kPhysical = 4;  // m, c_x, c_y, I

using PhysicalBox = Eigen::Matrix<double, kPhysical, 1>;

Eigen::VectorXd linearParameters(const Eigen::VectorXd& z) {
    Eigen::VectorXd x = z;
    x(1) = z(0) * z(1);
    x(2) = z(0) * z(2);
    x(3) = z(3) + z(0) * (z(1) * z(1) + z(2) * z(2));
    return x;
}

Eigen::MatrixXd linearJacobian(const Eigen::VectorXd& z) {
    const Eigen::Index k = z.size();
    Eigen::MatrixXd J = Eigen::MatrixXd::Identity(k, k);
    J.col(0).head<kPhysical>() << 1.0, z(1), z(2), z(1) * z(1) + z(2) * z(2);
    J.col(1).head<kPhysical>() << 0.0, z(0), 0.0, 2.0 * z(0) * z(1);
    J.col(2).head<kPhysical>() << 0.0, 0.0, z(0), 2.0 * z(0) * z(2);
    return J;
}

/// min |M d - r|^2 with lo_i <= d_i <= hi_i for the physical entries (the rest free): the best
/// feasible face minimiser (see above); `tol` the feasibility slack per entry.
Eigen::VectorXd boxLeastSquares(const Eigen::MatrixXd& M, const Eigen::VectorXd& r, const PhysicalBox& lo,
                                const PhysicalBox& hi, const PhysicalBox& tol) {
    const Eigen::Index k = M.cols();
    Eigen::VectorXd best = Eigen::VectorXd::Zero(k);
    double best_cost = std::numeric_limits<double>::infinity();
    constexpr int kFaces = 81;  // 3^kPhysical
    for (int face = 0; face < kFaces; ++face) {
        Eigen::VectorXd d = Eigen::VectorXd::Zero(k);
        std::vector<Eigen::Index> free;
        bool valid = true;
        int code = face;
        for (int i = 0; i < kPhysical; ++i, code /= 3) {
            const int side = code % 3;  // 0 free, 1 on the lower bound, 2 on the upper
            if (side == 0) {
                free.push_back(i);
                continue;
            }
            const double bound = side == 1 ? lo(i) : hi(i);
            if (!std::isfinite(bound) || (side == 2 && hi(i) == lo(i))) valid = false;
            d(i) = bound;
        }
        if (!valid) continue;
        for (Eigen::Index i = kPhysical; i < k; ++i) free.push_back(i);
        if (!free.empty()) {
            Eigen::MatrixXd Mf(M.rows(), static_cast<Eigen::Index>(free.size()));
            for (std::size_t j = 0; j < free.size(); ++j) Mf.col(static_cast<Eigen::Index>(j)) = M.col(free[j]);
            const Eigen::VectorXd df = Mf.colPivHouseholderQr().solve(r - M * d);
            for (std::size_t j = 0; j < free.size(); ++j) d(free[j]) = df(static_cast<Eigen::Index>(j));
        }
        for (int i = 0; i < kPhysical && valid; ++i) {
            if (!(d(i) >= lo(i) - tol(i) && d(i) <= hi(i) + tol(i))) valid = false;
            d(i) = std::clamp(d(i), lo(i), hi(i));
        }
        if (!valid) continue;
        const double cost = (M * d - r).squaredNorm();
        if (cost < best_cost) {
            best_cost = cost;
            best = d;
        }
    }
    return best;
}

/// The z in [lo, hi] (physical entries) minimising |U (x(z) - x_ls)|^2, by Gauss-Newton from
/// `start` (feasible); `scale` the size of each entry (steps below 1e-13 of it end the iteration).
Eigen::VectorXd boundedPayload(const Eigen::MatrixXd& U, const Eigen::VectorXd& x_ls, const PhysicalBox& lo,
                               const PhysicalBox& hi, const Eigen::VectorXd& scale, Eigen::VectorXd z) {
    const auto cost = [&](const Eigen::VectorXd& zz) { return (U * (linearParameters(zz) - x_ls)).squaredNorm(); };
    double f = cost(z);
    for (int iteration = 0; iteration < 100 && f > 0.0; ++iteration) {
        const Eigen::VectorXd r = U * (x_ls - linearParameters(z));
        const Eigen::VectorXd d = boxLeastSquares(U * linearJacobian(z), r, lo - z.head<kPhysical>(),
                                                  hi - z.head<kPhysical>(), 1e-12 * scale.head<kPhysical>());
        double alpha = 1.0;
        bool decreased = false;
        for (int halving = 0; halving < 40 && !decreased; ++halving, alpha *= 0.5) {
            Eigen::VectorXd trial = z + alpha * d;
            trial.head<kPhysical>() = trial.head<kPhysical>().cwiseMax(lo).cwiseMin(hi);
            const double f_trial = cost(trial);
            if (f_trial < f) {
                z = trial;
                f = f_trial;
                decreased = true;
            }
        }
        if (!decreased || (alpha * d).cwiseQuotient(scale).cwiseAbs().maxCoeff() < 1e-13) break;
    }
    return z;
}

}  // namespace

void checkCalibration(const Model& model, const Calibration& calibration) {
    const BaseParameters base = baseParameters(model);
    if (calibration.beta.size() != static_cast<Eigen::Index>(calibration.independent.size()) ||
        calibration.independent != base.independent) {
        std::string which = "its number of base parameters";
        for (std::size_t c = 0; c < std::min(calibration.independent.size(), base.independent.size()); ++c) {
            if (calibration.independent[c] != base.independent[c]) {
                which = "base parameter " + std::to_string(c + 1) + " (" +
                        text::printable(parameterName(model, calibration.independent[c])) + ", this robot's is " +
                        text::printable(parameterName(model, base.independent[c])) + ")";
                break;
            }
        }
        throw Error("identification: the calibration was not made for this robot: " + which + " differs (" +
                    std::to_string(calibration.independent.size()) + " base parameters, this robot has " +
                    std::to_string(base.rank) + ")");
    }
    for (Eigen::Index c = 0; c < calibration.beta.size(); ++c) {
        if (!std::isfinite(calibration.beta(c)))
            throw Error("identification: calibrated base parameter " + std::to_string(c + 1) + " is not finite");
    }
}

namespace {

void fillCorrelation(const LeastSquares& ls, FitReport& fit) {
    fit.condition = ls.condition;
    fit.correlation_samples = ls.correlation_samples;
    fit.block_samples = ls.block_samples;
    fit.effective_samples = ls.effective_samples;
}

/// The friction estimates of a payload fit: unknowns `first`.. of x, their covariance that of
/// result.covariance.
void frictionEstimates(const Model& model, const std::vector<std::string>& names, const std::vector<int>& columns,
                       const Eigen::VectorXd& x, const ParameterVector& pi, Eigen::Index first, PayloadResult& result) {
    for (Eigen::Index c = first; c < x.size(); ++c) {
        Estimate e;
        e.name = names[at(static_cast<int>(c))];
        e.unit = parameterUnit(model, columns[at(static_cast<int>(c))]);
        e.value = x(c);
        e.stddev = std::sqrt(result.covariance(c, c));
        e.prior = pi(columns[at(static_cast<int>(c))]);
        result.friction.push_back(e);
    }
}

Eigen::Index fitSamples(const Motion& motion, const IdentificationOptions& options, int parameters, int n) {
    const auto N = static_cast<Eigen::Index>(motion.t.size());
    if (!(options.holdout >= 0.0 && options.holdout < 1.0))
        throw Error("identification: the held-out fraction must be in [0, 1)");
    const auto fit = static_cast<Eigen::Index>(std::floor((1.0 - options.holdout) * static_cast<double>(N)));
    if (fit * n < static_cast<Eigen::Index>(3) * parameters) {
        throw Error("identification: " + std::to_string(fit) + " samples to fit " + std::to_string(parameters) +
                    " parameters with " + std::to_string(n) + " forces each: too few (need at least " +
                    std::to_string((3 * parameters + n - 1) / n) + ")");
    }
    return fit;
}

}  // namespace

PayloadResult identifyPayload(const Model& model, const Motion& motion, const IdentificationOptions& options) {
    const int n = model.actuators;
    // a two-DOF robot's payload is a point mass at the tool point, which never turns: its c.o.m.
    // offset and inertia have no effect on the forces (zero regressor columns), only its mass
    const bool point = model.task_dimension == 2;
    const int inertial = point ? 1 : kBodyParameters;
    std::vector<int> columns;
    std::vector<std::string> names{"payload mass", "payload c.o.m. x (mass times)", "payload c.o.m. y (mass times)",
                                   "payload inertia"};
    names.resize(static_cast<std::size_t>(inertial));
    const int platform = bodyParameterIndex(model.platformBody());
    columns.reserve(static_cast<std::size_t>(kBodyParameters) + 2 * static_cast<std::size_t>(n));
    for (int c = 0; c < inertial; ++c) columns.push_back(platform + c);
    if (options.friction) {
        for (int a = 0; a < n; ++a) {
            const int index = jointParameterIndex(model, model.actuator_limb[at(a)], model.actuator_joint[at(a)]);
            columns.push_back(index);
            columns.push_back(index + 1);
            names.push_back(parameterName(model, index));
            names.push_back(parameterName(model, index + 1));
        }
    }
    const auto k = static_cast<Eigen::Index>(columns.size());
    const Eigen::Index fit = fitSamples(motion, options, static_cast<int>(k), n);
    const Calibration* calibration = options.calibration ? &*options.calibration : nullptr;
    if (calibration && options.friction) {
        throw Error(
            "identification: a calibration holds the joints' friction already; identify the payload "
            "against it without friction");
    }
    if (calibration) checkCalibration(model, *calibration);
    Stacked s = stack(model, motion, columns, true, calibration);
    // the platform's own parameters stay in the known part: the unknowns are the payload's
    // (a calibration's known part holds them already, within its base parameters)
    const ParameterVector pi = standardParameters(model);
    const Eigen::Vector4d platform_pi = pi.segment<kBodyParameters>(platform);
    if (!calibration) {
        for (int c = 0; c < inertial; ++c) s.known += s.A.col(c) * platform_pi(c);
    }
    const Eigen::VectorXd b = (s.tau - s.known).head(fit * n);
    const LeastSquares ls = solveWeighted(model, s.A.topRows(fit * n), b, n, names, &columns);
    Eigen::VectorXd x = ls.x;
    PayloadResult result;
    // the box: the prior's bounds, mass > 0 and inertia about the c.o.m. >= 0
    const PayloadPrior& prior = options.prior;
    const char* const bound_names[kPhysical] = {"mass", "com_x", "com_y", "inertia"};
    const Bounds bounds[kPhysical] = {prior.mass, prior.com_x, prior.com_y, prior.inertia};
    for (int i = 0; i < kPhysical; ++i) {
        if (std::isnan(bounds[i].lower) || std::isnan(bounds[i].upper) || bounds[i].lower > bounds[i].upper) {
            throw Error(std::string("identification: the prior's bounds on the payload ") + bound_names[i] +
                        " are not an interval [lower, upper]");
        }
    }
    if (!(prior.mass.upper > 0.0))
        throw Error("identification: the prior's upper bound on the payload mass is not positive");
    if (point) {
        for (int i = 1; i < kPhysical; ++i) {
            if (std::isfinite(bounds[i].lower) || std::isfinite(bounds[i].upper)) {
                throw Error(std::string("identification: the prior bounds the payload ") + bound_names[i] +
                            ", but a two-DOF robot's payload is a point mass at the tool point: only its mass is "
                            "identified (no c.o.m. offset, no inertia)");
            }
        }
    }
    const double m = x(0);
    if (!(m > 0.0) && !(prior.mass.lower > 0.0)) {
        std::string buffer;
        buffer = text::format(
            "identification: the payload mass comes out as %.6g kg (standard deviation %.3g kg), not "
            "positive: no payload, or the robot file's parameters do not match the robot",
            m, std::sqrt(ls.covariance(0, 0)));
        throw Error(buffer);
    }
    if (point) {
        // the mass enters linearly: outside its bounds the estimate is on the bound it crosses,
        // the friction refitted there (the minimiser of |U (x' - x_ls)|^2 with x'_0 fixed)
        if (m < prior.mass.lower || m > prior.mass.upper) {
            const bool upper = m > prior.mass.upper;
            const double bound = upper ? prior.mass.upper : prior.mass.lower;
            const double step = bound - m;
            if (k > 1) x.tail(k - 1) += ls.U.rightCols(k - 1).colPivHouseholderQr().solve(-ls.U.col(0) * step);
            x(0) = bound;
            result.active_bounds.push_back({"mass", upper, bound, m});
        }
        result.mass = x(0);
        result.covariance = ls.covariance;
        result.mass_sd = std::sqrt(ls.covariance(0, 0));
        frictionEstimates(model, names, columns, x, pi, 1, result);
        fillFit(model, motion, s, x, fit, result.fit);
        fillCorrelation(ls, result.fit);
        return result;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Eigen::VectorXd z_ls = x;  // the unbounded solution's physical parameters (NaN without a mass)
    if (m > 0.0) {
        z_ls.segment<2>(1) = x.segment<2>(1) / m;
        z_ls(3) = x(3) - x.segment<2>(1).squaredNorm() / m;
    } else {
        z_ls.segment<3>(1).setConstant(nan);
    }
    result.inertia_unconstrained = z_ls(3);
    PhysicalBox lo, hi;
    for (int i = 0; i < kPhysical; ++i) {
        lo(i) = bounds[i].lower;
        hi(i) = bounds[i].upper;
    }
    // mass > 0: without a lower bound from the prior, a floor far below the estimate
    const bool mass_floor = !(lo(0) > 0.0);
    if (mass_floor) lo(0) = 1e-6 * m;
    lo(3) = std::max(lo(3), 0.0);
    Eigen::Vector4d physical = z_ls.head<kPhysical>();
    bool inside = m > 0.0;
    for (int i = 0; i < kPhysical; ++i) inside = inside && z_ls(i) >= lo(i) && z_ls(i) <= hi(i);
    if (!inside) {
        // sizes of the entries: the mass, the robot's length scale, m L^2, the friction values
        double m_ref = std::abs(m);
        for (const double v : {lo(0), hi(0)}) {
            if (std::isfinite(v)) m_ref = std::max(m_ref, v);
        }
        const double L = model.length_scale;
        Eigen::VectorXd scale = x.cwiseAbs().cwiseMax(1e-12);
        scale.head<kPhysical>() << m_ref, L, L, m_ref * L * L;
        // from the unbounded solution moved into the box, and from the box's middle
        const auto inBox = [&](const Eigen::VectorXd& z) {
            Eigen::VectorXd c = z;
            for (int i = 0; i < kPhysical; ++i) {
                if (!std::isfinite(c(i))) c(i) = i == 0 ? m_ref : 0.0;
                c(i) = std::clamp(c(i), lo(i), hi(i));
            }
            return c;
        };
        Eigen::VectorXd middle = z_ls;
        for (int i = 0; i < kPhysical; ++i) {
            if (std::isfinite(lo(i)) && std::isfinite(hi(i))) middle(i) = 0.5 * (lo(i) + hi(i));
        }
        const auto cost = [&](const Eigen::VectorXd& z) { return (ls.U * (linearParameters(z) - x)).squaredNorm(); };
        Eigen::VectorXd z = boundedPayload(ls.U, x, lo, hi, scale, inBox(z_ls));
        const Eigen::VectorXd z_middle = boundedPayload(ls.U, x, lo, hi, scale, inBox(middle));
        if (cost(z_middle) < cost(z)) z = z_middle;
        for (int i = 0; i < kPhysical; ++i) {
            const double tol = 1e-9 * scale(i);
            const bool at_lower = z(i) - lo(i) <= tol, at_upper = hi(i) - z(i) <= tol;
            if (!at_lower && !at_upper) continue;
            if (i == 0 && at_lower && mass_floor) {
                throw Error(
                    "identification: within the prior's bounds the payload mass comes out as 0: no payload, or "
                    "the robot file's parameters do not match the robot");
            }
            // equal bounds (a fixed parameter): the side the unbounded solution lies beyond
            const bool upper = at_lower && at_upper ? z_ls(i) > hi(i) : at_upper;
            z(i) = upper ? hi(i) : lo(i);
            result.active_bounds.push_back({bound_names[i], upper, z(i), z_ls(i)});
            if (i == 3 && at_lower && z(i) == 0.0) result.inertia_constrained = true;
        }
        x = linearParameters(z);
        physical = z.head<kPhysical>();
    }
    result.mass = physical(0);
    result.com = physical.segment<2>(1);
    result.inertia = physical(3);
    // covariance of (m, c, I, friction) from that of x = (m, m c, I_O, friction) by the
    // first-order map z(x)
    Eigen::MatrixXd G = Eigen::MatrixXd::Identity(k, k);
    const double mm = x(0);
    const Vector2 hh = x.segment<2>(1);
    G.topLeftCorner<4, 4>().row(0) << 1.0, 0.0, 0.0, 0.0;
    G.topLeftCorner<4, 4>().row(1) << -hh.x() / (mm * mm), 1.0 / mm, 0.0, 0.0;
    G.topLeftCorner<4, 4>().row(2) << -hh.y() / (mm * mm), 0.0, 1.0 / mm, 0.0;
    G.topLeftCorner<4, 4>().row(3) << hh.squaredNorm() / (mm * mm), -2.0 * hh.x() / mm, -2.0 * hh.y() / mm, 1.0;
    result.covariance = G * ls.covariance * G.transpose();
    const Eigen::MatrixXd& cov = result.covariance;
    result.mass_sd = std::sqrt(cov(0, 0));
    result.com_sd = Vector2(std::sqrt(cov(1, 1)), std::sqrt(cov(2, 2)));
    result.inertia_sd = std::sqrt(cov(3, 3));
    frictionEstimates(model, names, columns, x, pi, kPhysical, result);
    // the held-out check uses the platform's own parameters in the known part
    fillFit(model, motion, s, x, fit, result.fit);
    fillCorrelation(ls, result.fit);
    return result;
}

BaseResult identifyBase(const Model& model, const Motion& motion, const IdentificationOptions& options) {
    const BaseParameters base = baseParameters(model);
    const int n = model.actuators;
    const Eigen::Index fit = fitSamples(motion, options, base.rank, n);
    Stacked s = stack(model, motion, base.independent, false);
    std::vector<std::string> names;
    names.reserve(base.independent.size());
    for (const int c : base.independent) names.push_back(parameterName(model, c));
    const LeastSquares ls = solveWeighted(model, s.A.topRows(fit * n), s.tau.head(fit * n), n, names);
    const Eigen::VectorXd prior = base.K * standardParameters(model);
    BaseResult result;
    for (int k = 0; k < base.rank; ++k) {
        Estimate e;
        e.name = "beta_" + std::to_string(k + 1) + " (" + names[at(k)] + " + ...)";
        e.unit = parameterUnit(model, base.independent[at(k)]);
        e.value = ls.x(k);
        e.stddev = std::sqrt(ls.covariance(k, k));
        e.prior = prior(k);
        result.beta.push_back(e);
    }
    result.calibration.independent = base.independent;
    result.calibration.beta = ls.x;
    result.covariance = ls.covariance;
    fillFit(model, motion, s, ls.x, fit, result.fit);
    fillCorrelation(ls, result.fit);
    return result;
}
}  // namespace nocdyn
