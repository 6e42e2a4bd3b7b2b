// The rigid robot linearised at an operating point, and its frequency response
// (analysis/linearization.hpp).
#include "nocdyn/analysis/linearization.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "nocdyn/detail/eigen_instances.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

const char* name(LinearInput input) { return input == LinearInput::force ? "tau" : "uc"; }

Status linearize(const Model& model, Data& data, const Pose& p, const Twist& dp, const ActuatorVector& tau,
                 LinearOutput output, StateSpace& out) {
    ForwardDynamicsDerivatives d;
    if (const Status status = forwardDynamicsDerivatives(model, data, p, dp, tau, d); !status) return status;
    const int n = model.actuators;
    out.output = output;
    out.inputs.assign(static_cast<std::size_t>(n), LinearInput::force);
    if (model.task_dimension == 2) {
        // translation: the state is [p_t; dp_t] over the task coordinates [x, y] (p = E p_t):
        // A = [0 I; E^T df/dp E, E^T df/d(dp) E], B = [0; E^T df/dtau], C of the actuators A_p E
        out.A = Eigen::MatrixXd::Zero(4, 4);
        out.A.topRightCorner<2, 2>().setIdentity();
        out.A.block<2, 2>(2, 0) = d.d_p.bottomRightCorner<2, 2>();
        out.A.block<2, 2>(2, 2) = d.d_dp.bottomRightCorner<2, 2>();
        out.B = Eigen::MatrixXd::Zero(4, n);
        out.B.bottomRows<2>() = d.d_tau.bottomRows<2>();
        if (output == LinearOutput::platform_acceleration) {
            out.C = out.A.bottomRows<2>();
            out.D = out.B.bottomRows<2>();
        } else {
            out.C = Eigen::MatrixXd::Zero(n, 4);
            out.C.leftCols<2>() = (Eigen::MatrixXd(data.A) * platformTwistMap(p.tail<2>())).rightCols<2>();
            out.D = Eigen::MatrixXd::Zero(n, n);
        }
        return {};
    }
    out.A = Eigen::MatrixXd::Zero(6, 6);
    out.A.topRightCorner<3, 3>().setIdentity();
    out.A.block<3, 3>(3, 0) = d.d_p;
    out.A.block<3, 3>(3, 3) = d.d_dp;
    out.B = Eigen::MatrixXd::Zero(6, n);
    out.B.bottomRows<3>() = d.d_tau;
    if (output == LinearOutput::platform_acceleration) {
        out.C = out.A.bottomRows<3>();
        out.D = out.B.bottomRows<3>();
    } else {
        // du = A S(c) dp/dt: the actuator variables' derivative by the pose is A_p
        out.C = Eigen::MatrixXd::Zero(n, 6);
        out.C.leftCols<3>() = Eigen::MatrixXd(data.A) * platformTwistMap(p.tail<2>());
        out.D = Eigen::MatrixXd::Zero(n, n);
    }
    return {};
}

namespace {

/// The modal damping of the lumped model, C = M Phi diag(2 zeta w_i) Phi^T M with K Phi = M Phi
/// Omega^2, Phi^T M Phi = I (a free direction, w_i = 0, is undamped).
Matrix3 modalDamping(const Matrix3& M, const Matrix3& K, double zeta) {
    if (!(zeta > 0.0)) return Matrix3::Zero();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix3> eig(0.5 * (K + K.transpose()), 0.5 * (M + M.transpose()));
    if (eig.info() != Eigen::Success) return Matrix3::Zero();
    const Vector3 w = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
    const Matrix3 MPhi = M * eig.eigenvectors();
    return MPhi * (2.0 * zeta * w).asDiagonal() * MPhi.transpose();
}

}  // namespace

Status linearizeCompliant(const Model& model, const StiffnessModel& compliance, Data& data, const Pose& p,
                          const Twist& dp, const ActuatorVector& tau, LinearOutput output, StateSpace& out) {
    if (!compliance.any) return linearize(model, data, p, dp, tau, output, out);
    if (model.task_dimension == 2) {
        throw Error(
            "the lumped compliant model of a two-DOF robot (motion: translation) is not built: its rigid "
            "model is");
    }
    ForwardDynamicsDerivatives d;
    if (const Status status = forwardDynamicsDerivatives(model, data, p, dp, tau, d); !status) return status;
    StiffnessData stiffness;
    if (const Status status = cartesianStiffness(model, compliance, data, stiffness); !status) return status;
    const int n = model.actuators;
    const Matrix3 S = platformTwistMap(data.p.tail<2>());
    const Eigen::PartialPivLU<Matrix3> M(d.M_p);
    // B_Q: the generalized force per unit input
    Eigen::MatrixXd BQ = Eigen::MatrixXd::Zero(3, n);
    out.inputs.assign(static_cast<std::size_t>(n), LinearInput::force);
    for (int a = 0; a < n; ++a) {
        const int j = model.actuator_limb[static_cast<std::size_t>(a)];
        const auto J = static_cast<std::size_t>(j);
        const auto q = static_cast<std::size_t>(model.actuator_joint[static_cast<std::size_t>(a)]);
        const LimbData& limb = data.limb[J];
        const Matrix3& K_j = stiffness.K_limb[J];
        if (compliance.joint[J][q] != JointSpring::free) {
            out.inputs[static_cast<std::size_t>(a)] = LinearInput::commanded_position;
            BQ.col(a) = S.transpose() * (K_j * limb.s[q]);  // S^T K_j s_a
            continue;
        }
        // W_j e_a: a wrench with G_f^T w = e_a (the free joints' forces), least norm
        Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 3, 3> Gft(0, 3);
        Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1> e(0);
        for (std::size_t r = 0; r < 3; ++r) {
            if (compliance.joint[J][r] != JointSpring::free) continue;
            Gft.conservativeResize(Gft.rows() + 1, Eigen::NoChange);
            e.conservativeResize(e.rows() + 1);
            Gft.row(Gft.rows() - 1) = limb.s[r].transpose();
            e(e.rows() - 1) = r == q ? 1.0 : 0.0;
        }
        const Vector3 w = Eigen::JacobiSVD<decltype(Gft)>(Gft, Eigen::ComputeFullU | Eigen::ComputeFullV).solve(e);
        const Matrix3 C_j = limbCompliance(compliance, data, j);
        BQ.col(a) = S.transpose() * ((Matrix3::Identity() - K_j * C_j) * w);
    }
    out.output = output;
    out.A = Eigen::MatrixXd::Zero(6, 6);
    out.A.topRightCorner<3, 3>().setIdentity();
    out.A.block<3, 3>(3, 0) = d.d_p - M.solve(stiffness.K);
    out.A.block<3, 3>(3, 3) = d.d_dp - M.solve(modalDamping(d.M_p, stiffness.K, model.description.damping_ratio));
    out.B = Eigen::MatrixXd::Zero(6, n);
    out.B.bottomRows<3>() = M.solve(BQ);
    if (output == LinearOutput::platform_acceleration) {
        out.C = out.A.bottomRows<3>();
        out.D = out.B.bottomRows<3>();
    } else {
        out.C = Eigen::MatrixXd::Zero(n, 6);
        out.C.leftCols<3>() = Eigen::MatrixXd(data.A) * S;
        out.D = Eigen::MatrixXd::Zero(n, n);
    }
    return {};
}

namespace {

/// True when the model is a mechanical second-order one, A = [0 I; A21 A22], B = [0; B2]
/// (linearize and linearizeCompliant build it so), exactly.
bool secondOrder(const StateSpace& system) {
    const Eigen::Index m = system.A.rows();
    if (m % 2 != 0 || system.A.cols() != m || system.B.rows() != m || system.C.cols() != m) return false;
    const Eigen::Index h = m / 2;
    return system.A.topLeftCorner(h, h).isZero(0.0) && system.A.topRightCorner(h, h).isIdentity(0.0) &&
           system.B.topRows(h).isZero(0.0);
}

}  // namespace

Eigen::MatrixXcd frequencyResponse(const StateSpace& system, double frequency) {
    const std::complex<double> s(0.0, 2.0 * std::numbers::pi * frequency);
    const Eigen::Index m = system.A.rows();
    if (secondOrder(system)) {
        // x1 = (s^2 I - s A22 - A21)^-1 B2, x2 = s x1: no cancellation as s -> 0. When y is the
        // acceleration (C = [A21 A22], D = B2), y = A21 x1 + A22 x2 + B2 = s^2 x1 exactly: the
        // form C X + D would subtract two terms of the size of D to leave one of s^2.
        using Complex = std::complex<double>;
        const Eigen::Index h = m / 2;
        const Eigen::MatrixXcd A21 = system.A.bottomLeftCorner(h, h).cast<Complex>();
        const Eigen::MatrixXcd A22 = system.A.bottomRightCorner(h, h).cast<Complex>();
        const Eigen::MatrixXcd P = s * s * Eigen::MatrixXcd::Identity(h, h) - s * A22 - A21;
        const Eigen::MatrixXcd x1 = P.fullPivLu().solve(system.B.bottomRows(h).cast<Complex>());
        const bool acceleration = system.C.rows() == h && system.C == system.A.bottomRows(h) && system.D.rows() == h &&
                                  system.D == system.B.bottomRows(h);
        if (acceleration) return s * s * x1;
        return system.C.leftCols(h).cast<Complex>() * x1 + system.C.rightCols(h).cast<Complex>() * (s * x1) +
               system.D.cast<Complex>();
    }
    const Eigen::MatrixXcd sI_A = s * Eigen::MatrixXcd::Identity(m, m) - system.A.cast<std::complex<double>>();
    const Eigen::MatrixXcd X = sI_A.partialPivLu().solve(system.B.cast<std::complex<double>>());
    return system.C.cast<std::complex<double>>() * X + system.D.cast<std::complex<double>>();
}

FrequencyResponse frequencyResponse(const StateSpace& system, const std::vector<double>& frequencies) {
    FrequencyResponse r;
    r.frequency = frequencies;
    r.outputs = static_cast<int>(system.C.rows());
    r.inputs = static_cast<int>(system.B.cols());
    const auto rows = static_cast<Eigen::Index>(frequencies.size());
    const auto channels = static_cast<Eigen::Index>(r.outputs) * r.inputs;
    r.magnitude_db.resize(rows, channels);
    r.phase_deg.resize(rows, channels);
    for (Eigen::Index k = 0; k < rows; ++k) {
        const double f = frequencies[static_cast<std::size_t>(k)];
        if (!(f > 0.0) || !std::isfinite(f) || (k > 0 && !(f > frequencies[static_cast<std::size_t>(k - 1)]))) {
            throw Error("frequency response: the frequencies must be positive and increasing (" +
                        text::format("%f", f) + " Hz)");
        }
        const Eigen::MatrixXcd H = frequencyResponse(system, f);
        for (int o = 0; o < r.outputs; ++o) {
            for (int i = 0; i < r.inputs; ++i) {
                const Eigen::Index c = o * r.inputs + i;
                const std::complex<double> h = H(o, i);
                r.magnitude_db(k, c) = 20.0 * std::log10(std::abs(h));
                double phase = std::arg(h) * 180.0 / std::numbers::pi;
                // unwrap: the first anchored, each next the nearest to the previous frequency's phase
                if (k == 0) phase = anchoredPhase(phase);
                if (k > 0) phase += 360.0 * std::round((r.phase_deg(k - 1, c) - phase) / 360.0);
                r.phase_deg(k, c) = phase;
            }
        }
    }
    return r;
}

double anchoredPhase(double phase_deg) {
    constexpr double kTie = 1e-6;
    return phase_deg <= -180.0 + kTie ? phase_deg + 360.0 : phase_deg;
}

double lowFrequencySlope(const FrequencyResponse& response, int o, int i) {
    const Eigen::Index c = o * response.inputs + i;
    if (response.magnitude_db.rows() < 2) return std::numeric_limits<double>::quiet_NaN();
    const double decades = std::log10(response.frequency[1] / response.frequency[0]);
    return (response.magnitude_db(1, c) - response.magnitude_db(0, c)) / (20.0 * decades);
}

double bandwidth3dB(const FrequencyResponse& response, int o, int i) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Eigen::Index c = o * response.inputs + i;
    const Eigen::Index rows = response.magnitude_db.rows();
    if (rows == 0) return nan;
    double k = 0.0;
    if (rows >= 2) {
        const double slope = lowFrequencySlope(response, o, i);
        k = std::round(slope);
        if (!(std::abs(slope - k) <= kSlopeTolerance)) return nan;
    }
    // the magnitude less the asymptote |H(f_1)| (f / f_1)^k, 0 dB at f_1
    const double f1 = response.frequency[0];
    const auto drop = [&](Eigen::Index r) {
        return response.magnitude_db(r, c) - response.magnitude_db(0, c) -
               20.0 * k * std::log10(response.frequency[static_cast<std::size_t>(r)] / f1);
    };
    for (Eigen::Index r = 1; r < rows; ++r) {
        const double m0 = drop(r - 1), m1 = drop(r);
        if (m1 < -3.0) {
            const double f0 = std::log(response.frequency[static_cast<std::size_t>(r - 1)]);
            const double fr = std::log(response.frequency[static_cast<std::size_t>(r)]);
            return std::exp(f0 + (fr - f0) * (m0 + 3.0) / (m0 - m1));
        }
    }
    return nan;
}

std::vector<double> logGrid(double f_min, double f_max, int count) {
    if (!(f_min > 0.0) || !(f_max > f_min) || !std::isfinite(f_max) || count < 2) {
        throw Error("frequency grid: expected 0 < f_min < f_max and at least 2 points");
    }
    std::vector<double> grid(static_cast<std::size_t>(count));
    const double a = std::log(f_min), b = std::log(f_max);
    for (int k = 0; k < count; ++k) grid[static_cast<std::size_t>(k)] = std::exp(a + (b - a) * k / (count - 1));
    return grid;
}

}  // namespace nocdyn
