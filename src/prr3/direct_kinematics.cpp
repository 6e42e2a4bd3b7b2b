// 3-PRR direct displacement: exact elimination to a polynomial in tan(theta/2), Newton
// polishing and verification; the Newton tracker used by forward dynamics (see the header).
#include "nocdyn/prr3/direct_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>
#include <unsupported/Eigen/Polynomials>

#include "nocdyn/error.hpp"
#include "nocdyn/prr3/kinematics.hpp"

namespace nocdyn::prr3 {

namespace {

constexpr double kPi = std::numbers::pi;

/// Polynomial in t, coefficients in ascending powers.
using Poly = std::vector<double>;

Poly operator*(const Poly& a, const Poly& b) {
    Poly out(a.size() + b.size() - 1, 0.0);
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t k = 0; k < b.size(); ++k) out[i + k] += a[i] * b[k];
    return out;
}

Poly operator+(const Poly& a, const Poly& b) {
    Poly out(std::max(a.size(), b.size()), 0.0);
    for (std::size_t i = 0; i < a.size(); ++i) out[i] += a[i];
    for (std::size_t i = 0; i < b.size(); ++i) out[i] += b[i];
    return out;
}

Poly operator-(const Poly& a, const Poly& b) {
    Poly out(std::max(a.size(), b.size()), 0.0);
    for (std::size_t i = 0; i < a.size(); ++i) out[i] += a[i];
    for (std::size_t i = 0; i < b.size(); ++i) out[i] -= b[i];
    return out;
}

Poly operator*(double s, Poly a) {
    for (double& c : a) c *= s;
    return a;
}

/// A_j for actuator displacement u_j: B_j + (s_ref_j + u_j) e_j.
Vector2 railPoint(const Model& model, int j, double u_j) { return model.B[j] + (model.s_ref[j] + u_j) * model.e[j]; }

Vector2 rotate(double theta, const Vector2& v) {
    const double c = std::cos(theta), s = std::sin(theta);
    return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

/// Real roots t of the degree-12 polynomial of the header (lengths scaled by 1/l), as theta.
std::vector<double> candidateAngles(const Model& model, const JointVector& u) {
    const double scale = 1.0 / model.l;
    // P~_j(t) = w P_j = A_j w - [v_x (1 - t^2) - v_y 2t ; v_y (1 - t^2) + v_x 2t]
    std::array<Poly, kLimbs> Px, Py;
    for (int j = 0; j < kLimbs; ++j) {
        const Vector2 a = scale * railPoint(model, j, u(j));
        const Vector2 v = scale * model.M_local[j];
        Px[j] = {a.x() - v.x(), 2.0 * v.y(), a.x() + v.x()};
        Py[j] = {a.y() - v.y(), -2.0 * v.x(), a.y() + v.y()};
    }
    const Poly w = {1.0, 0.0, 1.0};
    // Pairwise differences of the circles |C - P_j| = 1, times w^2:
    //   2 (P~_1 - P~_j) . (C w) = |P~_1|^2 - |P~_j|^2,  j = 2, 3   => G = C w = adj(K) b / Delta
    std::array<Poly, 2> Kx, Ky, b;
    for (int k = 0; k < 2; ++k) {
        const int j = k + 1;
        Kx[k] = 2.0 * (Px[0] - Px[j]);
        Ky[k] = 2.0 * (Py[0] - Py[j]);
        b[k] = (Px[0] * Px[0] + Py[0] * Py[0]) - (Px[j] * Px[j] + Py[j] * Py[j]);
    }
    const Poly delta = Kx[0] * Ky[1] - Ky[0] * Kx[1];
    const Poly Nx = Ky[1] * b[0] - Ky[0] * b[1];
    const Poly Ny = Kx[0] * b[1] - Kx[1] * b[0];
    // C = G / w = N / (Delta w); |C - P_1|^2 = 1  <=>  |N - Delta P~_1|^2 = Delta^2 w^2
    const Poly ex = Nx - delta * Px[0];
    const Poly ey = Ny - delta * Py[0];
    Poly f = (ex * ex + ey * ey) - (delta * delta) * (w * w);

    // Trim vanishing leading coefficients (a root at t = oo, i.e. theta = pi, is tried anyway).
    double largest = 0.0;
    for (double c : f) largest = std::max(largest, std::abs(c));
    std::vector<double> angles{kPi};
    if (largest == 0.0) return angles;  // degenerate: every theta; fall back to theta = pi only
    while (f.size() > 1 && std::abs(f.back()) <= 1e-14 * largest) f.pop_back();
    if (f.size() < 2) return angles;

    Eigen::VectorXd coefficients = Eigen::Map<const Eigen::VectorXd>(f.data(), static_cast<Eigen::Index>(f.size()));
    Eigen::PolynomialSolver<double, Eigen::Dynamic> solver;
    solver.compute(coefficients);
    for (const auto& root : solver.roots()) {
        // Generous: spurious candidates are rejected by Newton + verification below, and a
        // double root at a singular posture may split off the real axis by ~sqrt(eps).
        if (std::abs(root.imag()) <= 1e-3 * (1.0 + std::abs(root))) angles.push_back(2.0 * std::atan(root.real()));
    }
    return angles;
}

/// Closure residuals F_j = (|M_j - A_j|^2 - l^2) / (2 l) and their Jacobian in p.
void closures(const Model& model, const JointVector& u, const Pose& p, Vector3& F, Matrix3& J) {
    for (int j = 0; j < kLimbs; ++j) {
        const Vector2 rv = rotate(p(0), model.M_local[j]);
        const Vector2 m = p.tail<2>() + rv - railPoint(model, j, u(j));
        F(j) = (m.squaredNorm() - model.l * model.l) / (2.0 * model.l);
        J(j, 0) = m.dot(perp(rv)) / model.l;
        J.block<1, 2>(j, 1) = m.transpose() / model.l;
    }
}

/// Newton on the three closures from (theta, C). Returns false if it does not converge.
bool polish(const Model& model, const JointVector& u, Pose& p) {
    Vector3 F;
    Matrix3 J;
    for (int it = 0; it < 60; ++it) {
        closures(model, u, p, F, J);
        const Eigen::FullPivLU<Matrix3> lu(J);
        if (!lu.isInvertible()) return false;
        const Vector3 step = lu.solve(F);
        p -= step;
        if (!p.allFinite() || p.tail<2>().norm() > 10.0 * (model.R + model.l)) return false;
        if (step.cwiseAbs().maxCoeff() <= 1e-15 * (1.0 + model.R)) break;
    }
    closures(model, u, p, F, J);
    return F.cwiseAbs().maxCoeff() <= 1e-11 * model.l;
}

/// Centre C at a given theta: circumcentre of P_1 P_2 P_3 (same equations as the polynomial).
bool centreAt(const Model& model, const JointVector& u, double theta, Vector2& centre) {
    std::array<Vector2, kLimbs> P;
    for (int j = 0; j < kLimbs; ++j) P[j] = railPoint(model, j, u(j)) - rotate(theta, model.M_local[j]);
    Matrix2 K;
    Vector2 b;
    for (int k = 0; k < 2; ++k) {
        K.row(k) = 2.0 * (P[0] - P[k + 1]).transpose();
        b(k) = P[0].squaredNorm() - P[k + 1].squaredNorm();
    }
    const double det = K.determinant();
    if (std::abs(det) <= 1e-14 * K.squaredNorm()) return false;
    centre = K.inverse() * b;
    return true;
}

double wrapAngle(double theta) {
    theta = std::remainder(theta, 2.0 * kPi);  // [-pi, pi]
    return theta <= -kPi ? theta + 2.0 * kPi : theta;
}

}  // namespace

std::vector<AssemblyMode> directDisplacement(const Model& model, const JointVector& u,
                                             const DirectKinematicsOptions& options) {
    std::vector<AssemblyMode> modes;
    Data data;
    for (const double theta0 : candidateAngles(model, u)) {
        Vector2 centre;
        if (!centreAt(model, u, theta0, centre)) continue;
        Pose p(theta0, centre.x(), centre.y());
        if (!polish(model, u, p)) continue;
        p(0) = wrapAngle(p(0));

        AssemblyMode mode;
        mode.p = p;
        mode.working = true;
        for (int j = 0; j < kLimbs; ++j) {
            const Vector2 Mj = p.tail<2>() + rotate(p(0), model.M_local[j]);
            const Vector2 m = Mj - railPoint(model, j, u(j));
            mode.side[j] = model.n[j].dot(m) > 0.0 ? 1 : -1;
            mode.ahead[j] = model.e[j].dot(m) > 0.0 ? 1 : -1;
            mode.working = mode.working && mode.side[j] > 0 && mode.ahead[j] > 0;
            mode.closure_residual = std::max(mode.closure_residual, std::abs(m.norm() - model.l));
            // Inverse displacement on this limb's own branch: A_j is where the circle of
            // radius l about M_j meets L_j, behind M_j (ahead = +1) or in front of it.
            const double d = model.n[j].dot(Mj - model.B[j]);
            const double along = std::sqrt(std::max(0.0, model.l * model.l - d * d));
            const double u_j = model.e[j].dot(Mj - model.B[j]) - mode.ahead[j] * along - model.s_ref[j];
            mode.u_error = std::max(mode.u_error, std::abs(u_j - u(j)));
            mode.limb_condition = std::max(mode.limb_condition, model.l / std::abs(model.e[j].dot(m)));
        }
        if (options.working_branch_only && !mode.working) continue;
        // eq. 39 and the model notes' u_j: the library's own inverse displacement must agree.
        if (mode.working) {
            if (!inverseDisplacement(model, data, p)) continue;
            mode.u_error = (data.u - u).cwiseAbs().maxCoeff();
        }
        // u_j(p) amplifies rounding in p by up to l / |e_j . m_j| (a link normal to its rail).
        if (!(mode.u_error <= options.verify_tolerance * mode.limb_condition &&
              mode.closure_residual <= options.verify_tolerance)) {
            continue;
        }
        // Conditioning of H (eq. 7) at the solution, branch-independent form: rows [ (M_j - C) x f_j, f_j ].
        Matrix3 H;
        for (int j = 0; j < kLimbs; ++j) {
            const Vector2 a = rotate(p(0), model.M_local[j]);
            const Vector2 f = (p.tail<2>() + a - railPoint(model, j, u(j))) / model.l;
            H(j, 0) = cross(a, f) / model.r;
            H(j, 1) = f.x();
            H(j, 2) = f.y();
        }
        // 1-norm condition number, as kinematics.cpp computes cond_H
        const Eigen::FullPivLU<Matrix3> lu(H);
        mode.cond_H = lu.isInvertible()
                          ? H.cwiseAbs().colwise().sum().maxCoeff() * lu.inverse().cwiseAbs().colwise().sum().maxCoeff()
                          : std::numeric_limits<double>::infinity();

        const bool duplicate = std::any_of(modes.begin(), modes.end(), [&](const AssemblyMode& other) {
            return std::abs(wrapAngle(other.p(0) - p(0))) <= 1e-9 && (other.p.tail<2>() - p.tail<2>()).norm() <= 1e-9;
        });
        if (!duplicate) modes.push_back(mode);
    }
    std::sort(modes.begin(), modes.end(), [](const AssemblyMode& a, const AssemblyMode& b) { return a.p(0) < b.p(0); });
    return modes;
}

AssemblyModeCount countAssemblyModes(const Model& model, const JointVector& u) {
    const auto all = directDisplacement(model, u, {.working_branch_only = false});
    AssemblyModeCount count;
    count.all = static_cast<int>(all.size());
    count.working =
        static_cast<int>(std::count_if(all.begin(), all.end(), [](const AssemblyMode& m) { return m.working; }));
    return count;
}

namespace {

/// Why the tracker found no pose, from the position stage of its last iterate: a limb whose
/// link lies (nearly) normal to its rail, or along it, is at the edge of the workspace, where
/// u_j turns back and no pose has u_j further out; otherwise the assembly mode is lost.
Status notTracked(const Model& model, const Data& data, int worst, double residual) {
    constexpr double kEdge = 0.01;  // d_j^M within 1 % of l (link normal to rail) or of 0 (along it)
    int limb = -1;
    double margin = kEdge;
    for (int j = 0; j < kLimbs; ++j) {
        const double to_edge = std::min(1.0 - data.d_M(j) / model.l, data.d_M(j) / model.l);
        if (to_edge < margin) {
            margin = to_edge;
            limb = j;
        }
    }
    if (limb >= 0) return {StatusCode::workspace_edge, limb, data.d_M(limb)};
    return {StatusCode::assembly_mode_lost, worst, residual};
}

}  // namespace

Status trackPose(const Model& model, Data& data, const JointVector& u, Pose& p, const TrackerOptions& options) {
    double residual = std::numeric_limits<double>::infinity();
    int worst = -1;
    for (int it = 0; it <= options.max_iterations; ++it) {
        // A Newton iterate out of reach or singular: report that (limb and value), not a lost mode.
        if (const Status status = inverseDisplacement(model, data, p); !status) return status;
        const JointVector r = u - data.u;
        residual = r.cwiseAbs().maxCoeff(&worst);
        if (residual <= options.tolerance) return {};
        if (it == options.max_iterations) break;
        // eq. 5 as a Newton step: dp = H^{-1} D du
        if (const Status status = velocityFromActuatorRates(model, data, r); !status) return status;
        if (!(data.t_M.cwiseAbs().maxCoeff() <= options.max_step)) return notTracked(model, data, worst, residual);
        p += data.t_M;
    }
    return notTracked(model, data, worst, residual);
}

}  // namespace nocdyn::prr3
