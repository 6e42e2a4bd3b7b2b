// The lean inverse dynamics of one sample of the general model (dynamics.hpp,
// inverseDynamicsFast), on a scalar S that stays in registers and inlines into the
// per-sample entry (S = double) and the batch loop (S = fastmath::Pack or Pack8, four or
// eight samples in the lanes of one vector, the same arithmetic lane by lane). Internal (not
// installed).
//
// The same physics as the stages (kinematics.cpp, dynamics.cpp), one limb at a time:
//   position   closed-form joint variables (limb_ik_impl.hpp), screws by the product of
//              exponentials, body c.o.m.
//   velocity   J_j = [s_1 s_2 s_3] inverted by cofactors, gamma_dot_j = J_j^-1 xi_P,
//              body twists xi_1 = s_1 gd_1, xi_2 = xi_1 + s_2 gd_2, screw rates [xi, s]
//   accel.     gamma_ddot_j = J_j^-1 (dxi_P - ds_2 gd_2 - ds_3 gd_3), body twist rates
//   forces     body inertia wrenches less gravity, joint efforts, W_P += J_j^-T f_j;
//              then A^T tau = W_P (A^-T W_P, or the minimum-norm solution)
// and the conditioning tests of jacobianStage in division-free form. It does not form T_i,
// I or C. A rejected sample (unreachable, or a condition number beyond the limit) is false
// in the returned mask (on a double: false, returned as soon as known); the caller then
// asks the full path for the exact Status. On a Pack every test is a lane mask: no branch
// depends on a sample, only on the model (limb kinds, actuated joints).
#pragma once

#include <algorithm>

#include "nocdyn/detail/sanitizer.hpp"
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "limb_ik_impl.hpp"
#include "nocdyn/detail/fast_math.hpp"
#include "nocdyn/model.hpp"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace nocdyn::detail::lean {

using fastmath::absOf;
using fastmath::Mask;
using fastmath::maxOf;
using fastmath::Pack;
using fastmath::select;
using fastmath::splat;

/// The scalars of the kernel: one sample or a packet of them.
template <class S>
concept Real = std::is_same_v<S, double> || fastmath::Packet<S>;

/// A compile-time zero: the angular part of a prismatic joint's screw and of the twist of a
/// body that only translates. Terms with it vanish when the kernel is compiled (a double 0.0
/// cannot make a product vanish: 0 * inf is NaN), so that the one kernel written for every
/// limb type does no arithmetic on the zeros of P joints.
struct Zero {};
template <Real S>
NOCDYN_ALWAYS_INLINE constexpr Zero operator*(Zero, const S&) {
    return {};
}
template <Real S>
NOCDYN_ALWAYS_INLINE constexpr Zero operator*(const S&, Zero) {
    return {};
}
NOCDYN_ALWAYS_INLINE constexpr Zero operator*(Zero, Zero) { return {}; }
NOCDYN_ALWAYS_INLINE constexpr Zero operator+(Zero, Zero) { return {}; }
template <Real S>
NOCDYN_ALWAYS_INLINE constexpr S operator+(const S& a, Zero) {
    return a;
}
template <Real S>
NOCDYN_ALWAYS_INLINE constexpr S operator+(Zero, const S& b) {
    return b;
}
NOCDYN_ALWAYS_INLINE constexpr Zero operator-(Zero, Zero) { return {}; }
template <Real S>
NOCDYN_ALWAYS_INLINE constexpr S operator-(const S& a, Zero) {
    return a;
}
template <Real S>
NOCDYN_ALWAYS_INLINE constexpr S operator-(Zero, const S& b) {
    return -b;
}
NOCDYN_ALWAYS_INLINE constexpr Zero operator-(Zero) { return {}; }
/// An expression's value as an S (0 for Zero).
template <class S>
NOCDYN_ALWAYS_INLINE constexpr S value(const S& a) {
    return a;
}
template <class S>
NOCDYN_ALWAYS_INLINE constexpr S value(Zero) {
    return S{};
}
NOCDYN_ALWAYS_INLINE constexpr Zero absOf(Zero) { return {}; }

/// A planar twist or wrench referred to O, [w; x; y]; W = Zero when w is known to vanish.
template <class W, class S>
struct Tw {
    W w;
    S x, y;
};
template <class S>
using V3 = Tw<S, S>;

template <class A, class B, class S>
NOCDYN_ALWAYS_INLINE auto operator+(const Tw<A, S>& a, const Tw<B, S>& b) {
    return Tw<decltype(a.w + b.w), S>{a.w + b.w, a.x + b.x, a.y + b.y};
}
template <class A, class B, class S>
NOCDYN_ALWAYS_INLINE auto operator-(const Tw<A, S>& a, const Tw<B, S>& b) {
    return Tw<decltype(a.w - b.w), S>{a.w - b.w, a.x - b.x, a.y - b.y};
}
template <class A, class S>
NOCDYN_ALWAYS_INLINE auto operator*(const S& k, const Tw<A, S>& a) {
    return Tw<decltype(k * a.w), S>{k * a.w, k * a.x, k * a.y};
}
template <class A, class B, class S>
NOCDYN_ALWAYS_INLINE S dot(const Tw<A, S>& a, const Tw<B, S>& b) {
    return a.w * b.w + a.x * b.x + a.y * b.y;
}
/// The cross product of 3-arrays: the cofactors of a 3 x 3 matrix.
template <class A, class B, class S>
NOCDYN_ALWAYS_INLINE V3<S> cross(const Tw<A, S>& a, const Tw<B, S>& b) {
    return {a.x * b.y - a.y * b.x, value<S>(a.y * b.w - a.w * b.y), value<S>(a.w * b.x - a.x * b.w)};
}
/// Lie bracket of planar twists referred to O (kinematics.hpp, bracket): a pure translation.
template <class A, class B, class S>
NOCDYN_ALWAYS_INLINE Tw<Zero, S> bracket(const Tw<A, S>& a, const Tw<B, S>& b) {
    return {{}, value<S>(-a.w * b.y + b.w * a.y), value<S>(a.w * b.x - b.w * a.x)};
}

/// A planar rigid displacement x -> R(c, s) x + t; Sn = Zero for a translation (c = 1).
template <class Sn, class S>
struct Move {
    S c;
    Sn s;
    S tx, ty;
    template <class X>
    [[nodiscard]] NOCDYN_ALWAYS_INLINE S rx(const X& x, const X& y) const {
        return c * x - s * y;
    }
    template <class X>
    [[nodiscard]] NOCDYN_ALWAYS_INLINE S ry(const X& x, const X& y) const {
        return s * x + c * y;
    }
    template <class T>
    [[nodiscard]] NOCDYN_ALWAYS_INLINE auto then(const Move<T, S>& o) const {
        return Move<decltype(s * o.c + c * o.s), S>{c * o.c - s * o.s, s * o.c + c * o.s, rx(o.tx, o.ty) + tx,
                                                    ry(o.tx, o.ty) + ty};
    }
};

/// Whether joint k of a limb of kind K is revolute (known at compile time, so that the
/// kernel below is specialised per limb type: one template, no hand-written copy).
template <LimbKind K>
constexpr bool revolute(int k) {
    constexpr const char* kNames[] = {"RRR", "PRR", "RPR", "RRP", "PRP", "RPP", "PPR", "PPP"};
    return kNames[static_cast<int>(K)][k] == 'R';
}

/// Scale of joint k's variable in the condition numbers and its inverse (model.hpp,
/// LimbModel::joint_scale): 1 for an R joint, known at compile time so that its products
/// vanish; the limb's value for a P joint.
template <LimbKind K, class LM>
NOCDYN_ALWAYS_INLINE double jointScale(const LM& limb, int k) {
    return revolute<K>(k) ? 1.0 : modelOf(limb).joint_scale[static_cast<std::size_t>(k)];
}
template <LimbKind K, class LM>
NOCDYN_ALWAYS_INLINE double invJointScale(const LM& limb, int k) {
    return revolute<K>(k) ? 1.0 : modelOf(limb).inv_joint_scale[static_cast<std::size_t>(k)];
}

/// A limb constant as an S: a double in every lane, or the packet of the limbs' values.
template <class S>
NOCDYN_ALWAYS_INLINE S asS(double x) {
    return splat<S>(x);
}
// NOLINTBEGIN(bugprone-return-const-ref-from-parameter): identities over lvalues, inlined
template <class S, fastmath::Packet P>
NOCDYN_ALWAYS_INLINE const P& asS(const P& x) {
    return x;
}
// NOLINTEND(bugprone-return-const-ref-from-parameter)

NOCDYN_ALWAYS_INLINE double massOf(const LimbModel& limb, int b) { return limb.M[static_cast<std::size_t>(b)].mass; }
template <int kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<kN> massOf(const LaneLimbOf<kN>& limb, int b) {
    return lanesOf(limb.lanes.mass[static_cast<std::size_t>(b)]);
}
NOCDYN_ALWAYS_INLINE double inertiaOf(const LimbModel& limb, int b) {
    return limb.M[static_cast<std::size_t>(b)].inertia;
}
template <int kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<kN> inertiaOf(const LaneLimbOf<kN>& limb, int b) {
    return lanesOf(limb.lanes.inertia[static_cast<std::size_t>(b)]);
}
NOCDYN_ALWAYS_INLINE const Vector2& comHomeOf(const LimbModel& limb, int b) {
    return limb.com_home[static_cast<std::size_t>(b)];
}
template <int kN>
NOCDYN_ALWAYS_INLINE PV<PackOfLanes<kN>> comHomeOf(const LaneLimbOf<kN>& limb, int b) {
    const auto bb = static_cast<std::size_t>(b);
    return {lanesOf(limb.lanes.com_x[bb]), lanesOf(limb.lanes.com_y[bb])};
}
NOCDYN_ALWAYS_INLINE double dampingOf(const LimbModel& limb, int k) {
    return limb.damping[static_cast<std::size_t>(k)];
}
template <int kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<kN> dampingOf(const LaneLimbOf<kN>& limb, int k) {
    return lanesOf(limb.lanes.damping[static_cast<std::size_t>(k)]);
}
NOCDYN_ALWAYS_INLINE double frictionOf(const LimbModel& limb, int k) {
    return limb.friction[static_cast<std::size_t>(k)];
}
template <int kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<kN> frictionOf(const LaneLimbOf<kN>& limb, int k) {
    return lanesOf(limb.lanes.friction[static_cast<std::size_t>(k)]);
}
/// The linear part of the first joint's home screw, s_1(0) = [w; x; y].
NOCDYN_ALWAYS_INLINE Vector2 homeScrewLinearOf(const LimbModel& limb) {
    return {limb.screw_home[0](1), limb.screw_home[0](2)};
}
template <int kN>
NOCDYN_ALWAYS_INLINE PV<PackOfLanes<kN>> homeScrewLinearOf(const LaneLimbOf<kN>& limb) {
    return {lanesOf(limb.lanes.screw_x), lanesOf(limb.lanes.screw_y)};
}
/// Where joint k's actuator writes: its actuator index for one limb, -1 when the joint is
/// passive; 0 for a LaneLimb, whose lane l is the actuator of limb l (one per limb).
NOCDYN_ALWAYS_INLINE int actuatorOf(const LimbModel& limb, int k) { return limb.actuator[static_cast<std::size_t>(k)]; }
NOCDYN_ALWAYS_INLINE int actuatorOf(const LaneLimb& limb, int k) {
    return limb.first.actuator[static_cast<std::size_t>(k)] >= 0 ? 0 : -1;
}

/// exp of joint k's home screw times q_k.
template <bool kRevolute, class S, class LM>
NOCDYN_ALWAYS_INLINE auto jointMove(const LM& limb, const JointSolution<S>& js, int k) {
    if constexpr (!kRevolute) {
        const auto& d = directionOf(limb, k);
        return Move<Zero, S>{splat<S>(1.0), {}, js.q(k) * d.x(), js.q(k) * d.y()};
    } else {
        const S c = js.c(k), s = js.s(k);
        const auto& r = pointHomeOf(limb, k);
        const auto px = r.x(), py = r.y();
        return Move<S, S>{c, s, px - (c * px - s * py), py - (s * px + c * py)};
    }
}

/// Home screw of the first joint (referred to O).
template <bool kRevolute, class S, class LM>
NOCDYN_ALWAYS_INLINE auto homeScrew(const LM& limb) {
    const auto& v = homeScrewLinearOf(limb);
    if constexpr (kRevolute) {
        return V3<S>{splat<S>(1.0), asS<S>(v.x()), asS<S>(v.y())};
    } else {
        return Tw<Zero, S>{{}, asS<S>(v.x()), asS<S>(v.y())};
    }
}

/// Current screw of joint k carried by the body displaced by g.
template <bool kRevolute, class Sn, class S, class LM>
NOCDYN_ALWAYS_INLINE auto jointScrew(const LM& limb, const Move<Sn, S>& g, int k) {
    if constexpr (kRevolute) {
        const auto& r = pointHomeOf(limb, k);
        const auto px = r.x(), py = r.y();
        return V3<S>{splat<S>(1.0), g.ry(px, py) + g.ty, -(g.rx(px, py) + g.tx)};
    } else {
        const auto& d = directionOf(limb, k);
        const auto dx = d.x(), dy = d.y();
        return Tw<Zero, S>{{}, g.rx(dx, dy), g.ry(dx, dy)};
    }
}

/// Inertia wrench, less gravity, of a body (inertia I, mass m, c.o.m. x) with twist xi and
/// twist rate alpha referred to O, itself referred to O (dynamics.cpp, bodyWrench).
template <class A, class B, class S, class C>
NOCDYN_ALWAYS_INLINE V3<S> bodyWrench(const C& I, const C& m, double gx, double gy, const S& px, const S& py,
                                      const Tw<A, S>& xi, const Tw<B, S>& alpha) {
    const A w = xi.w;
    const S vx = xi.x - w * py, vy = xi.y + w * px;
    const S ax = alpha.x - alpha.w * py - w * vy, ay = alpha.y + alpha.w * px + w * vx;
    const S fx = m * (ax - gx), fy = m * (ay - gy);
    return {I * alpha.w + (px * fy - py * fx), fx, fy};
}

template <class S>
NOCDYN_ALWAYS_INLINE S sign(const S& v) {
    return select(v > 0.0, splat<S>(1.0), select(v < 0.0, splat<S>(-1.0), splat<S>(0.0)));
}

/// Where one sample's outputs go: actuator a's u at u[a * stride], and so on (stride 1 for
/// a vector, the number of samples for the columns of a column-major array).
template <class S>
struct Out {
    S* u;
    S* du;
    S* ddu;
    S* tau;
    std::ptrdiff_t stride;
};

/// The constants of a sample shared by every limb.
template <class S>
struct Frame {
    PlatformMove<S> G;
    V3<S> xi_P, xi_P_dot;
    double gx, gy, L, inv_L, max_condition;
};

/// ok & test, on a double as soon as known: `if (!reject(ok, test)) return ok;` leaves at
/// the first failed test of one sample, never for a packet (its lanes go on together).
template <class S>
NOCDYN_ALWAYS_INLINE bool pass(Mask<S>& ok, const Mask<S>& test) {
    if constexpr (std::is_same_v<S, double>) {
        ok = test;
        return test;
    } else {
        ok = ok & test;
        return true;
    }
}

/// What the joint reactions (reactions.cpp) keep of one limb: the screws s_k, the rows j_k of
/// J_j^-1, the bodies' wrenches w_1, w_2 (M dt - gravity, referred to O) and c.o.m., the joint
/// rates and accelerations, and f = k_j + phi_j (each joint's share of the bodies' wrenches
/// plus its friction), so that F_3 = J_j^-T (e - f) with e the actuators' forces.
template <class S>
struct LimbTerms {
    V3<S> s[3], j[3], w[2], xi[2];
    S x[2], y[2];
    S gd[3], gdd[3], f[3];
};
/// No capture: the inverse dynamics alone (the capture's stores compiled away).
struct NoCapture {};

/// One limb of kind K: its joint rates and accelerations, its bodies' share of W_P (into
/// W), and its actuators' u, du, ddu and rows of A. False (lane by lane) when the limb
/// cannot close or its J_j is too ill-conditioned. With a LimbTerms `capture`, also what the
/// reactions need.
/// kAct: the one actuated joint of the limb (0..2), known at compile time, or kAnyActuation
/// (read from limb.actuator).
inline constexpr int kAnyActuation = -1;

template <LimbKind K, int kAct, class S, class LM, class Capture = NoCapture>
NOCDYN_ALWAYS_INLINE Mask<S> limbTerms(const LM& limb, const Frame<S>& f, const Out<S>& out, V3<S>& W, V3<S>* rows,
                                       double* weight, double* scale, Capture* capture = nullptr) {
    const PlatformMove<S>& G = f.G;
    const V3<S>& xi_P = f.xi_P;
    const V3<S>& xi_P_dot = f.xi_P_dot;
    const double gx = f.gx, gy = f.gy, L = f.L, inv_L = f.inv_L, max_condition = f.max_condition;
    JointSolution<S> js;
    Mask<S> ok = ik::yes<S>();
    {
        const Closure<S> closure = ik::solveKind<K>(limb, G, branchOf(limb), js);
        if (!pass<S>(ok, static_cast<Mask<S>>(closure.regular & closure.reach))) return ok;
    }
    // screws by the product of exponentials, c.o.m. of the two bodies
    const auto g1 = jointMove<revolute<K>(0)>(limb, js, 0);
    const auto g2 = g1.then(jointMove<revolute<K>(1)>(limb, js, 1));
    const auto s0 = homeScrew<revolute<K>(0), S>(limb);
    const auto s1 = jointScrew<revolute<K>(1)>(limb, g1, 1);
    const auto s2 = jointScrew<revolute<K>(2)>(limb, g2, 2);
    const auto& c0 = comHomeOf(limb, 0);
    const auto& c1 = comHomeOf(limb, 1);
    const S x0 = g1.rx(c0.x(), c0.y()) + g1.tx, y0 = g1.ry(c0.x(), c0.y()) + g1.ty;
    const S x1 = g2.rx(c1.x(), c1.y()) + g2.tx, y1 = g2.ry(c1.x(), c1.y()) + g2.ty;

    // J_j^-1 = adj / det, rows a_k of adj: s_2 x s_3, s_3 x s_1, s_1 x s_2
    const V3<S> a0 = cross(s1, s2), a1 = cross(s2, s0), a2 = cross(s0, s1);
    const S det = dot(s0, a0);
    // scaled 1-norm condition number (stages.hpp, limbConditionNorms), times |det|
    const auto cs = [&limb](int k) NOCDYN_INLINE_LAMBDA { return jointScale<K>(limb, k); };
    const auto ic = [&limb](int k) NOCDYN_INLINE_LAMBDA { return invJointScale<K>(limb, k); };
    const S n_J = maxOf(maxOf(cs(0) * (absOf(s0.w) + (absOf(s0.x) + absOf(s0.y)) * inv_L),
                              cs(1) * (absOf(s1.w) + (absOf(s1.x) + absOf(s1.y)) * inv_L)),
                        cs(2) * (absOf(s2.w) + (absOf(s2.x) + absOf(s2.y)) * inv_L));
    const S n_adj = maxOf(absOf(a0.w) * ic(0) + absOf(a1.w) * ic(1) + absOf(a2.w) * ic(2),
                          L * maxOf(absOf(a0.x) * ic(0) + absOf(a1.x) * ic(1) + absOf(a2.x) * ic(2),
                                    absOf(a0.y) * ic(0) + absOf(a1.y) * ic(1) + absOf(a2.y) * ic(2)));
    if (!pass<S>(ok, n_J * n_adj <= max_condition * absOf(det))) return ok;
    const S inv_det = 1.0 / det;
    const V3<S> j0 = inv_det * a0, j1 = inv_det * a1, j2 = inv_det * a2;  // rows of J_j^-1

    // rates (eq. 3), body twists, screw rates, accelerations
    const S gd0 = dot(j0, xi_P), gd1 = dot(j1, xi_P), gd2 = dot(j2, xi_P);
    const auto xi0 = gd0 * s0;
    const auto xi1 = xi0 + gd1 * s1;
    const auto sd1_gd1 = gd1 * bracket(xi0, s1);
    const V3<S> rhs = xi_P_dot - sd1_gd1 - gd2 * bracket(xi1, s2);
    const S gdd0 = dot(j0, rhs), gdd1 = dot(j1, rhs), gdd2 = dot(j2, rhs);
    const auto alpha0 = gdd0 * s0;
    const auto alpha1 = alpha0 + gdd1 * s1 + sd1_gd1;
    const V3<S> W0 = bodyWrench(inertiaOf(limb, 0), massOf(limb, 0), gx, gy, x0, y0, xi0, alpha0);
    const V3<S> W1 = bodyWrench(inertiaOf(limb, 1), massOf(limb, 1), gx, gy, x1, y1, xi1, alpha1);
    // joint efforts: joint k carries every body outboard of it in the limb, plus friction
    S f0 = dot(s0, W0 + W1), f1 = dot(s1, W1);
    S f2 = splat<S>(0.0);
    if (modelOf(limb).frictionless) [[likely]] {
        W = W + f0 * j0 + f1 * j1;
    } else {
        f0 += dampingOf(limb, 0) * gd0 + frictionOf(limb, 0) * sign(gd0);
        f1 += dampingOf(limb, 1) * gd1 + frictionOf(limb, 1) * sign(gd1);
        f2 = dampingOf(limb, 2) * gd2 + frictionOf(limb, 2) * sign(gd2);
        W = W + f0 * j0 + f1 * j1 + f2 * j2;
    }
    if constexpr (!std::is_same_v<Capture, NoCapture>) {
        const auto full = [](const auto& t) NOCDYN_INLINE_LAMBDA { return V3<S>{value<S>(t.w), t.x, t.y}; };
        LimbTerms<S>& c = *capture;
        c.s[0] = full(s0), c.s[1] = full(s1), c.s[2] = full(s2);
        c.j[0] = j0, c.j[1] = j1, c.j[2] = j2;
        c.w[0] = W0, c.w[1] = W1;
        c.xi[0] = full(xi0), c.xi[1] = full(xi1);
        c.x[0] = x0, c.y[0] = y0, c.x[1] = x1, c.y[1] = y1;
        c.gd[0] = gd0, c.gd[1] = gd1, c.gd[2] = gd2;
        c.gdd[0] = gdd0, c.gdd[1] = gdd1, c.gdd[2] = gdd2;
        c.f[0] = f0, c.f[1] = f1, c.f[2] = f2;
    }

    // joint k's value of three (no array: the values stay in registers)
    const auto pick = [](int k, const auto& x0, const auto& x1, const auto& x2) NOCDYN_INLINE_LAMBDA -> const auto& {
        return k == 0 ? x0 : k == 1 ? x1 : x2;
    };
    const auto actuated = [&](int k) NOCDYN_INLINE_LAMBDA {
        const int a = actuatorOf(limb, k);
        // an actuated R joint's angle: the one atan2 the lean path needs
        const std::ptrdiff_t at = a * out.stride;
        if (revolute<K>(k)) {
            out.u[at] = fastmath::atan2Of(js.s(k), js.c(k));
        } else {
            out.u[at] = js.q(k);
        }
        out.du[at] = pick(k, gd0, gd1, gd2);
        out.ddu[at] = pick(k, gdd0, gdd1, gdd2);
        rows[a] = pick(k, j0, j1, j2);
        weight[a] = ic(k);
        scale[a] = cs(k);
    };
    if constexpr (kAct == kAnyActuation) {
        for (int k = 0; k < 3; ++k) {
            if (actuatorOf(limb, k) >= 0) actuated(k);
        }
    } else {
        actuated(kAct);
    }
    return ok;
}

/// Every limb by its kind read at run time, its actuated joints from limb.actuator.
struct AnyLimb {
    static constexpr bool kUnitWeights = false;  ///< every actuated joint revolute (weight 1)
    template <class S>
    NOCDYN_ALWAYS_INLINE Mask<S> operator()(int /*j*/, const LimbModel& limb, const Frame<S>& f, const Out<S>& out,
                                            V3<S>& W, V3<S>* rows, double* weight, double* scale) const {
        switch (limb.kind) {
            case LimbKind::RRR:
                return limbTerms<LimbKind::RRR, kAnyActuation>(limb, f, out, W, rows, weight, scale);
            case LimbKind::PRR:
                return limbTerms<LimbKind::PRR, kAnyActuation>(limb, f, out, W, rows, weight, scale);
            case LimbKind::RPR:
                return limbTerms<LimbKind::RPR, kAnyActuation>(limb, f, out, W, rows, weight, scale);
            case LimbKind::RRP:
                return limbTerms<LimbKind::RRP, kAnyActuation>(limb, f, out, W, rows, weight, scale);
            case LimbKind::PRP:
                return limbTerms<LimbKind::PRP, kAnyActuation>(limb, f, out, W, rows, weight, scale);
            case LimbKind::RPP:
                return limbTerms<LimbKind::RPP, kAnyActuation>(limb, f, out, W, rows, weight, scale);
            case LimbKind::PPR:
                return limbTerms<LimbKind::PPR, kAnyActuation>(limb, f, out, W, rows, weight, scale);
            case LimbKind::PPP:
                break;  // rejected by validate()
        }
        return splat<S>(0.0) != 0.0;
    }
};

/// One limb's constants as packets of kN lanes, every lane the same value (the batch: a
/// packet holds four or eight samples of one limb). Read through LaneLimbOf's accessors, so
/// that the kernel's constants are whole packets loaded from memory (an arithmetic operand),
/// splatted once per chunk rather than broadcast at every packet; its actuated joints write
/// their own actuators (not lane l = limb l).
template <int kN>
struct SplatLimb : LaneLimbOf<kN> {};
template <int kN>
NOCDYN_ALWAYS_INLINE int actuatorOf(const SplatLimb<kN>& limb, int k) {
    return limb.first.actuator[static_cast<std::size_t>(k)];
}

/// A limb of a uniform robot (Model::uniform_limbs = kCode = kind * 3 + the actuated joint):
/// limbTerms compiled for that kind and joint (UniformLimb, four or eight lanes).
template <int kCode, class LM, class S>
NOCDYN_ALWAYS_INLINE Mask<S> uniformTerms(const LM& limb, const Frame<S>& f, const Out<S>& out, V3<S>& W, V3<S>* rows,
                                          double* weight, double* scale) {
    return limbTerms<static_cast<LimbKind>(kCode / 3), kCode % 3>(limb, f, out, W, rows, weight, scale);
}

/// The batch's limbs when they are uniform (Model::uniform_limbs = kCode = kind * 3 + the
/// actuated joint): compiled for that kind and joint, no dispatch and no search for the
/// actuated joint in the limb loop; their constants splatted once per chunk (`lanes`, limb j
/// at lanes[j], kN lanes).
template <int kCode, int kN>
struct UniformLimb {
    using P = PackOfLanes<kN>;
    static constexpr bool kUnitWeights = revolute<static_cast<LimbKind>(kCode / 3)>(kCode % 3);
    const LimbLanesOf<kN>* lanes;
    NOCDYN_ALWAYS_INLINE Mask<P> operator()(int j, const LimbModel& model_limb, const Frame<P>& f, const Out<P>& out,
                                            V3<P>& W, V3<P>* rows, double* weight, double* scale) const {
        return uniformTerms<kCode>(SplatLimb<kN>{{lanes[j], model_limb}}, f, out, W, rows, weight, scale);
    }
};

/// A robot of mixed limbs in the batch: the kind read per limb (once per limb and packet),
/// each limb through the same template as a uniform robot's (kN lanes).
template <int kN>
struct SplatAny {
    using P = PackOfLanes<kN>;
    static constexpr bool kUnitWeights = false;
    const LimbLanesOf<kN>* lanes;
    NOCDYN_ALWAYS_INLINE Mask<P> operator()(int j, const LimbModel& limb, const Frame<P>& f, const Out<P>& out,
                                            V3<P>& W, V3<P>* rows, double* weight, double* scale) const {
        const auto terms = [&]<LimbKind K>() NOCDYN_INLINE_LAMBDA {
            return limbTerms<K, kAnyActuation>(SplatLimb<kN>{{lanes[j], limb}}, f, out, W, rows, weight, scale);
        };
        switch (limb.kind) {
            case LimbKind::RRR:
                return terms.template operator()<LimbKind::RRR>();
            case LimbKind::PRR:
                return terms.template operator()<LimbKind::PRR>();
            case LimbKind::RPR:
                return terms.template operator()<LimbKind::RPR>();
            case LimbKind::RRP:
                return terms.template operator()<LimbKind::RRP>();
            case LimbKind::PRP:
                return terms.template operator()<LimbKind::PRP>();
            case LimbKind::RPP:
                return terms.template operator()<LimbKind::RPP>();
            case LimbKind::PPR:
                return terms.template operator()<LimbKind::PPR>();
            case LimbKind::PPP:
                break;  // rejected by validate()
        }
        return splat<P>(0.0) != 0.0;
    }
};

/// The adjugate of a symmetric 3 x 3 matrix by its upper triangle (00 01 02 11 12 22), and
/// the determinant.
template <class S>
NOCDYN_ALWAYS_INLINE S symmetricAdjugate(const S* m, S* adj) {
    adj[0] = m[3] * m[5] - m[4] * m[4];
    adj[1] = m[2] * m[4] - m[1] * m[5];
    adj[2] = m[1] * m[4] - m[2] * m[3];
    adj[3] = m[0] * m[5] - m[2] * m[2];
    adj[4] = m[1] * m[2] - m[0] * m[4];
    adj[5] = m[0] * m[3] - m[1] * m[1];
    return m[0] * adj[0] + m[1] * adj[1] + m[2] * adj[2];
}
/// The 1-norm of a symmetric 3 x 3 matrix by its upper triangle.
template <class S>
NOCDYN_ALWAYS_INLINE S symmetricNorm1(const S* m) {
    return maxOf(maxOf(absOf(m[0]) + absOf(m[1]) + absOf(m[2]), absOf(m[1]) + absOf(m[3]) + absOf(m[4])),
                 absOf(m[2]) + absOf(m[4]) + absOf(m[5]));
}

/// A^T tau = W_P for the rows of A (the actuated rows of the J_j^-1) with their weights and
/// scales: A^-T W_P, or the minimum-norm solution; false (lane by lane) where the actuation
/// conditioning of jacobianStage fails (division-free).
template <bool kUnitWeights, class S>
NOCDYN_ALWAYS_INLINE Mask<S> actuation(const Model& model, V3<S>* rows, double* weight, double* scale, const V3<S>& W,
                                       const Out<S>& out) {
    Mask<S> ok = ik::yes<S>();
    const double L = model.length_scale;
    const double inv_L = 1.0 / L;
    const double max_condition = model.max_condition;
    const int n = model.actuators;
    if constexpr (kUnitWeights) std::fill(weight, weight + n, 1.0), std::fill(scale, scale + n, 1.0);
    if (model.coordinates == Coordinates::actuators) {
        const V3<S> b0 = cross(rows[1], rows[2]), b1 = cross(rows[2], rows[0]), b2 = cross(rows[0], rows[1]);
        const S det = dot(rows[0], b0);
        const S n_A = maxOf(
            weight[0] * absOf(rows[0].w) + weight[1] * absOf(rows[1].w) + weight[2] * absOf(rows[2].w),
            L * maxOf(weight[0] * absOf(rows[0].x) + weight[1] * absOf(rows[1].x) + weight[2] * absOf(rows[2].x),
                      weight[0] * absOf(rows[0].y) + weight[1] * absOf(rows[1].y) + weight[2] * absOf(rows[2].y)));
        const S n_adj = maxOf(maxOf((absOf(b0.w) + (absOf(b0.x) + absOf(b0.y)) * inv_L) * scale[0],
                                    (absOf(b1.w) + (absOf(b1.x) + absOf(b1.y)) * inv_L) * scale[1]),
                              (absOf(b2.w) + (absOf(b2.x) + absOf(b2.y)) * inv_L) * scale[2]);
        if (!pass<S>(ok, n_A * n_adj <= max_condition * absOf(det))) return ok;
        // tau = A^-T W_P: A^-1 has columns b_a / det
        const S inv_det = 1.0 / det;
        out.tau[0] = dot(b0, W) * inv_det;
        out.tau[out.stride] = dot(b1, W) * inv_det;
        out.tau[2 * out.stride] = dot(b2, W) * inv_det;
        return ok;
    }
    const S zero = splat<S>(0.0);
    if (model.task_dimension == 2) {
        // translation: A_E = A S(c) E, the x, y columns of A; cond_A^2 = cond_1(B) with
        // B = (L diag(w) A_E)^T (L diag(w) A_E), and the minimum-norm tau = A_E (A_E^T A_E)^-1 f_P,
        // f_P the force part of W_P (as jacobianStage and distribute)
        S B00 = zero, B01 = zero, B11 = zero, N00 = zero, N01 = zero, N11 = zero;
        for (int a = 0; a < n; ++a) {
            const V3<S>& ra = rows[a];
            N00 += ra.x * ra.x, N01 += ra.x * ra.y, N11 += ra.y * ra.y;
            const double wl = weight[a] * L;
            const S rx = wl * ra.x, ry = wl * ra.y;
            B00 += rx * rx, B01 += rx * ry, B11 += ry * ry;
        }
        const S det_B = B00 * B11 - B01 * B01;
        const S norm_B = maxOf(absOf(B00) + absOf(B01), absOf(B01) + absOf(B11));
        if (!pass<S>(ok, norm_B * norm_B <= max_condition * max_condition * absOf(det_B))) return ok;
        const S inv_det = 1.0 / (N00 * N11 - N01 * N01);
        const S lx = (N11 * W.x - N01 * W.y) * inv_det;
        const S ly = (N00 * W.y - N01 * W.x) * inv_det;
        for (int a = 0; a < n; ++a) out.tau[a * out.stride] = rows[a].x * lx + rows[a].y * ly;
        return ok;
    }
    // redundant: cond_A^2 = cond_1(B), B = As^T As, As = diag(w) A diag(1, L, L); and the
    // minimum-norm tau = A (A^T A)^-1 W_P
    S B[6] = {zero, zero, zero, zero, zero, zero};  // upper triangles 00 01 02 11 12 22
    S N[6] = {zero, zero, zero, zero, zero, zero};
    for (int a = 0; a < n; ++a) {
        const V3<S>& ra = rows[a];
        N[0] += ra.w * ra.w, N[1] += ra.w * ra.x, N[2] += ra.w * ra.y;
        N[3] += ra.x * ra.x, N[4] += ra.x * ra.y, N[5] += ra.y * ra.y;
        if constexpr (!kUnitWeights) {
            const double w2 = weight[a] * weight[a];
            B[0] += w2 * ra.w * ra.w, B[1] += w2 * ra.w * ra.x, B[2] += w2 * ra.w * ra.y;
            B[3] += w2 * ra.x * ra.x, B[4] += w2 * ra.x * ra.y, B[5] += w2 * ra.y * ra.y;
        }
    }
    // unit weights (R actuators): As^T As is A^T A itself, the same sums
    if constexpr (kUnitWeights) std::copy(N, N + 6, B);
    B[1] *= L, B[2] *= L, B[3] *= L * L, B[4] *= L * L, B[5] *= L * L;
    S adj_B[6], adj_N[6];
    const S det_B = symmetricAdjugate(B, adj_B);
    if (!pass<S>(ok, symmetricNorm1(B) * symmetricNorm1(adj_B) <= max_condition * max_condition * absOf(det_B)))
        return ok;
    const S det_N = symmetricAdjugate(N, adj_N);
    const S inv_det = 1.0 / det_N;
    const V3<S> lambda{(adj_N[0] * W.w + adj_N[1] * W.x + adj_N[2] * W.y) * inv_det,
                       (adj_N[1] * W.w + adj_N[3] * W.x + adj_N[4] * W.y) * inv_det,
                       (adj_N[2] * W.w + adj_N[4] * W.x + adj_N[5] * W.y) * inv_det};
    for (int a = 0; a < n; ++a) out.tau[a * out.stride] = dot(rows[a], lambda);
    return ok;
}

/// One sample (or packet) given cos and sin of dtheta = theta - home(0); p, dp, ddp finite;
/// the limbs' terms by `terms` (AnyLimb or UniformLimb).
/// False (lane by lane) where the per-sample path would fail (or is within rounding of a
/// threshold).
template <class Terms, class S>
NOCDYN_ALWAYS_INLINE Mask<S> sampleWith(const Model& model, const S& cos_dtheta, const S& sin_dtheta, const S* p,
                                        const S* dp, const S* ddp, const Out<S>& out, V3<S>& W, Terms terms) {
    // xi_P = S(c) t_M and its derivative
    const S cx = p[1], cy = p[2], w = dp[0];
    const PlatformMove<S> G{cos_dtheta, sin_dtheta, {cx, cy}};
    const V3<S> xi_P{w, dp[1] + w * cy, dp[2] - w * cx};
    const V3<S> xi_P_dot{ddp[0], ddp[1] + ddp[0] * cy + w * dp[2], ddp[2] - ddp[0] * cx - w * dp[1]};
    const double gx = model.gravity.x(), gy = model.gravity.y();
    const double L = model.length_scale;
    const double inv_L = 1.0 / L;
    const double max_condition = model.max_condition;

    V3<S> rows[kMaxActuators];     // rows of A: the actuated rows of the J_j^-1
    double weight[kMaxActuators];  // 1 / joint scale of each actuator, and the scale
    double scale[kMaxActuators];
    // W_P = sum_i T_i^{xi T} w_i: each limb's bodies through J_j^-T, the platform directly
    {
        const Vector2& com = model.platform_com_home;
        const S px = cx + G.cos_dtheta * com.x() - G.sin_dtheta * com.y();
        const S py = cy + G.sin_dtheta * com.x() + G.cos_dtheta * com.y();
        W = bodyWrench(model.platform_M.inertia, model.platform_M.mass, gx, gy, px, py, xi_P, xi_P_dot);
    }
    const Frame<S> frame{G, xi_P, xi_P_dot, gx, gy, L, inv_L, max_condition};
    Mask<S> ok = ik::yes<S>();
    for (int j = 0; j < model.limbs; ++j) {
        if (!pass<S>(ok, terms(j, model.limb[static_cast<std::size_t>(j)], frame, out, W, rows, weight, scale)))
            return ok;
    }
    if (!pass<S>(ok, actuation<Terms::kUnitWeights>(model, rows, weight, scale, W, out))) return ok;
    return ok;
}

/// The limbs of a uniform robot (Model::limbsInLanes) all at once, limb l in lane l of
/// one packet: the same kernel (limbTerms) as one limb, its constants read lane by lane.
/// One sample, given cos and sin of dtheta; false where sampleWith would be. Compiled per
/// limb kind K (the actuated joint read from the first limb: a packet is worth one branch).
template <LimbKind K>
NOCDYN_ALWAYS_INLINE bool sampleLanes(const Model& model, double cos_dtheta, double sin_dtheta, const double* p,
                                      const double* dp, const double* ddp, const Out<double>& out, V3<double>& W) {
    const double cx = p[1], cy = p[2], w = dp[0];
    const V3<double> xi_P{w, dp[1] + w * cy, dp[2] - w * cx};
    const V3<double> xi_P_dot{ddp[0], ddp[1] + ddp[0] * cy + w * dp[2], ddp[2] - ddp[0] * cx - w * dp[1]};
    const double gx = model.gravity.x(), gy = model.gravity.y();
    const double L = model.length_scale;
    {
        const Vector2& com = model.platform_com_home;
        const double px = cx + cos_dtheta * com.x() - sin_dtheta * com.y();
        const double py = cy + sin_dtheta * com.x() + cos_dtheta * com.y();
        W = bodyWrench(model.platform_M.inertia, model.platform_M.mass, gx, gy, px, py, xi_P, xi_P_dot);
    }
    const auto wide = [](const V3<double>& v) NOCDYN_INLINE_LAMBDA {
        return V3<Pack>{splat<Pack>(v.w), splat<Pack>(v.x), splat<Pack>(v.y)};
    };
    const Frame<Pack> frame{
        PlatformMove<Pack>{splat<Pack>(cos_dtheta), splat<Pack>(sin_dtheta), {splat<Pack>(cx), splat<Pack>(cy)}},
        wide(xi_P),
        wide(xi_P_dot),
        gx,
        gy,
        L,
        1.0 / L,
        model.max_condition};
    // written by the limbs' one actuated joint each (Model::uniform_limbs)
    Pack u{}, du{}, ddu{};
    V3<Pack> row{Pack{}, Pack{}, Pack{}};
    V3<Pack> W_limbs{Pack{}, Pack{}, Pack{}};
    double weight = 1.0, scale = 1.0;
    const Out<Pack> lane_out{&u, &du, &ddu, nullptr, 0};
    const Mask<Pack> ok = limbTerms<K, kAnyActuation>(LaneLimb{detail::ModelKernel::lanes(model), model.limb[0]}, frame,
                                                      lane_out, W_limbs, &row, &weight, &scale);
    // lanes past the last limb repeat limb 0: neither their test nor their share counts
    const int limbs = model.limbs;
    for (int j = 0; j < limbs; ++j) {
        if (ok[j] == 0) return false;
    }
    V3<double> rows[LimbLanes::kLanes];
    double weights[LimbLanes::kLanes], scales[LimbLanes::kLanes];
    for (int j = 0; j < limbs; ++j) {
        W.w += W_limbs.w[j], W.x += W_limbs.x[j], W.y += W_limbs.y[j];
        out.u[j * out.stride] = u[j];
        out.du[j * out.stride] = du[j];
        out.ddu[j * out.stride] = ddu[j];
        rows[j] = {row.w[j], row.x[j], row.y[j]};
        weights[j] = weight;
        scales[j] = scale;
    }
    return actuation<false>(model, rows, weights, scales, W, out);
}

template <int... kKinds>
NOCDYN_ALWAYS_INLINE bool sampleInLanes(const Model& model, double cos_dtheta, double sin_dtheta, const double* p,
                                        const double* dp, const double* ddp, const Out<double>& out, V3<double>& W,
                                        bool& ok, std::integer_sequence<int, kKinds...> /*kinds*/) {
    const int kind = model.uniform_limbs / 3;
    return (
        (kind == kKinds &&
         (ok = sampleLanes<static_cast<LimbKind>(kKinds)>(model, cos_dtheta, sin_dtheta, p, dp, ddp, out, W), true)) ||
        ...);
}

/// One sample: a robot with uniform limbs, at most four, runs its limbs in the lanes of a
/// packet (sampleLanes); any other, sampleWith with the per-limb dispatch. (The batch runs
/// packets of four samples through sampleWith, its limbs' terms chosen once per chunk.)
NOCDYN_ALWAYS_INLINE bool sample(const Model& model, double cos_dtheta, double sin_dtheta, const double* p,
                                 const double* dp, const double* ddp, const Out<double>& out, V3<double>& W) {
#if !NOCDYN_ASAN()
    // Under the sanitizers every robot takes the per-limb dispatch: the same template, the
    // fewest instantiations (the instrumented compile of the others takes many minutes).
    // The limbs in lanes, else the dispatch (the rare uniform robot with more than four
    // limbs, or friction at some of its limbs only).
    bool ok = false;
    if (model.limbsInLanes() && sampleInLanes(model, cos_dtheta, sin_dtheta, p, dp, ddp, out, W, ok,
                                              std::make_integer_sequence<int, static_cast<int>(LimbKind::PPP)>{}))
        return ok;
#endif
    return sampleWith(model, cos_dtheta, sin_dtheta, p, dp, ddp, out, W, AnyLimb{});
}

}  // namespace nocdyn::detail::lean

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
