// Exact derivatives of the inverse and forward dynamics by forward-mode automatic
// differentiation (derivatives.hpp): the NOC after the position stage, written once on a
// scalar T (a double or a dual number), seeded with the exact position-level derivatives.
#include "nocdyn/derivatives.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <string>
#include <vector>

#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/parallel.hpp"
#include <Eigen/LU>

#include "stages.hpp"

namespace nocdyn {

namespace {

/// A dual number: a value and its derivatives along N input directions.
template <int N>
struct Dual {
    double v = 0.0;
    Eigen::Array<double, N, 1> d = Eigen::Array<double, N, 1>::Zero();
};

template <int N>
Dual<N> operator+(const Dual<N>& a, const Dual<N>& b) {
    return {a.v + b.v, a.d + b.d};
}
template <int N>
Dual<N> operator-(const Dual<N>& a, const Dual<N>& b) {
    return {a.v - b.v, a.d - b.d};
}
template <int N>
Dual<N> operator-(const Dual<N>& a) {
    return {-a.v, -a.d};
}
template <int N>
Dual<N> operator*(const Dual<N>& a, const Dual<N>& b) {
    return {a.v * b.v, a.d * b.v + b.d * a.v};
}
template <int N>
Dual<N> operator*(double k, const Dual<N>& a) {
    return {k * a.v, k * a.d};
}
template <int N>
Dual<N> operator*(const Dual<N>& a, double k) {
    return {k * a.v, k * a.d};
}
template <int N>
Dual<N> operator+(const Dual<N>& a, double k) {
    return {a.v + k, a.d};
}
template <int N>
Dual<N> operator-(const Dual<N>& a, double k) {
    return {a.v - k, a.d};
}
template <int N>
Dual<N> operator/(const Dual<N>& a, const Dual<N>& b) {
    const double inv = 1.0 / b.v;
    const double q = a.v * inv;
    return {q, (a.d - q * b.d) * inv};
}
template <int N>
double value(const Dual<N>& a) {
    return a.v;
}

template <class T>
T constant(double v) {
    return T{v};
}

/// A planar vector and a planar twist or wrench [w; x; y] on T.
template <class T>
struct P2 {
    T x, y;
};
template <class T>
struct S3 {
    T w, x, y;
};

template <class T>
S3<T> operator+(const S3<T>& a, const S3<T>& b) {
    return {a.w + b.w, a.x + b.x, a.y + b.y};
}
template <class T>
S3<T> operator-(const S3<T>& a, const S3<T>& b) {
    return {a.w - b.w, a.x - b.x, a.y - b.y};
}
template <class T>
S3<T> scale(const S3<T>& a, const T& k) {
    return {a.w * k, a.x * k, a.y * k};
}
template <class T>
T dot(const S3<T>& a, const S3<T>& b) {
    return a.w * b.w + a.x * b.x + a.y * b.y;
}
template <class T>
S3<T> cross3(const S3<T>& a, const S3<T>& b) {
    return {a.x * b.y - a.y * b.x, a.y * b.w - a.w * b.y, a.w * b.x - a.x * b.w};
}
/// Lie bracket of planar twists referred to O (kinematics.hpp).
template <class T>
S3<T> bracket(const S3<T>& a, const S3<T>& b) {
    return {a.w * 0.0, b.w * a.y - a.w * b.y, a.w * b.x - b.w * a.x};
}

/// The rows of a 3 x 3 inverse: of J = [a b c] (columns), J^-1 has rows (b x c, c x a, a x b) / det.
template <class T>
std::array<S3<T>, 3> inverseRowsOfColumns(const S3<T>& a, const S3<T>& b, const S3<T>& c) {
    const S3<T> r0 = cross3(b, c), r1 = cross3(c, a), r2 = cross3(a, b);
    const T inv = constant<T>(1.0) / dot(a, r0);
    return {scale(r0, inv), scale(r1, inv), scale(r2, inv)};
}

/// The position-level inputs of one limb: joint screws s_k and body c.o.m.s x_b.
template <class T>
struct LimbIn {
    std::array<S3<T>, 3> s;
    std::array<P2<T>, 2> x;
};

/// Everything position-level, with the pose rates and accelerations.
template <class T>
struct SampleIn {
    std::array<LimbIn<T>, kMaxLimbs> limb;
    P2<T> c, x_P;
    S3<T> dp, ddp;
};

/// The wrench referred to O of a body of inertia M with twist xi and its rate dxi (both
/// referred to O), c.o.m. at x: w = [I dw + x x f; f], f = m (a - g), a the c.o.m.'s
/// acceleration d/dt (v_O + w E x) = dv_O + dw E x + w E dx.
template <class T>
S3<T> bodyWrench(const InertiaDyad& M, const Vector2& g, const S3<T>& xi, const S3<T>& dxi, const P2<T>& x) {
    const P2<T> xd{xi.x - xi.w * x.y, xi.y + xi.w * x.x};
    const T ax = dxi.x - dxi.w * x.y - xi.w * xd.y;
    const T ay = dxi.y + dxi.w * x.x + xi.w * xd.x;
    const T fx = M.mass * (ax - g.x());
    const T fy = M.mass * (ay - g.y());
    return {M.inertia * dxi.w + x.x * fy - x.y * fx, fx, fy};
}

/// xi_P = S(c) dp and its rate S(c) ddp + dS/dt dp.
template <class T>
void platformTwists(const SampleIn<T>& in, S3<T>& xi_P, S3<T>& xi_P_dot) {
    const S3<T>& dp = in.dp;
    const S3<T>& ddp = in.ddp;
    xi_P = {dp.w, dp.x + dp.w * in.c.y, dp.y - dp.w * in.c.x};
    xi_P_dot = {ddp.w, ddp.x + ddp.w * in.c.y + dp.w * dp.y, ddp.y - ddp.w * in.c.x - dp.w * dp.x};
}

/// One limb's velocity and acceleration stages: the rows of J_j^-1, the joint rates and
/// accelerations, the body twists xi_0, xi_1 and the screw rate ds_1 = [xi_0, s_1].
template <class T>
struct LimbRates {
    std::array<S3<T>, 3> Ji;
    S3<T> gd, gdd, xi0, xi1, sd1;
};

/// eq. 3: gamma_dot = J_j^-1 xi_P, and its rate J_j^-1 (dxi_P - dJ_j gamma_dot).
template <class T>
LimbRates<T> limbRates(const LimbIn<T>& li, const S3<T>& xi_P, const S3<T>& xi_P_dot) {
    const auto& s = li.s;
    LimbRates<T> r;
    r.Ji = inverseRowsOfColumns(s[0], s[1], s[2]);
    r.gd = {dot(r.Ji[0], xi_P), dot(r.Ji[1], xi_P), dot(r.Ji[2], xi_P)};
    r.xi0 = scale(s[0], r.gd.w);
    r.xi1 = r.xi0 + scale(s[1], r.gd.x);
    r.sd1 = bracket(r.xi0, s[1]);
    const S3<T> sd2 = bracket(r.xi1, s[2]);
    const S3<T> rhs = xi_P_dot - scale(r.sd1, r.gd.x) - scale(sd2, r.gd.y);
    r.gdd = {dot(r.Ji[0], rhs), dot(r.Ji[1], rhs), dot(r.Ji[2], rhs)};
    return r;
}

/// The platform wrench W_P referred to O that the limbs supply (the generalized force in the
/// xi_P coordinates), and the rows of A (du = A xi_P).
template <class T>
void platformWrench(const Model& model, const SampleIn<T>& in, S3<T>& W, std::array<S3<T>, kMaxActuators>& A) {
    S3<T> xi_P, xi_P_dot;
    platformTwists(in, xi_P, xi_P_dot);
    W = bodyWrench(model.platform_M, model.gravity, xi_P, xi_P_dot, in.x_P);
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbIn<T>& li = in.limb[static_cast<std::size_t>(j)];
        const auto& s = li.s;
        const LimbRates<T> r = limbRates(li, xi_P, xi_P_dot);
        const auto& Ji = r.Ji;
        const S3<T>& gd = r.gd;
        const S3<T>& gdd = r.gdd;
        const S3<T> dxi0 = scale(s[0], gdd.w);
        const S3<T> dxi1 = dxi0 + scale(s[1], gdd.x) + scale(r.sd1, gd.x);
        const S3<T> w0 = bodyWrench(limb.M[0], model.gravity, r.xi0, dxi0, li.x[0]);
        const S3<T> w1 = bodyWrench(limb.M[1], model.gravity, r.xi1, dxi1, li.x[1]);
        // the joint-space force U_j^T w + phi_j: body 1 moves with joint 1, body 2 with joints 1 and 2
        S3<T> y{dot(s[0], w0 + w1), dot(s[1], w1), w0.w * 0.0};
        if (!limb.frictionless) {
            // phi_k = damping q'_k + friction sign q'_k, the sign frozen (derivatives.hpp)
            const std::array<const T*, 3> rate{&gd.w, &gd.x, &gd.y};
            std::array<T*, 3> force{&y.w, &y.x, &y.y};
            for (std::size_t k = 0; k < 3; ++k) {
                const double v = value(*rate[k]);
                const double sign = v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0);
                *force[k] = *force[k] + limb.damping[k] * *rate[k] + limb.friction[k] * sign;
            }
        }
        // W_P += J_j^-T y
        W = W + scale(Ji[0], y.w) + scale(Ji[1], y.x) + scale(Ji[2], y.y);
        for (int k = 0; k < 3; ++k) {
            if (const int a = limb.actuator[static_cast<std::size_t>(k)]; a >= 0)
                A[static_cast<std::size_t>(a)] = Ji[static_cast<std::size_t>(k)];
        }
    }
}

/// tau from the force rows of a two-DOF robot (motion: translation): A_t^T tau = W_t with
/// A_t = A E and W_t = E^T W, E = [0 0; 1 0; 0 1] (the x, y rows); A_t^-T W_t with two
/// actuators, else the minimum-norm A_t (A_t^T A_t)^-1 W_t.
template <class T>
void distributeTask(int n, const std::array<S3<T>, kMaxActuators>& A, const S3<T>& W,
                    std::array<T, kMaxActuators>& tau) {
    if (n == 2) {
        // [r_0 r_1] tau = W_t by Cramer's rule
        const S3<T>& r0 = A[0];
        const S3<T>& r1 = A[1];
        const T det = r0.x * r1.y - r1.x * r0.y;
        tau[0] = (W.x * r1.y - r1.x * W.y) / det;
        tau[1] = (r0.x * W.y - W.x * r0.y) / det;
        return;
    }
    // B = A_t^T A_t = sum_a r_a r_a^T over x, y; lambda = B^-1 W_t; tau_a = r_a . lambda
    T bxx = constant<T>(0.0), bxy = constant<T>(0.0), byy = constant<T>(0.0);
    for (int a = 0; a < n; ++a) {
        const S3<T>& r = A[static_cast<std::size_t>(a)];
        bxx = bxx + r.x * r.x;
        bxy = bxy + r.x * r.y;
        byy = byy + r.y * r.y;
    }
    const T det = bxx * byy - bxy * bxy;
    const T lx = (byy * W.x - bxy * W.y) / det;
    const T ly = (bxx * W.y - bxy * W.x) / det;
    for (int a = 0; a < n; ++a) {
        const S3<T>& r = A[static_cast<std::size_t>(a)];
        tau[static_cast<std::size_t>(a)] = r.x * lx + r.y * ly;
    }
}

/// tau from A^T tau = W (eq. 20): A^-T W with three actuators, else the minimum-norm
/// A (A^T A)^-1 W.
template <class T>
void distribute(int n, const std::array<S3<T>, kMaxActuators>& A, const S3<T>& W, std::array<T, kMaxActuators>& tau) {
    if (n == 3) {
        // A^T = [r_0 r_1 r_2] (columns): its inverse's rows are the inverseRowsOfColumns
        const std::array<S3<T>, 3> inv = inverseRowsOfColumns(A[0], A[1], A[2]);
        for (std::size_t a = 0; a < 3; ++a) tau[a] = dot(inv[a], W);
        return;
    }
    // B = A^T A = sum_a r_a r_a^T; lambda = B^-1 W; tau_a = r_a . lambda
    std::array<std::array<T, 3>, 3> B{};
    for (auto& row : B) row.fill(constant<T>(0.0));
    for (int a = 0; a < n; ++a) {
        const S3<T>& r = A[static_cast<std::size_t>(a)];
        const std::array<const T*, 3> e{&r.w, &r.x, &r.y};
        for (std::size_t i = 0; i < 3; ++i) {
            for (std::size_t k = i; k < 3; ++k) B[i][k] = B[i][k] + *e[i] * *e[k];
        }
    }
    // B is symmetric: its columns are its rows
    const S3<T> b0{B[0][0], B[0][1], B[0][2]}, b1{B[0][1], B[1][1], B[1][2]}, b2{B[0][2], B[1][2], B[2][2]};
    const std::array<S3<T>, 3> Binv = inverseRowsOfColumns(b0, b1, b2);
    const S3<T> lambda{dot(Binv[0], W), dot(Binv[1], W), dot(Binv[2], W)};
    for (int a = 0; a < n; ++a) tau[static_cast<std::size_t>(a)] = dot(A[static_cast<std::size_t>(a)], lambda);
}

template <int N>
Dual<N> seeded(double v, int direction) {
    Dual<N> d{v};
    if (direction >= 0) d.d(direction) = 1.0;
    return d;
}

template <int N>
P2<Dual<N>> lift(const Vector2& v) {
    return {Dual<N>{v.x()}, Dual<N>{v.y()}};
}
template <int N>
S3<Dual<N>> lift(const Twist& v) {
    return {Dual<N>{v(0)}, Dual<N>{v(1)}, Dual<N>{v(2)}};
}

/// The position-level inputs from data (position and Jacobian stages set) as dual numbers,
/// with derivatives along the pose directions in slots `p_slot`..+2 (none when negative):
/// along e_i, the platform twist is S(c) e_i, joint rates J_j^-1 S(c) e_i, body twists
/// xi_0 = s_0 gd_0, xi_1 = xi_0 + s_1 gd_1, and then ds_1 = [xi_0, s_1], ds_2 = [xi_1, s_2],
/// dx_b = the velocity of body b's point at x_b, dx_P that of the platform's at x_P.
template <int N>
void seedPositions(const Model& model, const Data& data, int p_slot, SampleIn<Dual<N>>& in) {
    const Vector2 c = data.p.tail<2>();
    in.c = lift<N>(c);
    in.x_P = lift<N>(data.x_P);
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        LimbIn<Dual<N>>& li = in.limb[static_cast<std::size_t>(j)];
        for (std::size_t k = 0; k < 3; ++k) li.s[k] = lift<N>(Twist(ld.s[k]));
        for (std::size_t b = 0; b < 2; ++b) li.x[b] = lift<N>(Vector2(ld.x[b]));
    }
    if (p_slot < 0) return;
    for (int i = 0; i < 3; ++i) {
        const int slot = p_slot + i;
        const Twist t = platformTwistOfPoseRate(c, Twist::Unit(i));
        if (i > 0) (i == 1 ? in.c.x : in.c.y).d(slot) = 1.0;
        const Twist vP = twistAt(t, data.x_P);
        in.x_P.x.d(slot) = vP(1);
        in.x_P.y.d(slot) = vP(2);
        for (int j = 0; j < model.limbs; ++j) {
            const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
            LimbIn<Dual<N>>& li = in.limb[static_cast<std::size_t>(j)];
            const Vector3 gd = ld.J_inv * t;
            const Twist xi0 = ld.s[0] * gd(0);
            const Twist xi1 = xi0 + ld.s[1] * gd(1);
            const Twist ds1 = nocdyn::bracket(xi0, ld.s[1]);
            const Twist ds2 = nocdyn::bracket(xi1, ld.s[2]);
            li.s[1].w.d(slot) = ds1(0);
            li.s[1].x.d(slot) = ds1(1);
            li.s[1].y.d(slot) = ds1(2);
            li.s[2].w.d(slot) = ds2(0);
            li.s[2].x.d(slot) = ds2(1);
            li.s[2].y.d(slot) = ds2(2);
            const Twist v0 = twistAt(xi0, ld.x[0]), v1 = twistAt(xi1, ld.x[1]);
            li.x[0].x.d(slot) = v0(1);
            li.x[0].y.d(slot) = v0(2);
            li.x[1].x.d(slot) = v1(1);
            li.x[1].y.d(slot) = v1(2);
        }
    }
}

/// A pose-space vector as duals with derivatives in slots `slot`..+2 (none when negative).
template <int N>
S3<Dual<N>> seedVector(const Twist& v, int slot) {
    return {seeded<N>(v(0), slot < 0 ? -1 : slot), seeded<N>(v(1), slot < 0 ? -1 : slot + 1),
            seeded<N>(v(2), slot < 0 ? -1 : slot + 2)};
}

/// Position and Jacobian stages (the Status of inverseDynamics for a bad pose or rate).
Status kinematics(const Model& model, Data& data, const Pose& p, const Twist& dp) {
    if (const Status status = inverseDisplacement(model, data, p); !status) return status;
    return velocityFromPlatformTwist(model, data, dp);
}

/// The nine input directions of one pass: p in slots 0-2, dp in 3-5, ddp in 6-8.
constexpr int kNine = 9;

/// The position and Jacobian stages at (p, dp) and the sample's inputs as duals along the nine
/// directions (the Status of inverseDynamics for a bad pose, rate or acceleration).
Status seedNineDirections(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                          SampleIn<Dual<kNine>>& in) {
    if (const Status status = kinematics(model, data, p, dp); !status) return status;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(ddp(i))) return {StatusCode::not_finite, -1, ddp(i)};
    }
    seedPositions<kNine>(model, data, 0, in);
    in.dp = seedVector<kNine>(dp, 3);
    in.ddp = seedVector<kNine>(ddp, 6);
    return {};
}

/// de/d(p, dp) (3 x 6) of the residual e = W_P(p, dp, ddp) - A(p)^T tau at the motion ddp, tau
/// held: the second pass of forwardDynamicsDerivatives (its kinematics at p, dp done).
Eigen::Matrix<double, 3, 6> residualDerivatives(const Model& model, const Data& data, const Twist& dp, const Twist& ddp,
                                                const ActuatorVector& tau) {
    constexpr int N = 6;
    SampleIn<Dual<N>> in;
    seedPositions<N>(model, data, 0, in);
    in.dp = seedVector<N>(dp, 3);
    in.ddp = seedVector<N>(ddp, -1);
    S3<Dual<N>> W;
    std::array<S3<Dual<N>>, kMaxActuators> A;
    platformWrench(model, in, W, A);
    Eigen::Matrix<double, 3, 6> de;
    const std::array<const Dual<N>*, 3> w{&W.w, &W.x, &W.y};
    for (int r = 0; r < 3; ++r) de.row(r) = w[static_cast<std::size_t>(r)]->d.transpose().matrix();
    for (int a = 0; a < model.actuators; ++a) {
        const S3<Dual<N>>& row = A[static_cast<std::size_t>(a)];
        de.row(0) -= tau(a) * row.w.d.transpose().matrix();
        de.row(1) -= tau(a) * row.x.d.transpose().matrix();
        de.row(2) -= tau(a) * row.y.d.transpose().matrix();
    }
    return de;
}

}  // namespace

Status inverseDynamicsDerivatives(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                                  InverseDynamicsDerivatives& out) {
    // one pass with nine directions: p in slots 0-2, dp in 3-5, ddp in 6-8
    constexpr int N = kNine;
    SampleIn<Dual<N>> in;
    if (const Status status = seedNineDirections(model, data, p, dp, ddp, in); !status) return status;
    S3<Dual<N>> W;
    std::array<S3<Dual<N>>, kMaxActuators> A;
    platformWrench(model, in, W, A);
    std::array<Dual<N>, kMaxActuators> tau;
    if (model.task_dimension == 2) {
        distributeTask(model.actuators, A, W, tau);
    } else {
        distribute(model.actuators, A, W, tau);
    }
    const int n = model.actuators;
    out.tau.resize(n);
    out.d_p.resize(n, 3);
    out.d_dp.resize(n, 3);
    out.d_ddp.resize(n, 3);
    for (int a = 0; a < n; ++a) {
        const Dual<N>& t = tau[static_cast<std::size_t>(a)];
        out.tau(a) = t.v;
        for (int i = 0; i < 3; ++i) {
            out.d_p(a, i) = t.d(i);
            out.d_dp(a, i) = t.d(3 + i);
            out.d_ddp(a, i) = t.d(6 + i);
        }
    }
    return {};
}

Status forwardDynamicsDerivatives(const Model& model, Data& data, const Pose& p, const Twist& dp,
                                  const ActuatorVector& tau, ForwardDynamicsDerivatives& out) {
    if (const Status status = kinematics(model, data, p, dp); !status) return status;
    const int n = model.actuators;
    for (int a = 0; a < n; ++a) {
        if (!std::isfinite(tau(a))) return {StatusCode::not_finite, -1, tau(a)};
    }
    // the residual e = W_P(p, dp, ddp) - A(p)^T tau (xi_P coordinates) vanishes on the motion.
    // First pass, ddp = 0 seeded: e_0 and K = de/d ddp; ddp = -K^-1 e_0 (e is linear in ddp).
    Vector3 ATtau = Vector3::Zero();
    for (int a = 0; a < n; ++a) ATtau += data.A.row(a).transpose() * tau(a);
    Matrix3 K;
    Vector3 e0;
    {
        constexpr int N = 3;
        SampleIn<Dual<N>> in;
        seedPositions<N>(model, data, -1, in);
        in.dp = seedVector<N>(dp, -1);
        in.ddp = seedVector<N>(Twist::Zero(), 0);
        S3<Dual<N>> W;
        std::array<S3<Dual<N>>, kMaxActuators> A;
        platformWrench(model, in, W, A);
        const std::array<const Dual<N>*, 3> e{&W.w, &W.x, &W.y};
        for (int r = 0; r < 3; ++r) {
            e0(r) = e[static_cast<std::size_t>(r)]->v - ATtau(r);
            K.row(r) = e[static_cast<std::size_t>(r)]->d.transpose().matrix();
        }
    }
    // K = S(c)^-T M_p: M_p = S(c)^T K
    const Matrix3 S = platformTwistMap(data.p.tail<2>());
    out.M_p = S.transpose() * K;
    if (model.task_dimension == 2) {
        // translation: theta is no coordinate (ddp = E ddp_t, and a rotation about C moves no
        // body: K's theta column is zero), so the motion solves G e = 0 with G = E^T S(c)^T,
        // M_t = G K E (2 x 2); d(ddp_t) = -M_t^-1 G de, d(ddp_t)/d tau = M_t^-1 G A^T. The
        // derivatives by theta and theta's own acceleration are zero.
        const Eigen::Matrix<double, 2, 3> G = S.transpose().bottomRows<2>();
        const Eigen::PartialPivLU<Matrix2> lu(G * K.rightCols<2>());
        const Vector2 ddp_t = -lu.solve(G * e0);
        out.ddp = Twist(0.0, ddp_t(0), ddp_t(1));
        if (!out.ddp.allFinite()) return {StatusCode::not_finite, -1, ddp_t(0)};
        const Eigen::Matrix<double, 3, 6> de = residualDerivatives(model, data, dp, out.ddp, tau);
        const Eigen::Matrix<double, 2, 6> dddp = -lu.solve(G * de);
        out.d_p.setZero();
        out.d_dp.setZero();
        out.d_p.bottomRightCorner<2, 2>() = dddp.block<2, 2>(0, 1);
        out.d_dp.bottomRightCorner<2, 2>() = dddp.block<2, 2>(0, 4);
        out.d_tau.setZero(3, n);
        for (int a = 0; a < n; ++a) out.d_tau.col(a).tail<2>() = lu.solve(G * Vector3(data.A.row(a).transpose()));
        return {};
    }
    const Eigen::PartialPivLU<Matrix3> lu(K);
    out.ddp = -lu.solve(e0);
    if (!out.ddp.allFinite()) return {StatusCode::not_finite, -1, out.ddp(0)};
    // K d(ddp) + de = 0; de/d tau = -A^T
    const Eigen::Matrix<double, 3, 6> dddp = -lu.solve(residualDerivatives(model, data, dp, out.ddp, tau));
    out.d_p = dddp.leftCols<3>();
    out.d_dp = dddp.rightCols<3>();
    out.d_tau.resize(3, n);
    for (int a = 0; a < n; ++a) out.d_tau.col(a) = lu.solve(Vector3(data.A.row(a).transpose()));
    return {};
}

Status actuatorVariableDerivatives(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                                   ActuatorVariableDerivatives& out) {
    // one pass with nine directions, as inverseDynamicsDerivatives: p in 0-2, dp in 3-5, ddp in 6-8
    constexpr int N = kNine;
    SampleIn<Dual<N>> in;
    if (const Status status = seedNineDirections(model, data, p, dp, ddp, in); !status) return status;
    S3<Dual<N>> xi_P, xi_P_dot;
    platformTwists(in, xi_P, xi_P_dot);
    const int n = model.actuators;
    out.u = data.u;
    out.du.resize(n);
    out.ddu.resize(n);
    out.u_p.resize(n, 3);
    out.du_p.resize(n, 3);
    out.du_dp.resize(n, 3);
    out.ddu_p.resize(n, 3);
    out.ddu_dp.resize(n, 3);
    out.ddu_ddp.resize(n, 3);
    // d u/d p along e_i is the actuated joint's rate for dp = e_i: the rows of A S(c)
    const Matrix3 S = platformTwistMap(data.p.tail<2>());
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbRates<Dual<N>> r = limbRates(in.limb[static_cast<std::size_t>(j)], xi_P, xi_P_dot);
        const std::array<const Dual<N>*, 3> gd{&r.gd.w, &r.gd.x, &r.gd.y};
        const std::array<const Dual<N>*, 3> gdd{&r.gdd.w, &r.gdd.x, &r.gdd.y};
        for (std::size_t k = 0; k < 3; ++k) {
            const int a = limb.actuator[k];
            if (a < 0) continue;
            // du_a = gamma_dot_jk, ddu_a = gamma_ddot_jk (eq. 3 and its rate)
            out.du(a) = gd[k]->v;
            out.ddu(a) = gdd[k]->v;
            out.u_p.row(a) = data.limb[static_cast<std::size_t>(j)].J_inv.row(static_cast<Eigen::Index>(k)) * S;
            for (int i = 0; i < 3; ++i) {
                out.du_p(a, i) = gd[k]->d(i);
                out.du_dp(a, i) = gd[k]->d(3 + i);
                out.ddu_p(a, i) = gdd[k]->d(i);
                out.ddu_dp(a, i) = gdd[k]->d(3 + i);
                out.ddu_ddp(a, i) = gdd[k]->d(6 + i);
            }
        }
    }
    return {};
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The N x 3 inputs of a derivative batch and the order of their pose columns.
struct SampleArrays {
    const BatchInput& p;
    const BatchInput& dp;
    const BatchInput& ddp;
    PoseColumns order;
};

/// Rows [begin, end) of a batch: sample(data, row, p, dp, ddp) computes and writes one row (NaN
/// when it fails) and returns its Status; status, when not empty, gets each row's.
template <class Sample>
BatchResult derivativeChunk(const Model& model, const SampleArrays& in, Eigen::Index begin, Eigen::Index end,
                            std::span<Status> status, Sample sample) {
    Data data(model);
    BatchResult result;
    for (Eigen::Index row = begin; row < end; ++row) {
        const Status s = sample(data, row, poseRow(in.p, row, in.order), poseRow(in.dp, row, in.order),
                                poseRow(in.ddp, row, in.order));
        if (!status.empty()) status[static_cast<std::size_t>(row)] = s;
        if (!s && result.failed++ == 0) {
            result.first_failure = row;
            result.status = s;
        }
    }
    return result;
}

/// A batch of in.p.rows() samples split over `threads` as inverseDynamicsBatch; sample as
/// derivativeChunk's (it must keep its own per-sample workspace per chunk: see its callers).
template <class MakeSample>
BatchResult runDerivativeBatch(const char* what, const Model& model, const SampleArrays& in, unsigned threads,
                               std::span<Status> status, const MakeSample& make) {
    const Eigen::Index n = in.p.rows();
    const ParallelSplit split = splitRange(n, threads, 8);  // inverseDynamicsBatch's split
    if (split.workers == 1) return derivativeChunk(model, in, 0, n, status, make());
    std::vector<BatchResult> results(split.workers);
    parallelFor(what, split, [&](unsigned w, Eigen::Index begin, Eigen::Index end) {
        results[w] = derivativeChunk(model, in, begin, end, status, make());
    });
    return combineChunks(results);
}

void requireShape(const char* what, const char* name, Eigen::Index rows, Eigen::Index cols, Eigen::Index n,
                  Eigen::Index m) {
    if (rows != n || cols != m) {
        throw Error(std::string(what) + ": " + name + " is " + std::to_string(rows) + " x " + std::to_string(cols) +
                    ", expected " + std::to_string(n) + " x " + std::to_string(m));
    }
}

void requireInputs(const char* what, const SampleArrays& in) {
    const Eigen::Index n = in.p.rows();
    requireShape(what, "p", in.p.rows(), in.p.cols(), n, 3);
    requireShape(what, "dp", in.dp.rows(), in.dp.cols(), n, 3);
    requireShape(what, "ddp", in.ddp.rows(), in.ddp.cols(), n, 3);
}

/// Row `row` of an N x 3n output: column 3 a + (pose column of i) = m(a, i), or NaN.
void writeJacobianRow(BatchOutput& out, Eigen::Index row, const ActuatorPoseJacobian& m, int n, PoseColumns order,
                      bool ok) {
    for (int a = 0; a < n; ++a) {
        for (int i = 0; i < 3; ++i) out(row, 3 * a + poseColumn(order, i)) = ok ? m(a, i) : kNaN;
    }
}

/// Row `row` of an N x n output: v, or NaN.
void writeActuatorRow(BatchOutput& out, Eigen::Index row, const ActuatorVector& v, int n, bool ok) {
    for (int a = 0; a < n; ++a) out(row, a) = ok ? v(a) : kNaN;
}

}  // namespace

BatchResult inverseDynamicsDerivativesBatch(const Model& model, const BatchInput& p, const BatchInput& dp,
                                            const BatchInput& ddp, BatchOutput d_p, BatchOutput d_dp, BatchOutput d_ddp,
                                            unsigned threads, PoseColumns order) {
    constexpr const char* what = "inverseDynamicsDerivativesBatch";
    const SampleArrays in{p, dp, ddp, order};
    requireInputs(what, in);
    const Eigen::Index n = p.rows();
    const Eigen::Index columns = 3 * static_cast<Eigen::Index>(model.actuators);
    requireShape(what, "d_p", d_p.rows(), d_p.cols(), n, columns);
    requireShape(what, "d_dp", d_dp.rows(), d_dp.cols(), n, columns);
    requireShape(what, "d_ddp", d_ddp.rows(), d_ddp.cols(), n, columns);
    const int actuators = model.actuators;
    return runDerivativeBatch(what, model, in, threads, {}, [&] {
        return [&, d = InverseDynamicsDerivatives{}](Data& data, Eigen::Index row, const Pose& pk, const Twist& dpk,
                                                     const Twist& ddpk) mutable {
            const Status status = inverseDynamicsDerivatives(model, data, pk, dpk, ddpk, d);
            writeJacobianRow(d_p, row, d.d_p, actuators, order, status.ok());
            writeJacobianRow(d_dp, row, d.d_dp, actuators, order, status.ok());
            writeJacobianRow(d_ddp, row, d.d_ddp, actuators, order, status.ok());
            return status;
        };
    });
}

BatchResult actuatorVariableDerivativesBatch(const Model& model, const BatchInput& p, const BatchInput& dp,
                                             const BatchInput& ddp, ActuatorVariableDerivativesBatch out,
                                             unsigned threads, PoseColumns order) {
    constexpr const char* what = "actuatorVariableDerivativesBatch";
    const SampleArrays in{p, dp, ddp, order};
    requireInputs(what, in);
    const Eigen::Index n = p.rows();
    const auto actuators = static_cast<Eigen::Index>(model.actuators);
    const std::array<std::pair<const char*, const BatchOutput*>, 3> values{
        {{"u", &out.u}, {"du", &out.du}, {"ddu", &out.ddu}}};
    for (const auto& [name, m] : values) requireShape(what, name, m->rows(), m->cols(), n, actuators);
    const std::array<std::pair<const char*, const BatchOutput*>, 6> jacobians{{{"u_p", &out.u_p},
                                                                               {"du_p", &out.du_p},
                                                                               {"du_dp", &out.du_dp},
                                                                               {"ddu_p", &out.ddu_p},
                                                                               {"ddu_dp", &out.ddu_dp},
                                                                               {"ddu_ddp", &out.ddu_ddp}}};
    for (const auto& [name, m] : jacobians) requireShape(what, name, m->rows(), m->cols(), n, 3 * actuators);
    if (!out.status.empty() && std::ssize(out.status) != n) {
        throw Error(std::string(what) + ": status has " + std::to_string(out.status.size()) + " entries, expected " +
                    std::to_string(n));
    }
    const int a = model.actuators;
    return runDerivativeBatch(what, model, in, threads, out.status, [&] {
        return [&, d = ActuatorVariableDerivatives{}](Data& data, Eigen::Index row, const Pose& pk, const Twist& dpk,
                                                      const Twist& ddpk) mutable {
            const Status status = actuatorVariableDerivatives(model, data, pk, dpk, ddpk, d);
            const bool ok = status.ok();
            writeActuatorRow(out.u, row, d.u, a, ok);
            writeActuatorRow(out.du, row, d.du, a, ok);
            writeActuatorRow(out.ddu, row, d.ddu, a, ok);
            const std::array<std::pair<BatchOutput*, const ActuatorPoseJacobian*>, 6> rows{
                {{&out.u_p, &d.u_p},
                 {&out.du_p, &d.du_p},
                 {&out.du_dp, &d.du_dp},
                 {&out.ddu_p, &d.ddu_p},
                 {&out.ddu_dp, &d.ddu_dp},
                 {&out.ddu_ddp, &d.ddu_ddp}}};
            for (const auto& [o, m] : rows) writeJacobianRow(*o, row, *m, a, order, ok);
            return status;
        };
    });
}

}  // namespace nocdyn
