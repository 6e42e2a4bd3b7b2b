// The closed-form inverse displacement of one limb per type (limb_ik.hpp), on a scalar S:
// a double (solveLimb, the position stage and the lean per-sample path) or a packet of four
// samples (the batch), branch-free so that a packet's lanes stay together; solveLimb wraps
// it for LimbData and turns a failure into its Status. Internal (not installed).
#pragma once

#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "nocdyn/detail/fast_math.hpp"
#include "limb_lanes.hpp"
#include "nocdyn/limb_ik.hpp"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace nocdyn::detail {

using fastmath::Mask;
using fastmath::splat;

/// Joint variables of one limb: q (P joints, and R joints once their angle is wanted), and
/// cos q, sin q (R joints; 1 and 0 for P).
/// Trivial: the lean kernel fills only what its limb kind has; home() is q = 0 everywhere.
template <class S = double>
struct JointSolution {
    S q_[3];
    S c_[3];
    S s_[3];
    [[nodiscard]] static JointSolution home() {
        const S zero = splat<S>(0.0), one = splat<S>(1.0);
        return {{zero, zero, zero}, {one, one, one}, {zero, zero, zero}};
    }
    S& q(int k) { return q_[k]; }
    S& c(int k) { return c_[k]; }
    S& s(int k) { return s_[k]; }
    [[nodiscard]] const S& q(int k) const { return q_[k]; }
    [[nodiscard]] const S& c(int k) const { return c_[k]; }
    [[nodiscard]] const S& s(int k) const { return s_[k]; }
};

/// Planar vectors, one per lane of a packet P: x() and y() as Vector2's.
template <class P>
struct PackVector2T {
    P x_, y_;
    [[nodiscard]] NOCDYN_ALWAYS_INLINE const P& x() const { return x_; }
    [[nodiscard]] NOCDYN_ALWAYS_INLINE const P& y() const { return y_; }
};
using PackVector2 = PackVector2T<fastmath::Pack>;
/// A planar vector of S: Eigen's Vector2 for one sample (its packed SSE arithmetic), a
/// PackVector2T for a packet.
template <class S>
using V2 = std::conditional_t<std::is_same_v<S, double>, Vector2, PackVector2T<S>>;

template <class P>
using PV = PackVector2T<P>;
template <class P>
NOCDYN_ALWAYS_INLINE PV<P> operator+(const PV<P>& a, const PV<P>& b) {
    return {a.x_ + b.x_, a.y_ + b.y_};
}
template <class P>
NOCDYN_ALWAYS_INLINE PV<P> operator-(const PV<P>& a, const PV<P>& b) {
    return {a.x_ - b.x_, a.y_ - b.y_};
}
template <class P>
NOCDYN_ALWAYS_INLINE PV<P> operator-(const PV<P>& a, const Vector2& b) {
    return {a.x_ - b.x(), a.y_ - b.y()};
}
template <class P>
NOCDYN_ALWAYS_INLINE PV<P> operator+(const Vector2& a, const PV<P>& b) {
    return {a.x() + b.x_, a.y() + b.y_};
}
template <class P>
NOCDYN_ALWAYS_INLINE PV<P> operator*(const P& k, const PV<P>& a) {
    return {k * a.x_, k * a.y_};
}
template <class P>
NOCDYN_ALWAYS_INLINE PV<P> operator-(const PV<P>& a) {
    return {-a.x_, -a.y_};
}
template <class P>
NOCDYN_ALWAYS_INLINE P dot(const PV<P>& a, const PV<P>& b) {
    return a.x_ * b.x_ + a.y_ * b.y_;
}
template <class P>
NOCDYN_ALWAYS_INLINE P dot(const Vector2& a, const PV<P>& b) {
    return a.x() * b.x_ + a.y() * b.y_;
}
NOCDYN_ALWAYS_INLINE double dot(const Vector2& a, const Vector2& b) { return a.dot(b); }
template <class P>
NOCDYN_ALWAYS_INLINE P cross(const PV<P>& a, const PV<P>& b) {
    return a.x_ * b.y_ - a.y_ * b.x_;
}
template <class P>
NOCDYN_ALWAYS_INLINE P cross(const Vector2& a, const PV<P>& b) {
    return a.x() * b.y_ - a.y() * b.x_;
}
template <class P>
NOCDYN_ALWAYS_INLINE P cross(const PV<P>& a, const Vector2& b) {
    return a.x_ * b.y() - a.y_ * b.x();
}
NOCDYN_ALWAYS_INLINE double cross(const Vector2& a, const Vector2& b) { return nocdyn::cross(a, b); }
template <class P>
NOCDYN_ALWAYS_INLINE PV<P> perp(const PV<P>& v) {
    return {-v.y_, v.x_};
}
NOCDYN_ALWAYS_INLINE Vector2 perp(const Vector2& v) { return nocdyn::perp(v); }
/// k a for a constant direction a.
NOCDYN_ALWAYS_INLINE Vector2 scaled(double k, const Vector2& a) { return k * a; }
template <fastmath::Packet P>
NOCDYN_ALWAYS_INLINE PV<P> scaled(const P& k, const Vector2& a) {
    return {k * a.x(), k * a.y()};
}
template <fastmath::Packet P>
NOCDYN_ALWAYS_INLINE PV<P> scaled(const P& k, const PV<P>& a) {
    return k * a;
}
/// a - b of two constant vectors (evaluated: not an Eigen expression).
NOCDYN_ALWAYS_INLINE Vector2 minus(const Vector2& a, const Vector2& b) { return a - b; }
template <class P>
NOCDYN_ALWAYS_INLINE PV<P> minus(const PV<P>& a, const PV<P>& b) {
    return a - b;
}
/// A constant vector as a V2<S>.
template <class S>
NOCDYN_ALWAYS_INLINE V2<S> vec(const Vector2& v) {
    if constexpr (std::is_same_v<S, double>) {
        return v;
    } else {
        return {splat<S>(v.x()), splat<S>(v.y())};
    }
}
template <class S, class P>
NOCDYN_ALWAYS_INLINE PV<P> vec(const PV<P>& v) {
    return v;
}

/// The limbs of a uniform robot lane by lane (limb_lanes.hpp, lane l = limb l). The kernels
/// read a limb's constants through the accessors below: as doubles and Vector2's from a
/// LimbModel, as packets of kN lanes from a LaneLimbOf<kN>, so that one kernel runs one limb
/// or every limb of a sample at once.
template <int kN>
struct LaneLimbOf {
    const LimbLanesOf<kN>& lanes;
    const LimbModel& first;  ///< limb 0: kind, joint scales and actuated joints, shared by all
};
using LaneLimb = LaneLimbOf<4>;
/// The packet of kN lanes.
template <int kN>
using PackOfLanes = std::conditional_t<kN == 8, fastmath::Pack8, fastmath::Pack>;

/// A lane array as a packet.
template <std::size_t kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<static_cast<int>(kN)> lanesOf(const std::array<double, kN>& a) {
    PackOfLanes<static_cast<int>(kN)> v;
    static_assert(sizeof v == sizeof a);
    std::memcpy(&v, a.data(), sizeof v);
    return v;
}
// NOLINTNEXTLINE(bugprone-return-const-ref-from-parameter): the identity over one lane, inlined
NOCDYN_ALWAYS_INLINE const LimbModel& modelOf(const LimbModel& limb) { return limb; }
template <int kN>
NOCDYN_ALWAYS_INLINE const LimbModel& modelOf(const LaneLimbOf<kN>& limb) {
    return limb.first;
}
NOCDYN_ALWAYS_INLINE const Vector2& pointOf(const LimbModel& limb, int k) {
    return limb.point[static_cast<std::size_t>(k)];
}
template <int kN>
NOCDYN_ALWAYS_INLINE PV<PackOfLanes<kN>> pointOf(const LaneLimbOf<kN>& limb, int k) {
    const auto kk = static_cast<std::size_t>(k);
    return {lanesOf(limb.lanes.point_x[kk]), lanesOf(limb.lanes.point_y[kk])};
}
NOCDYN_ALWAYS_INLINE const Vector2& pointHomeOf(const LimbModel& limb, int k) {
    return limb.point_home[static_cast<std::size_t>(k)];
}
template <int kN>
NOCDYN_ALWAYS_INLINE PV<PackOfLanes<kN>> pointHomeOf(const LaneLimbOf<kN>& limb, int k) {
    const auto kk = static_cast<std::size_t>(k);
    return {lanesOf(limb.lanes.point_home_x[kk]), lanesOf(limb.lanes.point_home_y[kk])};
}
NOCDYN_ALWAYS_INLINE const Vector2& directionOf(const LimbModel& limb, int k) {
    return limb.direction[static_cast<std::size_t>(k)];
}
template <int kN>
NOCDYN_ALWAYS_INLINE PV<PackOfLanes<kN>> directionOf(const LaneLimbOf<kN>& limb, int k) {
    const auto kk = static_cast<std::size_t>(k);
    return {lanesOf(limb.lanes.direction_x[kk]), lanesOf(limb.lanes.direction_y[kk])};
}
NOCDYN_ALWAYS_INLINE double length1Of(const LimbModel& limb) { return limb.length1; }
template <int kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<kN> length1Of(const LaneLimbOf<kN>& limb) {
    return lanesOf(limb.lanes.length1);
}
NOCDYN_ALWAYS_INLINE double length2Of(const LimbModel& limb) { return limb.length2; }
template <int kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<kN> length2Of(const LaneLimbOf<kN>& limb) {
    return lanesOf(limb.lanes.length2);
}
NOCDYN_ALWAYS_INLINE double invLength1SqOf(const LimbModel& limb) { return limb.inv_length1_sq; }
template <int kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<kN> invLength1SqOf(const LaneLimbOf<kN>& limb) {
    return lanesOf(limb.lanes.inv_length1_sq);
}
NOCDYN_ALWAYS_INLINE double invLength2SqOf(const LimbModel& limb) { return limb.inv_length2_sq; }
template <int kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<kN> invLength2SqOf(const LaneLimbOf<kN>& limb) {
    return lanesOf(limb.lanes.inv_length2_sq);
}
/// The home branch, as the sign the closed forms take.
NOCDYN_ALWAYS_INLINE int branchOf(const LimbModel& limb) { return limb.branch; }
template <int kN>
NOCDYN_ALWAYS_INLINE PackOfLanes<kN> branchOf(const LaneLimbOf<kN>& limb) {
    return lanesOf(limb.lanes.branch);
}
NOCDYN_ALWAYS_INLINE double branchSign(int branch) { return static_cast<double>(branch); }
template <fastmath::Packet P>
NOCDYN_ALWAYS_INLINE const P& branchSign(const P& branch) {
    return branch;  // NOLINT(bugprone-return-const-ref-from-parameter): the identity over packets
}

/// The platform's displacement from home on S (limb_ik.hpp, PlatformDisplacement):
/// x -> Rot(dtheta) x + C.
template <class S>
struct PlatformMove {
    S cos_dtheta, sin_dtheta;
    V2<S> C;
    template <class V>
    [[nodiscard]] NOCDYN_ALWAYS_INLINE V2<S> rotate(const V& v) const {
        return {cos_dtheta * v.x() - sin_dtheta * v.y(), sin_dtheta * v.x() + cos_dtheta * v.y()};
    }
    template <class V>
    [[nodiscard]] NOCDYN_ALWAYS_INLINE V2<S> apply(const V& x) const {
        return rotate(x) + C;
    }
};

NOCDYN_ALWAYS_INLINE PlatformMove<double> displacement(const PlatformDisplacement& G) {
    return {G.cos_dtheta, G.sin_dtheta, {G.C.x(), G.C.y()}};
}

/// The outcome of a closed form: `regular` false when the limb is singular, `reach` false
/// when the pose is out of its reach, by `miss` [m]. Singular is reported first.
template <class S>
struct Closure {
    Mask<S> regular;
    Mask<S> reach;
    S miss;
};

namespace ik {

using fastmath::atan2Of;

constexpr double kTiny = 1e-300;

template <class S>
NOCDYN_ALWAYS_INLINE Mask<S> yes() {
    return splat<S>(0.0) == 0.0;
}

/// cos and sin of the angle from a to b, both of squared length 1 / inv_n2.
template <class S, class A, class N>
NOCDYN_ALWAYS_INLINE void angleBetween(const A& a, const V2<S>& b, const N& inv_n2, S& c, S& s) {
    c = dot(a, b) * inv_n2;
    s = cross(a, b) * inv_n2;
}

/// cos and sin of dtheta - (the angles of the R joints kRevolute...) for the joint `skip`
/// that closes the rotation (a P joint does not turn: nothing to take off for it).
template <int... kRevolute, class S>
NOCDYN_ALWAYS_INLINE void remainingAngle(const PlatformMove<S>& G, JointSolution<S>& out, int skip) {
    S c = G.cos_dtheta;
    S s = G.sin_dtheta;
    const auto turnBack = [&](int k) NOCDYN_INLINE_LAMBDA {
        const S ck = out.c(k);
        const S sk = out.s(k);
        const S c_new = c * ck + s * sk;  // rotate by -q_k
        s = s * ck - c * sk;
        c = c_new;
    };
    (turnBack(kRevolute), ...);
    out.c(skip) = c;
    out.s(skip) = s;
}

/// RRR: the elbow P_2 where circle (r_1, L_1) meets circle (P_3 = G(r_3), L_2).
template <class S, class LM, class B>
NOCDYN_ALWAYS_INLINE Closure<S> solveRRR(const LM& limb, const PlatformMove<S>& G, const B& branch,
                                         JointSolution<S>& out) {
    using fastmath::absOf, fastmath::select, fastmath::sqrtOf;
    const auto& r1 = pointHomeOf(limb, 0);
    const V2<S> P3 = G.apply(pointOf(limb, 2));
    const V2<S> D = P3 - r1;
    const S d2 = dot(D, D);
    const S d = sqrtOf(d2);
    const auto L1 = length1Of(limb);
    const auto L2 = length2Of(limb);
    const S inv_d = 1.0 / d;
    const S a = 0.5 * (L1 * L1 - L2 * L2 + d2) * inv_d;
    const S h2 = (L1 - a) * (L1 + a);
    const Closure<S> result{d > kTiny, h2 >= 0.0, select(d > L1 + L2, d - (L1 + L2), absOf(L1 - L2) - d)};
    const S h = sqrtOf(h2);
    const V2<S> P2 = (r1 + (a * inv_d) * D) + (branchSign(branch) * h * inv_d) * perp(D);
    angleBetween<S>(minus(pointHomeOf(limb, 1), r1), P2 - r1, invLength1SqOf(limb), out.c(0), out.s(0));
    const auto link = minus(pointHomeOf(limb, 2), pointHomeOf(limb, 1));
    const V2<S> turned{out.c(0) * link.x() - out.s(0) * link.y(), out.s(0) * link.x() + out.c(0) * link.y()};
    angleBetween<S>(turned, P3 - P2, invLength2SqOf(limb), out.c(1), out.s(1));
    remainingAngle<0, 1>(G, out, 2);
    return result;
}

/// PRR: the slider point P_2 = r_2 + q_1 d_1 at distance L_2 from P_3 = G(r_3) (the paper's limb).
template <class S, class LM, class B>
NOCDYN_ALWAYS_INLINE Closure<S> solvePRR(const LM& limb, const PlatformMove<S>& G, const B& branch,
                                         JointSolution<S>& out) {
    using fastmath::absOf, fastmath::sqrtOf;
    const auto& d1 = directionOf(limb, 0);
    const auto& r2 = pointHomeOf(limb, 1);
    const V2<S> P3 = G.apply(pointOf(limb, 2));
    const V2<S> w = P3 - r2;
    const S foot = dot(d1, w);
    const S delta = cross(d1, w);
    const auto L2 = length2Of(limb);
    const S h2 = (L2 - delta) * (L2 + delta);
    const Closure<S> result{yes<S>(), h2 >= 0.0, absOf(delta) - L2};
    out.q(0) = foot - branchSign(branch) * sqrtOf(h2);
    const V2<S> P2 = r2 + scaled(out.q(0), d1);
    angleBetween<S>(minus(pointHomeOf(limb, 2), r2), P3 - P2, invLength2SqOf(limb), out.c(1), out.s(1));
    remainingAngle<1>(G, out, 2);
    return result;
}

/// RPR: in the first body's frame, r_3 slides along d_2 to distance |G(r_3) - r_1| from r_1.
template <class S, class LM, class B>
NOCDYN_ALWAYS_INLINE Closure<S> solveRPR(const LM& limb, const PlatformMove<S>& G, const B& branch,
                                         JointSolution<S>& out) {
    using fastmath::absOf, fastmath::sqrtOf;
    const auto& r1 = pointHomeOf(limb, 0);
    const auto& d2 = directionOf(limb, 1);
    const auto a = minus(pointHomeOf(limb, 2), r1);
    const V2<S> W = G.apply(pointOf(limb, 2)) - r1;
    const S rho2 = dot(W, W);
    const auto delta = cross(d2, a);
    const S h2 = rho2 - delta * delta;
    const auto reach = h2 >= 0.0;
    // out of reach is reported first: the limb is singular only where it reaches
    const Closure<S> result{static_cast<Mask<S>>((rho2 > kTiny) | fastmath::notOf(reach)), reach,
                            absOf(delta) - sqrtOf(rho2)};
    out.q(1) = -dot(a, d2) + branchSign(branch) * sqrtOf(h2);
    angleBetween<S>(vec<S>(a) + scaled(out.q(1), d2), W, 1.0 / rho2, out.c(0), out.s(0));
    remainingAngle<0>(G, out, 2);
    return result;
}

/// RRP: the elbow P_2 = G(r_2) - q_3 Rot(dtheta) d_3 on the circle (r_1, L_1).
template <class S, class LM, class B>
NOCDYN_ALWAYS_INLINE Closure<S> solveRRP(const LM& limb, const PlatformMove<S>& G, const B& branch,
                                         JointSolution<S>& out) {
    using fastmath::absOf, fastmath::sqrtOf;
    const auto& r1 = pointHomeOf(limb, 0);
    const V2<S> Gr2 = G.apply(pointOf(limb, 1));
    const V2<S> w = -G.rotate(directionOf(limb, 2));
    const S foot = -dot(w, Gr2 - r1);
    const S delta = cross(w, Gr2 - r1);
    const auto L1 = length1Of(limb);
    const S h2 = (L1 - delta) * (L1 + delta);
    const Closure<S> result{yes<S>(), h2 >= 0.0, absOf(delta) - L1};
    out.q(2) = foot + branchSign(branch) * sqrtOf(h2);
    const V2<S> P2 = Gr2 + out.q(2) * w;
    angleBetween<S>(minus(pointHomeOf(limb, 1), r1), P2 - r1, invLength1SqOf(limb), out.c(0), out.s(0));
    remainingAngle<0>(G, out, 1);
    return result;
}

/// Two prismatic joints and one revolute: the angle is dtheta, q_a a + q_b b = rhs.
template <class S, class A, class B>
NOCDYN_ALWAYS_INLINE Closure<S> solveLinear(const A& a, const B& b, const V2<S>& rhs, S& qa, S& qb) {
    using fastmath::absOf;
    const S det = cross(a, b) + splat<S>(0.0);
    qa = cross(rhs, b) / det;
    qb = cross(a, rhs) / det;
    return {absOf(det) > 1e-12, yes<S>(), splat<S>(0.0)};
}

template <class S, class LM>
NOCDYN_ALWAYS_INLINE Closure<S> solvePRP(const LM& limb, const PlatformMove<S>& G, JointSolution<S>& out) {
    out.c(1) = G.cos_dtheta;
    out.s(1) = G.sin_dtheta;
    // G(r_2 - q_3 d_3) = r_2 + q_1 d_1
    return solveLinear<S>(directionOf(limb, 0), G.rotate(directionOf(limb, 2)),
                          G.apply(pointOf(limb, 1)) - pointHomeOf(limb, 1), out.q(0), out.q(2));
}

template <class S, class LM>
NOCDYN_ALWAYS_INLINE Closure<S> solveRPP(const LM& limb, const PlatformMove<S>& G, JointSolution<S>& out) {
    out.c(0) = G.cos_dtheta;
    out.s(0) = G.sin_dtheta;
    // G(r_1) = r_1 + Rot(dtheta) (q_2 d_2 + q_3 d_3)
    const V2<S> back = G.apply(pointOf(limb, 0)) - pointHomeOf(limb, 0);
    const V2<S> rhs{G.cos_dtheta * back.x() + G.sin_dtheta * back.y(),
                    -G.sin_dtheta * back.x() + G.cos_dtheta * back.y()};
    return solveLinear<S>(directionOf(limb, 1), directionOf(limb, 2), rhs, out.q(1), out.q(2));
}

template <class S, class LM>
NOCDYN_ALWAYS_INLINE Closure<S> solvePPR(const LM& limb, const PlatformMove<S>& G, JointSolution<S>& out) {
    out.c(2) = G.cos_dtheta;
    out.s(2) = G.sin_dtheta;
    // G(r_3) = r_3 + q_1 d_1 + q_2 d_2
    return solveLinear<S>(directionOf(limb, 0), directionOf(limb, 1), G.apply(pointOf(limb, 2)) - pointHomeOf(limb, 2),
                          out.q(0), out.q(1));
}

/// The closed form of limb kind K on `branch` (of a LimbModel, or of every limb of a
/// LaneLimb: then lane by lane).
template <LimbKind K, class S, class LM, class B>
NOCDYN_ALWAYS_INLINE Closure<S> solveKind(const LM& limb, const PlatformMove<S>& G, const B& branch,
                                          JointSolution<S>& js) {
    if constexpr (K == LimbKind::RRR)
        return solveRRR(limb, G, branch, js);
    else if constexpr (K == LimbKind::PRR)
        return solvePRR(limb, G, branch, js);
    else if constexpr (K == LimbKind::RPR)
        return solveRPR(limb, G, branch, js);
    else if constexpr (K == LimbKind::RRP)
        return solveRRP(limb, G, branch, js);
    else if constexpr (K == LimbKind::PRP)
        return solvePRP(limb, G, js);
    else if constexpr (K == LimbKind::RPP)
        return solveRPP(limb, G, js);
    else
        return solvePPR(limb, G, js);
}

/// The Status of a closed form's outcome for limb j.
inline Status status(const Closure<double>& c, int j) {
    if (!c.regular) return {StatusCode::singular_limb, j, std::numeric_limits<double>::infinity()};
    if (!c.reach) return {StatusCode::unreachable, j, c.miss};
    return {};
}

}  // namespace ik

using fastmath::atan2Of;

/// Solves limb `j` for its joint variables on `branch` (+1 or -1; ignored by the types with
/// one solution; limb.branch is the home branch). Angles of R joints are not computed: only
/// their cos and sin. Fails with unreachable or singular_limb.
NOCDYN_ALWAYS_INLINE Status solveJoints(const LimbModel& limb, int j, const PlatformDisplacement& P, int branch,
                                        JointSolution<double>& out) {
    using ik::solveKind;
    const PlatformMove<double> G = displacement(P);
    switch (limb.kind) {
        case LimbKind::RRR:
            return ik::status(solveKind<LimbKind::RRR>(limb, G, branch, out), j);
        case LimbKind::PRR:
            return ik::status(solveKind<LimbKind::PRR>(limb, G, branch, out), j);
        case LimbKind::RPR:
            return ik::status(solveKind<LimbKind::RPR>(limb, G, branch, out), j);
        case LimbKind::RRP:
            return ik::status(solveKind<LimbKind::RRP>(limb, G, branch, out), j);
        case LimbKind::PRP:
            return ik::status(solveKind<LimbKind::PRP>(limb, G, branch, out), j);
        case LimbKind::RPP:
            return ik::status(solveKind<LimbKind::RPP>(limb, G, branch, out), j);
        case LimbKind::PPR:
            return ik::status(solveKind<LimbKind::PPR>(limb, G, branch, out), j);
        default:
            return {StatusCode::singular_limb, j,
                    std::numeric_limits<double>::infinity()};  // PPP: validate() rejects it
    }
}

/// solveLimb (limb_ik.hpp), inlined into the position stage.
NOCDYN_ALWAYS_INLINE Status solveLimbData(const LimbModel& limb, int j, const PlatformDisplacement& G, int branch,
                                          bool angles, LimbData& out) {
    JointSolution<double> solution = JointSolution<double>::home();
    if (const Status status = solveJoints(limb, j, G, branch, solution); !status) return status;
    for (int k = 0; k < 3; ++k) {
        out.q(k) = solution.q(k);
        out.cos_q(k) = solution.c(k);
        out.sin_q(k) = solution.s(k);
        if (limb.type[static_cast<std::size_t>(k)] != JointType::revolute) continue;
        if (angles || limb.actuator[static_cast<std::size_t>(k)] >= 0) out.q(k) = atan2Of(out.sin_q(k), out.cos_q(k));
    }
    return {};
}

}  // namespace nocdyn::detail

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
