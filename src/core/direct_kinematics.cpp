// Direct kinematics of the general model: constraints of the locked limbs (locked_limbs.hpp),
// elimination to a polynomial in tan(phi / 2), polishing, verification by inverse displacement
// on each limb's branch (see the header; the tracker is in tracker.cpp).
#include "nocdyn/direct_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <unsupported/Eigen/Polynomials>

#include "nocdyn/kinematics.hpp"
#include "nocdyn/limb_ik.hpp"
#include "locked_limbs.hpp"
#include "stages.hpp"

namespace nocdyn {

namespace {

using namespace detail::locked;

/// Polynomial in t, ascending powers, degree <= 10.
struct Poly {
    static constexpr int kCapacity = 11;
    std::array<double, kCapacity> c{};
    int size = 0;

    [[nodiscard]] double maxAbs() const {
        double m = 0.0;
        for (int i = 0; i < size; ++i) m = std::max(m, std::abs(c[static_cast<std::size_t>(i)]));
        return m;
    }
};

/// w (k + c cos + s sin), w = 1 + t^2: cos = (1 - t^2) / w, sin = 2 t / w.
Poly fromTrig(const Trig& f) { return {{f.k + f.c, 2.0 * f.s, f.k - f.c}, 3}; }

Poly operator*(const Poly& a, const Poly& b) {
    Poly out;
    out.size = std::min(a.size + b.size - 1, Poly::kCapacity);
    for (std::size_t i = 0; i < static_cast<std::size_t>(a.size); ++i) {
        for (std::size_t k = 0; k < static_cast<std::size_t>(b.size) && i + k < out.c.size(); ++k) {
            out.c[i + k] += a.c[i] * b.c[k];
        }
    }
    return out;
}

Poly combine(const Poly& a, double sb, const Poly& b) {
    Poly out;
    out.size = std::max(a.size, b.size);
    for (int i = 0; i < a.size; ++i) out.c[static_cast<std::size_t>(i)] += a.c[static_cast<std::size_t>(i)];
    for (int i = 0; i < b.size; ++i) out.c[static_cast<std::size_t>(i)] += sb * b.c[static_cast<std::size_t>(i)];
    return out;
}

Poly operator+(const Poly& a, const Poly& b) { return combine(a, 1.0, b); }
Poly operator-(const Poly& a, const Poly& b) { return combine(a, -1.0, b); }

/// Candidate angles phi: at most kCapacity roots plus pi.
struct Angles {
    std::array<double, Poly::kCapacity + 1> phi{};
    int count = 0;
    void add(double a) {
        if (count < static_cast<int>(phi.size())) phi[static_cast<std::size_t>(count++)] = a;
    }
};

/// Divides out the factors w = 1 + t^2 (roots +-i, which the circles bring) while the
/// remainder is round-off: fewer eigenvalues to compute, none of them spurious.
void deflateImaginaryUnit(Poly& f) {
    while (f.size > 3) {
        const double scale = f.maxAbs();
        // f = (t^2 + 1) q + r, synthetic division from the top
        Poly q;
        q.size = f.size - 2;
        std::array<double, Poly::kCapacity> rem = f.c;
        for (int i = f.size - 1; i >= 2; --i) {
            const double qi = rem[static_cast<std::size_t>(i)];
            q.c[static_cast<std::size_t>(i - 2)] = qi;
            rem[static_cast<std::size_t>(i)] = 0.0;
            rem[static_cast<std::size_t>(i - 2)] -= qi;
        }
        if (std::abs(rem[0]) + std::abs(rem[1]) > 1e-12 * scale) return;
        f = q;
    }
}

/// The companion matrix of f: one storage type for every degree (fixed capacity, no
/// allocation), so that a single eigenvalue solver serves them all.
using Companion = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, Poly::kCapacity - 1, Poly::kCapacity - 1>;

/// Eigen's companion matrix of f (degree Deg >= 2), balanced (Parlett and Reinsch), as
/// PolynomialSolver builds it; only this small step depends on the degree.
template <int Deg>
void balancedCompanion(const Poly& f, Companion& out) {
    Eigen::Matrix<double, Deg + 1, 1> coefficients;
    for (int i = 0; i <= Deg; ++i) coefficients(i) = f.c[static_cast<std::size_t>(i)];
    Eigen::internal::companion<double, Deg> companion(coefficients);
    companion.balance();
    out = companion.denseMatrix();
}

template <int... Degs>
void companionDispatch(const Poly& f, Companion& out, std::integer_sequence<int, Degs...> /*unused*/) {
    const int degree = f.size - 1;
    ((degree == Degs + 2 ? balancedCompanion<Degs + 2>(f, out) : void()), ...);
}

/// Real roots t of f (degree >= 1), as angles phi = 2 atan t: the eigenvalues of the balanced
/// companion matrix (what PolynomialSolver computes, with one solver for every degree).
void realRootsOfPolynomial(const Poly& f, Angles& out) {
    const auto add = [&out](std::complex<double> z) {
        // generous: a double root splits off the real axis by ~sqrt(eps); Newton and the
        // verification reject the spurious candidates
        if (std::abs(z.imag()) <= 1e-4 * (1.0 + std::abs(z))) out.add(2.0 * std::atan(z.real()));
    };
    if (f.size == 2) {
        add(-f.c[0] / f.c[1]);
        return;
    }
    Companion companion;
    companionDispatch(f, companion, std::make_integer_sequence<int, Poly::kCapacity - 2>{});
    Eigen::EigenSolver<Companion> solver;
    solver.compute(companion, /*computeEigenvectors=*/false);
    for (Eigen::Index i = 0; i < solver.eigenvalues().size(); ++i) add(solver.eigenvalues()(i));
}

/// Real roots of f as angles phi = 2 atan t (leading coefficients that are round-off are
/// dropped: their roots are near t = oo, i.e. phi = pi, which is tried anyway).
void realRoots(Poly f, Angles& out) {
    const double scale = f.maxAbs();
    while (f.size > 1 && std::abs(f.c[static_cast<std::size_t>(f.size - 1)]) <= 1e-13 * scale) --f.size;
    deflateImaginaryUnit(f);
    if (f.size < 2) return;
    realRootsOfPolynomial(f, out);
}

/// Linear equation (times w) a~ . C + b~ = 0 in polynomial form.
struct LinearPoly {
    Poly ax, ay, b;
};

LinearPoly linearPoly(const Equation& e) { return {fromTrig(e.ax), fromTrig(e.ay), fromTrig(e.b)}; }

/// Eliminates C from L1, L2 (linear) and E (circle or linear): C = N / Delta by Cramer's rule,
/// substituted into E times Delta^2 (or Delta when E is linear). Returns false when Delta or
/// the result vanishes identically (a dependent choice of equations).
bool eliminate(const Equation& e1, const Equation& e2, const Equation& e3, Angles& out) {
    const LinearPoly l1 = linearPoly(e1), l2 = linearPoly(e2), l3 = linearPoly(e3);
    const Poly delta = l1.ax * l2.ay - l1.ay * l2.ax;
    const double delta_scale = (l1.ax * l2.ay).maxAbs() + (l1.ay * l2.ax).maxAbs();
    if (!(delta.maxAbs() > 1e-10 * delta_scale)) return false;
    const Poly Nx = l1.ay * l2.b - l1.b * l2.ay;
    const Poly Ny = l1.b * l2.ax - l1.ax * l2.b;
    Poly f;
    double scale = 0.0;
    const Poly linear = l3.ax * Nx + l3.ay * Ny;
    if (e3.kappa != 0.0) {
        const Poly w{{1.0, 0.0, 1.0}, 3};
        const Poly quadratic = w * (Nx * Nx + Ny * Ny);
        const Poly first = delta * linear, last = (delta * delta) * l3.b;
        f = quadratic + first + last;
        scale = std::max({quadratic.maxAbs(), first.maxAbs(), last.maxAbs()});
    } else {
        const Poly last = delta * l3.b;
        f = linear + last;
        scale = std::max(linear.maxAbs(), last.maxAbs());
    }
    if (!(f.maxAbs() > 1e-10 * scale)) return false;
    realRoots(f, out);
    return true;
}

/// Candidate angles when no equation fixes the orientation: the first choice of three
/// equations whose elimination does not vanish identically (the circles of a choice enter as
/// differences from one of them, which is kept as the third equation).
bool eliminationAngles(const Equations& eqs, Angles& out) {
    const int m = eqs.count;
    const auto& e = eqs.eq;
    for (int i = 0; i < m; ++i) {
        for (int j = i + 1; j < m; ++j) {
            for (int k = j + 1; k < m; ++k) {
                const std::array<int, 3> idx{i, j, k};
                // each member of the triple in turn as the third equation
                for (int r = 0; r < 3; ++r) {
                    const Equation& third = e[static_cast<std::size_t>(idx[static_cast<std::size_t>(r)])];
                    const Equation& first = e[static_cast<std::size_t>(idx[static_cast<std::size_t>((r + 1) % 3)])];
                    const Equation& second = e[static_cast<std::size_t>(idx[static_cast<std::size_t>((r + 2) % 3)])];
                    if (third.kappa == 0.0 && (first.kappa != 0.0 || second.kappa != 0.0)) continue;
                    const Equation l1 = first.kappa != 0.0 ? first - third : first;
                    const Equation l2 = second.kappa != 0.0 ? second - third : second;
                    if (eliminate(l1, l2, third, out)) return true;
                }
            }
        }
    }
    return false;
}

/// Up to two centres C at a fixed phi: the best-conditioned pair of linear equations (circles
/// as differences from the first), else a line meeting the first circle.
struct Centres {
    std::array<Vector2, 2> C{};
    int count = 0;
};

Centres centresAt(const Equations& eqs, double phi) {
    const double cs = std::cos(phi), sn = std::sin(phi);
    std::array<Vector2, kMaxActuators> a{};
    std::array<double, kMaxActuators> b{};
    int lines = 0;
    int first_circle = -1;
    for (int i = 0; i < eqs.count; ++i) {
        const Equation& e = eqs.eq[static_cast<std::size_t>(i)];
        if (e.orientation) continue;
        Equation lin = e;
        if (e.kappa != 0.0) {
            if (first_circle < 0) {
                first_circle = i;
                continue;
            }
            lin = e - eqs.eq[static_cast<std::size_t>(first_circle)];
        }
        a[static_cast<std::size_t>(lines)] = Vector2(lin.ax.at(cs, sn), lin.ay.at(cs, sn));
        b[static_cast<std::size_t>(lines++)] = lin.b.at(cs, sn);
    }
    Centres out;
    double best = 0.0;
    int bi = -1, bj = -1;
    for (int i = 0; i < lines; ++i) {
        for (int j = i + 1; j < lines; ++j) {
            const auto ii = static_cast<std::size_t>(i), jj = static_cast<std::size_t>(j);
            const double norms = a[ii].norm() * a[jj].norm();
            const double sine = norms > 0.0 ? std::abs(cross(a[ii], a[jj])) / norms : 0.0;
            if (sine > best) {
                best = sine;
                bi = i;
                bj = j;
            }
        }
    }
    if (best > 1e-8) {
        const auto ii = static_cast<std::size_t>(bi), jj = static_cast<std::size_t>(bj);
        const double det = cross(a[ii], a[jj]);
        // a_i . C = -b_i, a_j . C = -b_j
        out.C[0] = Vector2(-b[ii] * a[jj].y() + b[jj] * a[ii].y(), -a[ii].x() * b[jj] + a[jj].x() * b[ii]) / det;
        out.count = 1;
        return out;
    }
    if (first_circle < 0) return out;
    // the longest line normal meets the circle |C|^2 + a0 . C + b0 = 0: C = C0 + tau e
    int li = -1;
    double longest = 0.0;
    for (int i = 0; i < lines; ++i) {
        if (a[static_cast<std::size_t>(i)].norm() > longest) {
            longest = a[static_cast<std::size_t>(i)].norm();
            li = i;
        }
    }
    if (li < 0 || !(longest > 1e-12)) return out;
    const Equation& c0 = eqs.eq[static_cast<std::size_t>(first_circle)];
    const Vector2 a0(c0.ax.at(cs, sn), c0.ay.at(cs, sn));
    const double b0 = c0.b.at(cs, sn);
    const Vector2& n = a[static_cast<std::size_t>(li)];
    const Vector2 C0 = -b[static_cast<std::size_t>(li)] / n.squaredNorm() * n;
    const Vector2 e = perp(n) / n.norm();
    const double half_p = C0.dot(e) + 0.5 * a0.dot(e);
    const double q = C0.squaredNorm() + a0.dot(C0) + b0;
    const double disc = half_p * half_p - q;
    // a slightly negative discriminant (a tangency in round-off) still gives a candidate
    if (disc < -1e-8 * (1.0 + half_p * half_p + std::abs(q))) return out;
    const double root = std::sqrt(std::max(disc, 0.0));
    out.C[0] = C0 + (-half_p + root) * e;
    out.C[1] = C0 + (-half_p - root) * e;
    out.count = root > 0.0 ? 2 : 1;
    return out;
}

/// Outcome of Gauss-Newton on the equations.
struct NewtonResult {
    double residual = std::numeric_limits<double>::infinity();  ///< final max |F_i|
    int iterations = 0;
    bool step_too_large = false;  ///< a step beyond max_step (phi [rad], C over L)
    bool singular = false;        ///< rank-deficient Jacobian
};

/// Gauss-Newton on every equation from z = (phi, C), until the step is round-off.
NewtonResult newton(const Equations& eqs, Vector3& z, int max_iterations, double max_step) {
    using Jacobian = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, kMaxActuators, 3>;
    using Residual = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxActuators, 1>;
    Jacobian J(eqs.count, 3);
    Residual F(eqs.count);
    const auto evaluate = [&] {
        const double cs = std::cos(z(0)), sn = std::sin(z(0));
        const double x = z(1), y = z(2);
        for (int i = 0; i < eqs.count; ++i) {
            const Equation& e = eqs.eq[static_cast<std::size_t>(i)];
            if (e.orientation) {
                F(i) = wrapAngle(z(0) - e.phi0);
                J.row(i) << 1.0, 0.0, 0.0;
                continue;
            }
            F(i) = e.kappa * (x * x + y * y) + e.ax.at(cs, sn) * x + e.ay.at(cs, sn) * y + e.b.at(cs, sn);
            J(i, 0) = e.ax.derivative(cs, sn) * x + e.ay.derivative(cs, sn) * y + e.b.derivative(cs, sn);
            J(i, 1) = 2.0 * e.kappa * x + e.ax.at(cs, sn);
            J(i, 2) = 2.0 * e.kappa * y + e.ay.at(cs, sn);
        }
        return F.cwiseAbs().maxCoeff();
    };
    NewtonResult out;
    out.residual = evaluate();
    // the equations are O(1) (lengths over L): a residual at round-off needs no further step
    constexpr double kRoundOff = 1e-15;
    for (; out.iterations < max_iterations && out.residual > kRoundOff && std::isfinite(out.residual);
         ++out.iterations) {
        Vector3 step;
        if (eqs.count == 3) {
            // 3 x 3 by cofactors (a singular J gives a non-finite step: the mode is lost)
            step = J.topRows<3>().inverse() * F.head<3>();
        } else {
            // normal equations of the least-squares step (J^T J is 3 x 3, symmetric positive
            // definite unless J loses rank: its determinant against the cube of its scale,
            // then the inverse by cofactors)
            const Matrix3 JtJ = J.transpose() * J;
            const double scale = JtJ.norm();
            if (!(JtJ.determinant() > 1e-14 * scale * scale * scale)) {
                out.singular = true;
                break;
            }
            step = JtJ.inverse() * (J.transpose() * F);
        }
        if (!(step.cwiseAbs().maxCoeff() <= max_step)) {
            out.step_too_large = true;
            break;
        }
        z -= step;
        out.residual = evaluate();
        if (!(step.cwiseAbs().maxCoeff() > 1e-15 * (1.0 + z.cwiseAbs().maxCoeff()))) {
            ++out.iterations;
            break;
        }
    }
    if (!std::isfinite(out.residual)) out.residual = std::numeric_limits<double>::infinity();
    return out;
}

/// |u_a(p) - u_a| over the actuators of one limb solved on `branch`, scaled by the joint
/// scales; infinity when the limb does not reach p on that branch.
double limbActuatorError(const LimbModel& limb, int j, int branch, const PlatformDisplacement& G,
                         const ActuatorVector& u, LimbData& ld) {
    if (!solveLimb(limb, j, branch, G, false, ld)) return std::numeric_limits<double>::infinity();
    double err = 0.0;
    for (int k = 0; k < 3; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        const int a = limb.actuator[kk];
        if (a < 0) continue;
        double d = ld.q(k) - u(a);
        if (limb.type[kk] == JointType::revolute) d = wrapAngle(d);
        err = std::max(err, std::abs(d) * limb.inv_joint_scale[kk]);
    }
    return err;
}

/// max_a |u_a(p) - u_a| of the position stage, R joints modulo 2 pi (raw units).
double actuatorError(const Model& model, const Data& data, const ActuatorVector& u) {
    double err = 0.0;
    for (int a = 0; a < model.actuators; ++a) {
        const auto aa = static_cast<std::size_t>(a);
        const LimbModel& limb = model.limb[static_cast<std::size_t>(model.actuator_limb[aa])];
        double d = data.u(a) - u(a);
        if (limb.type[static_cast<std::size_t>(model.actuator_joint[aa])] == JointType::revolute) d = wrapAngle(d);
        err = std::max(err, std::abs(d));
    }
    return err;
}

/// Verifies a polished candidate pose: each limb's branch from its own actuator values (the
/// home branch when both fit, e.g. for a limb without actuators), then inverse displacement
/// on those branches. Returns false when no branch of some limb fits.
bool verify(const Model& model, Data& data, const ActuatorVector& u, const Pose& p, double tolerance,
            AssemblyMode& mode) {
    PlatformDisplacement G;
    G.dtheta = p(0) - model.home(0);
    G.cos_dtheta = std::cos(G.dtheta);
    G.sin_dtheta = std::sin(G.dtheta);
    G.C = p.tail<2>();
    LimbData ld;
    mode.working = true;
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        int branch = limb.branch;
        const double home_error = limbActuatorError(limb, j, branch, G, u, ld);
        if (limb.branch != 0 && !(home_error <= tolerance)) {
            const double other_error = limbActuatorError(limb, j, -branch, G, u, ld);
            if (other_error < home_error) branch = -branch;
        }
        mode.branch[static_cast<std::size_t>(j)] = branch;
        mode.working = mode.working && branch == limb.branch;
    }
    mode.p = Pose(wrapAngle(p(0)), p(1), p(2));
    if (!inverseDisplacement(model, data, mode.p, mode.branch)) return false;
    mode.u_error = actuatorError(model, data, u);
    if (!(mode.u_error <= tolerance)) return false;
    const Status status = velocityFromPlatformTwist(model, data, Twist::Zero());
    mode.condition = data.cond_A;
    for (int j = 0; j < model.limbs; ++j)
        mode.condition = std::max(mode.condition, data.limb[static_cast<std::size_t>(j)].cond);
    if (!status) mode.condition = status.value;
    return true;
}

bool sameMode(const AssemblyMode& a, const AssemblyMode& b, double length_scale) {
    return a.branch == b.branch && std::abs(wrapAngle(a.p(0) - b.p(0))) <= 1e-8 &&
           (a.p.tail<2>() - b.p.tail<2>()).cwiseAbs().maxCoeff() <= 1e-8 * length_scale;
}

}  // namespace

Status directKinematics(const Model& model, Data& data, const ActuatorVector& u, AssemblyModes& modes,
                        const DirectKinematicsOptions& options) {
    modes.count = 0;
    modes.degenerate = false;
    modes.truncated = false;
    for (int a = 0; a < model.actuators; ++a) {
        if (!std::isfinite(u(a)))
            return {StatusCode::not_finite, model.actuator_limb[static_cast<std::size_t>(a)], u(a)};
    }
    Equations eqs;
    lockedLimbEquations(model, u, eqs);

    Angles angles;
    const auto orient =
        std::find_if(eqs.eq.begin(), eqs.eq.begin() + eqs.count, [](const Equation& e) { return e.orientation; });
    if (orient != eqs.eq.begin() + eqs.count) {
        angles.add(orient->phi0);
    } else {
        angles.add(kPi);
        modes.degenerate = !eliminationAngles(eqs, angles);
    }

    const double L = model.length_scale;
    for (int i = 0; i < angles.count; ++i) {
        const double phi = angles.phi[static_cast<std::size_t>(i)];
        const Centres centres = centresAt(eqs, phi);
        for (int c = 0; c < centres.count; ++c) {
            Vector3 z(phi, centres.C[static_cast<std::size_t>(c)].x(), centres.C[static_cast<std::size_t>(c)].y());
            // three equations hold exactly at a mode; more (redundant actuation) may be
            // inconsistent, and the verification against `tolerance` decides
            const double residual = newton(eqs, z, 30, std::numeric_limits<double>::infinity()).residual;
            if (!(eqs.count == 3 ? residual <= 1e-8 : std::isfinite(residual))) continue;
            const Pose p(model.home(0) + z(0), L * z(1), L * z(2));
            AssemblyMode mode;
            if (!verify(model, data, u, p, options.tolerance, mode)) continue;
            const bool duplicate = std::any_of(modes.begin(), modes.end(),
                                               [&](const AssemblyMode& other) { return sameMode(other, mode, L); });
            if (duplicate) continue;
            if (modes.count == kMaxAssemblyModes) {
                modes.truncated = true;
                continue;
            }
            modes.mode[static_cast<std::size_t>(modes.count++)] = mode;
        }
    }
    if (model.task_dimension == 2) {
        // every mode at theta = home(0): by x, then y
        std::sort(modes.mode.begin(), modes.mode.begin() + modes.count,
                  [](const AssemblyMode& a, const AssemblyMode& b) {
                      return a.p(1) < b.p(1) || (a.p(1) == b.p(1) && a.p(2) < b.p(2));
                  });
    } else {
        std::sort(modes.mode.begin(), modes.mode.begin() + modes.count,
                  [](const AssemblyMode& a, const AssemblyMode& b) { return a.p(0) < b.p(0); });
    }
    return {};
}

Status stateFromActuators(const Model& model, Data& data, const ActuatorVector& u, const ActuatorVector& du, int choice,
                          ActuatorStart& start) {
    start = ActuatorStart{};
    AssemblyModes modes;
    if (const Status status = directKinematics(model, data, u, modes); !status) return status;
    start.modes = modes.count;
    const AssemblyMode* chosen = nullptr;
    double nearest = std::numeric_limits<double>::infinity();
    for (const AssemblyMode& mode : modes) {
        if (!mode.working) continue;
        ++start.working;
        if (choice > 0) {
            if (start.working == choice) chosen = &mode;
            continue;
        }
        const Pose d = mode.p - model.home;
        const double distance = std::max(std::abs(std::remainder(d(0), 2.0 * std::numbers::pi)),
                                         d.tail<2>().cwiseAbs().maxCoeff() / model.length_scale);
        if (distance < nearest) {
            nearest = distance;
            chosen = &mode;
            start.mode = start.working;
        }
    }
    if (chosen == nullptr) return {StatusCode::assembly_mode_missing, -1, static_cast<double>(start.working)};
    if (choice > 0) start.mode = choice;
    start.nearest_home = choice == 0;
    start.p = chosen->p;
    if (const Status status = inverseDisplacement(model, data, start.p); !status) return status;
    if (du.size() == 0) return velocityFromPlatformTwist(model, data, start.dp);
    return velocityFromActuatorRatesLeastSquares(model, data, du, start.dp);
}

}  // namespace nocdyn
