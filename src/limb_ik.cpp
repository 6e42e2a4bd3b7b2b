// Closed-form inverse displacement per limb type (limb_ik.hpp).
#include "nocdyn/limb_ik.hpp"

#include <cmath>

namespace nocdyn {

namespace {

constexpr double kTiny = 1e-300;

[[nodiscard]] double dot(const Vector2& a, const Vector2& b) { return a.dot(b); }

/// cos and sin of the angle from a to b, both of squared length n2.
void angleBetween(const Vector2& a, const Vector2& b, double n2, double& c, double& s) {
    c = dot(a, b) / n2;
    s = cross(a, b) / n2;
}

/// cos and sin of dtheta - (angles already found) for the joint that closes the rotation.
void remainingAngle(const PlatformDisplacement& G, LimbData& out, int skip) {
    double c = G.cos_dtheta;
    double s = G.sin_dtheta;
    for (int k = 0; k < 3; ++k) {
        if (k == skip) continue;
        const double ck = out.cos_q(k);
        const double sk = out.sin_q(k);
        const double c_new = c * ck + s * sk;  // rotate by -q_k
        s = s * ck - c * sk;
        c = c_new;
    }
    out.cos_q(skip) = c;
    out.sin_q(skip) = s;
}

Status unreachable(int j, double by) { return {StatusCode::unreachable, j, by}; }
Status singular(int j) { return {StatusCode::singular_limb, j, std::numeric_limits<double>::infinity()}; }

/// RRR: the elbow P_2 where circle (r_1, L_1) meets circle (P_3 = G(r_3), L_2).
Status solveRRR(const LimbModel& limb, int j, const PlatformDisplacement& G, LimbData& out) {
    const Vector2& r1 = limb.point_home[0];
    const Vector2 P3 = G.apply(limb.point[2]);
    const Vector2 D = P3 - r1;
    const double d2 = D.squaredNorm();
    const double d = std::sqrt(d2);
    const double L1 = limb.length1;
    const double L2 = limb.length2;
    if (!(d > kTiny)) return singular(j);
    const double a = (L1 * L1 - L2 * L2 + d2) / (2.0 * d);
    const double h2 = (L1 - a) * (L1 + a);
    if (!(h2 >= 0.0)) return unreachable(j, d > L1 + L2 ? d - (L1 + L2) : std::abs(L1 - L2) - d);
    const double h = std::sqrt(h2);
    const Vector2 P2 = r1 + (a / d) * D + (limb.branch * h / d) * perp(D);
    angleBetween(limb.point_home[1] - r1, P2 - r1, L1 * L1, out.cos_q(0), out.sin_q(0));
    const Vector2 link = limb.point_home[2] - limb.point_home[1];
    const Vector2 turned(out.cos_q(0) * link.x() - out.sin_q(0) * link.y(),
                         out.sin_q(0) * link.x() + out.cos_q(0) * link.y());
    angleBetween(turned, P3 - P2, L2 * L2, out.cos_q(1), out.sin_q(1));
    remainingAngle(G, out, 2);
    return {};
}

/// PRR: the slider point P_2 = r_2 + q_1 d_1 at distance L_2 from P_3 = G(r_3) (the paper's limb).
Status solvePRR(const LimbModel& limb, int j, const PlatformDisplacement& G, LimbData& out) {
    const Vector2& d1 = limb.direction[0];
    const Vector2& r2 = limb.point_home[1];
    const Vector2 P3 = G.apply(limb.point[2]);
    const Vector2 w = P3 - r2;
    const double foot = dot(d1, w);
    const double delta = cross(d1, w);
    const double L2 = limb.length2;
    const double h2 = (L2 - delta) * (L2 + delta);
    if (!(h2 >= 0.0)) return unreachable(j, std::abs(delta) - L2);
    out.q(0) = foot - limb.branch * std::sqrt(h2);
    const Vector2 P2 = r2 + out.q(0) * d1;
    angleBetween(limb.point_home[2] - r2, P3 - P2, L2 * L2, out.cos_q(1), out.sin_q(1));
    remainingAngle(G, out, 2);
    return {};
}

/// RPR: in the first body's frame, r_3 slides along d_2 to distance |G(r_3) - r_1| from r_1.
Status solveRPR(const LimbModel& limb, int j, const PlatformDisplacement& G, LimbData& out) {
    const Vector2& r1 = limb.point_home[0];
    const Vector2& d2 = limb.direction[1];
    const Vector2 a = limb.point_home[2] - r1;
    const Vector2 W = G.apply(limb.point[2]) - r1;
    const double rho2 = W.squaredNorm();
    const double delta = cross(d2, a);
    const double h2 = rho2 - delta * delta;
    if (!(h2 >= 0.0)) return unreachable(j, std::abs(delta) - std::sqrt(rho2));
    if (!(rho2 > kTiny)) return singular(j);
    out.q(1) = -dot(a, d2) + limb.branch * std::sqrt(h2);
    angleBetween(a + out.q(1) * d2, W, rho2, out.cos_q(0), out.sin_q(0));
    remainingAngle(G, out, 2);
    return {};
}

/// RRP: the elbow P_2 = G(r_2) - q_3 Rot(dtheta) d_3 on the circle (r_1, L_1).
Status solveRRP(const LimbModel& limb, int j, const PlatformDisplacement& G, LimbData& out) {
    const Vector2& r1 = limb.point_home[0];
    const Vector2 Gr2 = G.apply(limb.point[1]);
    const Vector2 w = -G.rotate(limb.direction[2]);
    const double foot = dot(w, r1 - Gr2);
    const double delta = cross(w, Gr2 - r1);
    const double L1 = limb.length1;
    const double h2 = (L1 - delta) * (L1 + delta);
    if (!(h2 >= 0.0)) return unreachable(j, std::abs(delta) - L1);
    out.q(2) = foot + limb.branch * std::sqrt(h2);
    const Vector2 P2 = Gr2 + out.q(2) * w;
    angleBetween(limb.point_home[1] - r1, P2 - r1, L1 * L1, out.cos_q(0), out.sin_q(0));
    remainingAngle(G, out, 1);
    return {};
}

/// Two prismatic joints and one revolute: the angle is dtheta, q_a a + q_b b = rhs.
Status solveLinear(int j, const Vector2& a, const Vector2& b, const Vector2& rhs, double& qa, double& qb) {
    const double det = cross(a, b);
    if (!(std::abs(det) > 1e-12)) return singular(j);
    qa = cross(rhs, b) / det;
    qb = cross(a, rhs) / det;
    return {};
}

Status solvePRP(const LimbModel& limb, int j, const PlatformDisplacement& G, LimbData& out) {
    out.cos_q(1) = G.cos_dtheta;
    out.sin_q(1) = G.sin_dtheta;
    // G(r_2 - q_3 d_3) = r_2 + q_1 d_1
    return solveLinear(j, limb.direction[0], G.rotate(limb.direction[2]),
                       G.apply(limb.point[1]) - limb.point_home[1], out.q(0), out.q(2));
}

Status solveRPP(const LimbModel& limb, int j, const PlatformDisplacement& G, LimbData& out) {
    out.cos_q(0) = G.cos_dtheta;
    out.sin_q(0) = G.sin_dtheta;
    // G(r_1) = r_1 + Rot(dtheta) (q_2 d_2 + q_3 d_3)
    const Vector2 back = G.apply(limb.point[0]) - limb.point_home[0];
    const Vector2 rhs(G.cos_dtheta * back.x() + G.sin_dtheta * back.y(),
                      -G.sin_dtheta * back.x() + G.cos_dtheta * back.y());
    return solveLinear(j, limb.direction[1], limb.direction[2], rhs, out.q(1), out.q(2));
}

Status solvePPR(const LimbModel& limb, int j, const PlatformDisplacement& G, LimbData& out) {
    out.cos_q(2) = G.cos_dtheta;
    out.sin_q(2) = G.sin_dtheta;
    // G(r_3) = r_3 + q_1 d_1 + q_2 d_2
    return solveLinear(j, limb.direction[0], limb.direction[1],
                       G.apply(limb.point[2]) - limb.point_home[2], out.q(0), out.q(1));
}

}  // namespace

Status solveLimb(const LimbModel& limb, int j, const PlatformDisplacement& G, bool angles, LimbData& out) {
    out.cos_q.setOnes();
    out.sin_q.setZero();
    const bool r1 = limb.type[0] == JointType::revolute;
    const bool r2 = limb.type[1] == JointType::revolute;
    const bool r3 = limb.type[2] == JointType::revolute;
    Status status;
    if (r1 && r2 && r3) status = solveRRR(limb, j, G, out);
    else if (!r1 && r2 && r3) status = solvePRR(limb, j, G, out);
    else if (r1 && !r2 && r3) status = solveRPR(limb, j, G, out);
    else if (r1 && r2 && !r3) status = solveRRP(limb, j, G, out);
    else if (!r1 && r2 && !r3) status = solvePRP(limb, j, G, out);
    else if (r1 && !r2 && !r3) status = solveRPP(limb, j, G, out);
    else if (!r1 && !r2 && r3) status = solvePPR(limb, j, G, out);
    else status = singular(j);  // PPP is rejected by validate()
    if (!status) return status;
    for (int k = 0; k < 3; ++k) {
        if (limb.type[static_cast<std::size_t>(k)] != JointType::revolute) continue;
        if (angles || limb.actuator[static_cast<std::size_t>(k)] >= 0) {
            out.q(k) = std::atan2(out.sin_q(k), out.cos_q(k));
        }
    }
    return {};
}

int homeBranch(const LimbModel& limb) {
    const auto sign = [](double v) { return v > 0.0 ? 1 : (v < 0.0 ? -1 : 0); };
    const bool r1 = limb.type[0] == JointType::revolute;
    const bool r2 = limb.type[1] == JointType::revolute;
    const bool r3 = limb.type[2] == JointType::revolute;
    const auto& p = limb.point_home;
    const auto& d = limb.direction;
    if (r1 && r2 && r3) return sign(cross(p[2] - p[0], p[1] - p[0]));
    if (!r1 && r2 && r3) return sign(d[0].dot(p[2] - p[1]));
    if (r1 && !r2 && r3) return sign(d[1].dot(p[2] - p[0]));
    if (r1 && r2 && !r3) return sign(-d[2].dot(p[1] - p[0]));
    return 0;
}

}  // namespace nocdyn
