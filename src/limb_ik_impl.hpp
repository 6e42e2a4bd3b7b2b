// The closed-form inverse displacement of one limb per type (limb_ik.hpp), on plain arrays
// so that the lean path (dynamics.cpp) inlines it; solveLimb wraps it for LimbData.
// Internal (not installed).
#pragma once

#include <cmath>
#include <limits>

#include "nocdyn/limb_ik.hpp"

// The lean kernel must be inlined into the loops that call it (and into their AVX2 clones).
#if defined(__GNUC__)
#define NOCDYN_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define NOCDYN_ALWAYS_INLINE inline
#endif

namespace nocdyn::detail {

/// Joint variables of one limb: q (P joints, and R joints once their angle is wanted), and
/// cos q, sin q (R joints; 1 and 0 for P).
/// Trivial: the lean kernel fills only what its limb kind has; home() is q = 0 everywhere.
struct JointSolution {
    double q_[3];
    double c_[3];
    double s_[3];
    [[nodiscard]] static JointSolution home() { return {{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}}; }
    double& q(int k) { return q_[k]; }
    double& c(int k) { return c_[k]; }
    double& s(int k) { return s_[k]; }
    [[nodiscard]] double q(int k) const { return q_[k]; }
    [[nodiscard]] double c(int k) const { return c_[k]; }
    [[nodiscard]] double s(int k) const { return s_[k]; }
};

namespace ik {

/// The joint angle from its cosine and sine: atan2(y, x) for (x, y) != (0, 0), finite.
/// Branch-free and within 2 ulp of libm's (tested), about a third of its cost. fdlibm's
/// atan (s_atan.c): t = |y| / |x| is reduced by the breakpoints 7/16, 11/16, 19/16, 39/16
/// to r = (a t + b) / (c t + d) with |r| <= 7/16, so atan t = atan(t_k) + atan r, the latter
/// by an odd polynomial of degree 23; here r takes one division, (a|y| + b|x|) / (c|y| + d|x|).
/// Then the quadrant: pi - atan t for x < 0, the sign of y.
[[nodiscard]] inline double atan2Of(double y, double x) {
    const double ay = std::abs(y), ax = std::abs(x);
    // interval k of t = ay / ax, by comparisons free of division (t = inf when ax = 0)
    const int k = static_cast<int>(ay >= 0.4375 * ax) + static_cast<int>(ay >= 0.6875 * ax) +
                  static_cast<int>(ay >= 1.1875 * ax) + static_cast<int>(ay >= 2.4375 * ax);
    // r = (a t + b) / (c t + d): t; (2t - 1) / (2 + t); (t - 1) / (t + 1); (t - 1.5) / (1 + 1.5 t); -1 / t
    static constexpr double kA[5] = {1.0, 2.0, 1.0, 1.0, 0.0}, kB[5] = {0.0, -1.0, -1.0, -1.5, -1.0};
    static constexpr double kC[5] = {0.0, 1.0, 1.0, 1.5, 1.0}, kD[5] = {1.0, 2.0, 1.0, 1.0, 0.0};
    // atan(t_k) in two parts (hi + lo): 0, atan 0.5, atan 1, atan 1.5, pi / 2
    static constexpr double kHi[5] = {0.0, 4.63647609000806093515e-01, 7.85398163397448278999e-01,
                                      9.82793723247329054082e-01, 1.57079632679489655800e+00};
    static constexpr double kLo[5] = {0.0, 2.26987774529616870924e-17, 3.06161699786838301793e-17,
                                      1.39033110312309984516e-17, 6.12323399573676603587e-17};
    const double a = kA[k], b = kB[k], c = kC[k], d = kD[k], hi = kHi[k], lo = kLo[k];
    const double r = (a * ay + b * ax) / (c * ay + d * ax);
    const double z = r * r, w = z * z;
    const double s1 = z * (3.33333333333329318027e-01 +
                           w * (1.42857142725034663711e-01 +
                                w * (9.09088713343650656196e-02 +
                                     w * (6.66107313738753120669e-02 +
                                          w * (4.97687799461593236017e-02 + w * 1.62858201153657823623e-02)))));
    const double s2 =
        w *
        (-1.99999999998764832476e-01 +
         w * (-1.11111104054623557880e-01 +
              w * (-7.69187620504482999495e-02 + w * (-5.83357013379057348645e-02 + w * -3.65315727442169155270e-02))));
    const double t = hi - ((r * (s1 + s2) - lo) - r);  // atan(ay / ax) in [0, pi / 2]
    // x < 0: pi - t, pi = pi_hi + pi_lo
    const double q = x < 0.0 ? 3.1415926535897931160e+00 - (t - 1.2246467991473531772e-16) : t;
    return std::copysign(q, y);
}

constexpr double kTiny = 1e-300;

[[nodiscard]] inline double dot(const Vector2& a, const Vector2& b) { return a.dot(b); }

/// cos and sin of the angle from a to b, both of squared length 1 / inv_n2.
inline void angleBetween(const Vector2& a, const Vector2& b, double inv_n2, double& c, double& s) {
    c = dot(a, b) * inv_n2;
    s = cross(a, b) * inv_n2;
}

/// cos and sin of dtheta - (the angles of the R joints kRevolute...) for the joint `skip`
/// that closes the rotation (a P joint does not turn: nothing to take off for it).
template <int... kRevolute>
inline void remainingAngle(const PlatformDisplacement& G, JointSolution& out, int skip) {
    double c = G.cos_dtheta;
    double s = G.sin_dtheta;
    const auto turnBack = [&](int k) {
        const double ck = out.c(k);
        const double sk = out.s(k);
        const double c_new = c * ck + s * sk;  // rotate by -q_k
        s = s * ck - c * sk;
        c = c_new;
    };
    (turnBack(kRevolute), ...);
    out.c(skip) = c;
    out.s(skip) = s;
}

inline Status unreachable(int j, double by) { return {StatusCode::unreachable, j, by}; }
inline Status singular(int j) { return {StatusCode::singular_limb, j, std::numeric_limits<double>::infinity()}; }

/// RRR: the elbow P_2 where circle (r_1, L_1) meets circle (P_3 = G(r_3), L_2).
inline Status solveRRR(const LimbModel& limb, int j, const PlatformDisplacement& G, int branch, JointSolution& out) {
    const Vector2& r1 = limb.point_home[0];
    const Vector2 P3 = G.apply(limb.point[2]);
    const Vector2 D = P3 - r1;
    const double d2 = D.squaredNorm();
    const double d = std::sqrt(d2);
    const double L1 = limb.length1;
    const double L2 = limb.length2;
    if (!(d > kTiny)) return singular(j);
    const double inv_d = 1.0 / d;
    const double a = 0.5 * (L1 * L1 - L2 * L2 + d2) * inv_d;
    const double h2 = (L1 - a) * (L1 + a);
    if (!(h2 >= 0.0)) return unreachable(j, d > L1 + L2 ? d - (L1 + L2) : std::abs(L1 - L2) - d);
    const double h = std::sqrt(h2);
    const Vector2 P2 = r1 + (a * inv_d) * D + (branch * h * inv_d) * perp(D);
    angleBetween(limb.point_home[1] - r1, P2 - r1, limb.inv_length1_sq, out.c(0), out.s(0));
    const Vector2 link = limb.point_home[2] - limb.point_home[1];
    const Vector2 turned(out.c(0) * link.x() - out.s(0) * link.y(), out.s(0) * link.x() + out.c(0) * link.y());
    angleBetween(turned, P3 - P2, limb.inv_length2_sq, out.c(1), out.s(1));
    remainingAngle<0, 1>(G, out, 2);
    return {};
}

/// PRR: the slider point P_2 = r_2 + q_1 d_1 at distance L_2 from P_3 = G(r_3) (the paper's limb).
inline Status solvePRR(const LimbModel& limb, int j, const PlatformDisplacement& G, int branch, JointSolution& out) {
    const Vector2& d1 = limb.direction[0];
    const Vector2& r2 = limb.point_home[1];
    const Vector2 P3 = G.apply(limb.point[2]);
    const Vector2 w = P3 - r2;
    const double foot = dot(d1, w);
    const double delta = cross(d1, w);
    const double L2 = limb.length2;
    const double h2 = (L2 - delta) * (L2 + delta);
    if (!(h2 >= 0.0)) return unreachable(j, std::abs(delta) - L2);
    out.q(0) = foot - branch * std::sqrt(h2);
    const Vector2 P2 = r2 + out.q(0) * d1;
    angleBetween(limb.point_home[2] - r2, P3 - P2, limb.inv_length2_sq, out.c(1), out.s(1));
    remainingAngle<1>(G, out, 2);
    return {};
}

/// RPR: in the first body's frame, r_3 slides along d_2 to distance |G(r_3) - r_1| from r_1.
inline Status solveRPR(const LimbModel& limb, int j, const PlatformDisplacement& G, int branch, JointSolution& out) {
    const Vector2& r1 = limb.point_home[0];
    const Vector2& d2 = limb.direction[1];
    const Vector2 a = limb.point_home[2] - r1;
    const Vector2 W = G.apply(limb.point[2]) - r1;
    const double rho2 = W.squaredNorm();
    const double delta = cross(d2, a);
    const double h2 = rho2 - delta * delta;
    if (!(h2 >= 0.0)) return unreachable(j, std::abs(delta) - std::sqrt(rho2));
    if (!(rho2 > kTiny)) return singular(j);
    out.q(1) = -dot(a, d2) + branch * std::sqrt(h2);
    angleBetween(a + out.q(1) * d2, W, 1.0 / rho2, out.c(0), out.s(0));
    remainingAngle<0>(G, out, 2);
    return {};
}

/// RRP: the elbow P_2 = G(r_2) - q_3 Rot(dtheta) d_3 on the circle (r_1, L_1).
inline Status solveRRP(const LimbModel& limb, int j, const PlatformDisplacement& G, int branch, JointSolution& out) {
    const Vector2& r1 = limb.point_home[0];
    const Vector2 Gr2 = G.apply(limb.point[1]);
    const Vector2 w = -G.rotate(limb.direction[2]);
    const double foot = dot(w, r1 - Gr2);
    const double delta = cross(w, Gr2 - r1);
    const double L1 = limb.length1;
    const double h2 = (L1 - delta) * (L1 + delta);
    if (!(h2 >= 0.0)) return unreachable(j, std::abs(delta) - L1);
    out.q(2) = foot + branch * std::sqrt(h2);
    const Vector2 P2 = Gr2 + out.q(2) * w;
    angleBetween(limb.point_home[1] - r1, P2 - r1, limb.inv_length1_sq, out.c(0), out.s(0));
    remainingAngle<0>(G, out, 1);
    return {};
}

/// Two prismatic joints and one revolute: the angle is dtheta, q_a a + q_b b = rhs.
inline Status solveLinear(int j, const Vector2& a, const Vector2& b, const Vector2& rhs, double& qa, double& qb) {
    const double det = cross(a, b);
    if (!(std::abs(det) > 1e-12)) return singular(j);
    qa = cross(rhs, b) / det;
    qb = cross(a, rhs) / det;
    return {};
}

inline Status solvePRP(const LimbModel& limb, int j, const PlatformDisplacement& G, JointSolution& out) {
    out.c(1) = G.cos_dtheta;
    out.s(1) = G.sin_dtheta;
    // G(r_2 - q_3 d_3) = r_2 + q_1 d_1
    return solveLinear(j, limb.direction[0], G.rotate(limb.direction[2]), G.apply(limb.point[1]) - limb.point_home[1],
                       out.q(0), out.q(2));
}

inline Status solveRPP(const LimbModel& limb, int j, const PlatformDisplacement& G, JointSolution& out) {
    out.c(0) = G.cos_dtheta;
    out.s(0) = G.sin_dtheta;
    // G(r_1) = r_1 + Rot(dtheta) (q_2 d_2 + q_3 d_3)
    const Vector2 back = G.apply(limb.point[0]) - limb.point_home[0];
    const Vector2 rhs(G.cos_dtheta * back.x() + G.sin_dtheta * back.y(),
                      -G.sin_dtheta * back.x() + G.cos_dtheta * back.y());
    return solveLinear(j, limb.direction[1], limb.direction[2], rhs, out.q(1), out.q(2));
}

inline Status solvePPR(const LimbModel& limb, int j, const PlatformDisplacement& G, JointSolution& out) {
    out.c(2) = G.cos_dtheta;
    out.s(2) = G.sin_dtheta;
    // G(r_3) = r_3 + q_1 d_1 + q_2 d_2
    return solveLinear(j, limb.direction[0], limb.direction[1], G.apply(limb.point[2]) - limb.point_home[2], out.q(0),
                       out.q(1));
}

}  // namespace ik

using ik::atan2Of;

/// Solves limb `j` for its joint variables on `branch` (+1 or -1; ignored by the types with
/// one solution; limb.branch is the home branch). Angles of R joints are not computed: only
/// their cos and sin. Fails with unreachable or singular_limb.
NOCDYN_ALWAYS_INLINE Status solveJoints(const LimbModel& limb, int j, const PlatformDisplacement& G, int branch,
                                        JointSolution& out) {
    using namespace ik;
    switch (limb.kind) {
        case LimbKind::RRR:
            return solveRRR(limb, j, G, branch, out);
        case LimbKind::PRR:
            return solvePRR(limb, j, G, branch, out);
        case LimbKind::RPR:
            return solveRPR(limb, j, G, branch, out);
        case LimbKind::RRP:
            return solveRRP(limb, j, G, branch, out);
        case LimbKind::PRP:
            return solvePRP(limb, j, G, out);
        case LimbKind::RPP:
            return solveRPP(limb, j, G, out);
        case LimbKind::PPR:
            return solvePPR(limb, j, G, out);
        default:
            return singular(j);  // PPP is rejected by validate()
    }
}

/// solveLimb (limb_ik.hpp), inlined into the position stage.
NOCDYN_ALWAYS_INLINE Status solveLimbData(const LimbModel& limb, int j, const PlatformDisplacement& G, int branch,
                                          bool angles, LimbData& out) {
    JointSolution solution = JointSolution::home();
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
