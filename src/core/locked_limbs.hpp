// The constraints of the locked limbs (direct_kinematics.hpp): with its actuated joints
// locked, each limb restricts the platform's displacement by a_j scalar equations
// kappa |C|^2 + a(phi) . C + b(phi) = 0, or phi = phi0. Shared by the all-modes solver and
// the tracker. Internal (not installed).
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "nocdyn/model.hpp"
#include "nocdyn/detail/fast_math.hpp"
#include "stages.hpp"

namespace nocdyn::detail::locked {

inline constexpr double kPi = std::numbers::pi;

/// Angle in (-pi, pi].
inline double wrapAngle(double a) {
    a = std::remainder(a, 2.0 * kPi);
    return a <= -kPi ? a + 2.0 * kPi : a;
}

/// cos x and sin x: inline, without a call (detail/fast_math.hpp, sinCos: within an ulp or so of libm's,
/// its reduction exact for |x| < 1.6e6), libm's beyond. The equations need them only to
/// round-off: the tracker verifies its pose by inverse displacement.
inline void cosSin(double x, double& c, double& s) {
    if (std::abs(x) < 1.0e6) [[likely]] {
        fastmath::sinCos(x, s, c);
    } else {
        c = std::cos(x);
        s = std::sin(x);
    }
}

/// g^-1: x -> Rot^T (x - t).
inline Displacement inverse(const Displacement& g) {
    const Displacement back{g.c, -g.s, Vector2::Zero()};
    return {g.c, -g.s, -back.rotate(g.t)};
}

/// exp of joint k's home screw times q: a rotation about r_k or a translation along d_k.
inline Displacement jointMotion(const LimbModel& limb, int k, double q) {
    const auto kk = static_cast<std::size_t>(k);
    if (limb.type[kk] == JointType::prismatic) return {1.0, 0.0, q * limb.direction[kk]};
    Displacement g;
    cosSin(q, g.c, g.s);
    g.t = limb.point_home[kk] - g.rotate(limb.point_home[kk]);
    return g;
}

/// k + c cos(phi) + s sin(phi). Trivial (not zeroed unless value-initialized): the tracker
/// builds a set of equations per step.
struct Trig {
    double k, c, s;
    [[nodiscard]] double at(double cs, double sn) const { return k + c * cs + s * sn; }
    [[nodiscard]] double derivative(double cs, double sn) const { return s * cs - c * sn; }
    Trig operator-(const Trig& o) const { return {k - o.k, c - o.c, s - o.s}; }
};

/// kappa |C|^2 + a(phi) . C + b(phi) = 0 (C over the length scale), or phi = phi0.
struct Equation {
    bool orientation;
    double phi0;
    double kappa;
    Trig ax, ay, b;

    Equation operator-(const Equation& o) const { return {false, 0.0, kappa - o.kappa, ax - o.ax, ay - o.ay, b - o.b}; }
};

/// Every locked limb gives one equation per actuated joint.
struct Equations {
    std::array<Equation, kMaxActuators> eq;  ///< the first `count` are set
    int count = 0;
    void add(const Equation& e) {
        if (count < kMaxActuators) eq[static_cast<std::size_t>(count++)] = e;
    }
};

/// Platform point P (from C, home axes) on the base line through B normal to n:
/// n . (Rot(phi) P + C - B) = 0.
inline Equation pointOnLine(const Vector2& n, const Vector2& P, const Vector2& B) {
    return {false, 0.0, 0.0, {n.x(), 0.0, 0.0}, {n.y(), 0.0, 0.0}, {-n.dot(B), n.dot(P), cross(P, n)}};
}

/// Base point B on the platform line through P (from C, home axes) normal to m (home axes):
/// (Rot(phi) m) . (B - C) - m . P = 0.
inline Equation lineThroughPoint(const Vector2& m, const Vector2& P, const Vector2& B) {
    return {false, 0.0, 0.0, {0.0, -m.x(), m.y()}, {0.0, -m.y(), -m.x()}, {-m.dot(P), m.dot(B), cross(m, B)}};
}

/// Platform point P at distance rho from base point B: |Rot(phi) P + C - B|^2 = rho^2.
inline Equation circle(const Vector2& P, const Vector2& B, double rho) {
    return {false,
            0.0,
            1.0,
            {-2.0 * B.x(), 2.0 * P.x(), -2.0 * P.y()},
            {-2.0 * B.y(), 2.0 * P.y(), 2.0 * P.x()},
            {P.squaredNorm() + B.squaredNorm() - rho * rho, -2.0 * B.dot(P), -2.0 * cross(P, B)}};
}

inline Equation orientation(const Displacement& g) {
    Equation e{};
    e.orientation = true;
    e.phi0 = std::atan2(g.s, g.c);
    return e;
}

/// The equations of every locked limb (see the header), lengths over L. Only the actuated
/// joints move in a locked limb: the products of the locked motions before, between and
/// after the passive joints compose those alone (an empty product is the identity, applied
/// as such), and a length between two passive R joints with no actuated joint between them
/// is the limb's constant length1 or length2.
inline void lockedLimbEquations(const Model& model, const ActuatorVector& u, Equations& out) {
    const double inv_L = 1.0 / model.length_scale;
    const Vector2 C_home = model.home.tail<2>();
    const Vector2 ex = Vector2::UnitX(), ey = Vector2::UnitY();
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        const auto type = [&](int k) { return limb.type[static_cast<std::size_t>(k)]; };
        const auto point = [&](int k) { return limb.point_home[static_cast<std::size_t>(k)]; };
        const auto direction = [&](int k) { return limb.direction[static_cast<std::size_t>(k)]; };
        if (limb.actuator[0] >= 0 && limb.actuator[1] < 0 && limb.actuator[2] < 0 && type(1) == JointType::revolute &&
            type(2) == JointType::revolute) {
            // the base joint alone locked (?RR, e.g. the paper's PRR and an RRR driven at the
            // base): the platform point r_3 (fixed to C) at the distance length2 from the
            // elbow B = F_1(r_2), whatever F_1 is; circle() with its constants worked out
            const double q = u(limb.actuator[0]);
            const Vector2& r2 = point(1);
            double Bx = 0.0, By = 0.0;
            if (type(0) == JointType::revolute) {
                double c = 1.0, sn = 0.0;
                cosSin(q, c, sn);
                const Vector2& r1 = point(0);
                const double dx = r2.x() - r1.x(), dy = r2.y() - r1.y();
                Bx = r1.x() + c * dx - sn * dy;
                By = r1.y() + sn * dx + c * dy;
            } else {
                Bx = r2.x() + q * direction(0).x();
                By = r2.y() + q * direction(0).y();
            }
            Bx *= inv_L, By *= inv_L;
            const double Px = (point(2).x() - C_home.x()) * inv_L, Py = (point(2).y() - C_home.y()) * inv_L;
            const double rho = limb.length2 * inv_L;
            if (out.count < kMaxActuators) {
                out.eq[static_cast<std::size_t>(out.count++)] = {
                    false,
                    0.0,
                    1.0,
                    {-2.0 * Bx, 2.0 * Px, -2.0 * Py},
                    {-2.0 * By, 2.0 * Py, 2.0 * Px},
                    {(Px * Px + Py * Py) + (Bx * Bx + By * By) - rho * rho, -2.0 * (Bx * Px + By * Py),
                     -2.0 * (Px * By - Py * Bx)}};
            }
            continue;
        }
        std::array<int, 3> passive{};
        unsigned locked = 0;  // bit k: joint k actuated (locked)
        int n_passive = 0;
        for (int k = 0; k < 3; ++k) {
            if (limb.actuator[static_cast<std::size_t>(k)] >= 0) {
                locked |= 1U << static_cast<unsigned>(k);
            } else {
                passive[static_cast<std::size_t>(n_passive++)] = k;
            }
        }
        if (n_passive == 3) continue;
        // the locked joints' motions; whether joints from..to-1 hold a locked one, and their product
        std::array<Displacement, 3> F;
        for (int k = 0; k < 3; ++k) {
            if (const int a = limb.actuator[static_cast<std::size_t>(k)]; a >= 0) {
                F[static_cast<std::size_t>(k)] = jointMotion(limb, k, u(a));
            }
        }
        const auto moves = [&](int from, int to) {
            return (locked & ((1U << static_cast<unsigned>(to)) - (1U << static_cast<unsigned>(from)))) != 0U;
        };
        const auto product = [&](int from, int to) {
            Displacement g;
            bool first = true;
            for (int k = from; k < to; ++k) {
                if ((locked & (1U << static_cast<unsigned>(k))) == 0U) continue;
                g = first ? F[static_cast<std::size_t>(k)] : g.then(F[static_cast<std::size_t>(k)]);
                first = false;
            }
            return g;
        };
        const auto scaled = [&](const Vector2& x) -> Vector2 { return inv_L * x; };
        if (n_passive == 0) {
            // D = F_1 F_2 F_3: the orientation and C = D(C_home)
            const Displacement L = product(0, 3);
            out.add(orientation(L));
            out.add(pointOnLine(ex, Vector2::Zero(), scaled(L.apply(C_home))));
            out.add(pointOnLine(ey, Vector2::Zero(), scaled(L.apply(C_home))));
            continue;
        }
        if (n_passive == 1) {
            // D = Lf exp(s_a q) Rf
            const int a = passive[0];
            const Displacement Lf = product(0, a), Rf = product(a + 1, 3);
            if (type(a) == JointType::revolute) {
                // the platform point on the joint's axis stays on its base position Lf(r_a)
                const Vector2 P = scaled(inverse(Rf).apply(point(a)) - C_home);
                const Vector2 B = scaled(Lf.apply(point(a)));
                out.add(pointOnLine(ex, P, B));
                out.add(pointOnLine(ey, P, B));
            } else {
                // a translation along Rot(Lf) d_a: the orientation of Lf Rf, C_home on a line
                const Displacement LR = Lf.then(Rf);
                out.add(orientation(LR));
                out.add(pointOnLine(perp(Lf.rotate(direction(a))), Vector2::Zero(), scaled(LR.apply(C_home))));
            }
            continue;
        }
        // two passive joints a < b: D = Lf exp(s_a q_a) exp(s_b' q_b) Rt, s_b' = Mf s_b; the one
        // locked joint is before a (Lf), between a and b (Mf = Rt) or after b (Rt)
        const int a = passive[0], b = passive[1];
        const bool between = moves(a + 1, b);
        const Displacement Lf = product(0, a), Rt = product(a + 1, 3);
        const Displacement Rt_inv = inverse(Rt);
        const Displacement Mf = between ? Rt : Displacement{};
        const bool ra = type(a) == JointType::revolute, rb = type(b) == JointType::revolute;
        if (ra && rb) {
            const Vector2 beta = between ? Mf.apply(point(b)) : point(b);
            // |r_b - r_a| of adjacent joints is the limb's length1 (0, 1) or length2 (1, 2)
            const double rho = between ? (beta - point(a)).norm() : (a == 0 ? limb.length1 : limb.length2);
            out.add(circle(scaled(Rt_inv.apply(beta) - C_home), scaled(Lf.apply(point(a))), inv_L * rho));
        } else if (!ra && rb) {
            const Vector2 beta = Mf.apply(point(b));
            out.add(pointOnLine(perp(Lf.rotate(direction(a))), scaled(Rt_inv.apply(beta) - C_home),
                                scaled(Lf.apply(beta))));
        } else if (ra && !rb) {
            const Vector2 e = Rt_inv.rotate(Mf.rotate(direction(b)));
            out.add(lineThroughPoint(perp(e), scaled(Rt_inv.apply(point(a)) - C_home), scaled(Lf.apply(point(a)))));
        } else {
            out.add(orientation(Lf.then(Rt)));
        }
    }
    if (model.task_dimension == 2) {
        // a translating point tool (task map E): every limb's last R joint is at the tool point,
        // so no limb fixes phi; the pose keeps theta at home, phi = 0
        Equation e{};
        e.orientation = true;
        e.phi0 = 0.0;
        out.add(e);
    }
}

}  // namespace nocdyn::detail::locked
