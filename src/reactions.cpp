// Joint reaction forces by Newton-Euler back-substitution along each limb (reactions.hpp).
#include "nocdyn/reactions.hpp"

#include <cmath>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/kinematics.hpp"
#include "stages.hpp"

namespace nocdyn {

namespace {

[[nodiscard]] double sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

/// w = M dt - [0; m g] of a body with c.o.m. x, twist xi and its rate xi_dot (both referred to
/// O), returned referred to O: f = m (a_c - g), n_O = I dw + x x f.
[[nodiscard]] Wrench netWrench(const InertiaDyad& M, const Vector2& gravity, const Vector2& x, const Twist& xi,
                               const Twist& xi_dot) {
    const double w = xi(0), dw = xi_dot(0);
    // v_c = v_O + w E x;  a_c = d/dt v_c = a_O + dw E x + w E v_c
    const Vector2 v_c = xi.tail<2>() + w * perp(x);
    const Vector2 a_c = xi_dot.tail<2>() + dw * perp(x) + w * perp(v_c);
    const Vector2 f = M.mass * (a_c - gravity);
    return {M.inertia * dw + cross(x, f), f.x(), f.y()};
}

/// w_1, w_2 of every limb and w_P into reactions.body (the velocity and acceleration stages done).
void bodyWrenches(const Model& model, const Data& data, Reactions& reactions) {
    reactions.body[static_cast<std::size_t>(model.platformBody())] =
        netWrench(model.platform_M, model.gravity, data.x_P, data.xi_P, data.xi_P_dot);
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        // body rates: dxi_1 = s_1 q1'' (s_1 is fixed to the base), dxi_2 = dxi_1 + s_2 q2'' + ds_2/dt q2'
        const Twist xi_dot_1 = ld.s[0] * ld.gamma_ddot(0);
        const Twist xi_dot_2 = xi_dot_1 + ld.s[1] * ld.gamma_ddot(1) + ld.s_dot[1] * ld.gamma_dot(1);
        reactions.body[static_cast<std::size_t>(model.body(j, 0))] =
            netWrench(limb.M[0], model.gravity, ld.x[0], ld.xi[0], xi_dot_1);
        reactions.body[static_cast<std::size_t>(model.body(j, 1))] =
            netWrench(limb.M[1], model.gravity, ld.x[1], ld.xi[1], xi_dot_2);
    }
}

/// phi: the friction to overcome at each joint of a limb (damping q' + friction sign q').
[[nodiscard]] Vector3 friction(const LimbModel& limb, const LimbData& ld) {
    Vector3 phi;
    for (std::size_t k = 0; k < 3; ++k) {
        const double rate = ld.gamma_dot(static_cast<Eigen::Index>(k));
        phi(static_cast<Eigen::Index>(k)) = limb.damping[k] * rate + limb.friction[k] * sign(rate);
    }
    return phi;
}

/// k_j = [s_1^T (w_1 + w_2); s_2^T w_2; 0]: what the limb's own bodies take of each joint's effort.
[[nodiscard]] Vector3 bodiesShare(const LimbData& ld, const Wrench& w1, const Wrench& w2) {
    return {ld.s[0].dot(w1 + w2), ld.s[1].dot(w2), 0.0};
}

/// F_3 = J_j^-T (e - k_j), F_2 = F_3 + w_2, F_1 = F_2 + w_1, and the reactions in the convention.
void backSubstitute(const Model& model, const Data& data, Reactions& reactions) {
    for (int j = 0; j < model.limbs; ++j) {
        const auto jj = static_cast<std::size_t>(j);
        const LimbModel& limb = model.limb[jj];
        const LimbData& ld = data.limb[jj];
        const Wrench& w1 = reactions.body[static_cast<std::size_t>(model.body(j, 0))];
        const Wrench& w2 = reactions.body[static_cast<std::size_t>(model.body(j, 1))];
        // e_k: the actuator's force or torque on the outboard body less the friction to overcome
        Vector3 e = -friction(limb, ld);
        for (std::size_t k = 0; k < 3; ++k) {
            if (limb.actuator[k] >= 0) e(static_cast<Eigen::Index>(k)) += data.tau(limb.actuator[k]);
        }
        std::array<Wrench, 3>& F = reactions.transmitted[jj];
        F[2].noalias() = ld.J_inv.transpose() * (e - bodiesShare(ld, w1, w2));
        F[1] = F[2] + w2;
        F[0] = F[1] + w1;

        for (std::size_t k = 0; k < 3; ++k) {
            const Vector2 f = F[k].tail<2>();
            Vector3& r = reactions.joint[jj][k];
            if (limb.type[k] == JointType::revolute) {
                r << f, 0.0;
            } else {
                // the direction d of a P screw [0; d]; the couple about the outboard body's c.o.m.
                const Vector2 d = ld.s[k].tail<2>();
                const Vector2 x = k == 2 ? data.x_P : ld.x[k];
                r << f - d.dot(f) * d, F[k](0) - cross(x, f);
            }
        }
    }
}

}  // namespace

void jointReactions(const Model& model, const Data& data, Reactions& reactions) {
    bodyWrenches(model, data, reactions);
    backSubstitute(model, data, reactions);
}

Status inverseDynamicsWithReactions(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                                    Reactions& reactions) {
    if (const Status status = inverseDisplacement(model, data, p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model, data, dp); !status) return status;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(ddp(i))) return {StatusCode::not_finite, -1, ddp(i)};
    }
    accelerationFromPlatform(model, data, ddp);
    bodyWrenches(model, data, reactions);
    // the platform's balance sum_j F_3j = w_P with F_3j = J_j^-T (E_j tau - phi_j - k_j) is
    // A^T tau = W_P, W_P = w_P + sum_j J_j^-T (phi_j + k_j) (the NOC applied to the wrenches)
    Wrench W = reactions.body[static_cast<std::size_t>(model.platformBody())];
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        const Wrench& w1 = reactions.body[static_cast<std::size_t>(model.body(j, 0))];
        const Wrench& w2 = reactions.body[static_cast<std::size_t>(model.body(j, 1))];
        W.noalias() +=
            ld.J_inv.transpose() * (friction(model.limb[static_cast<std::size_t>(j)], ld) + bodiesShare(ld, w1, w2));
    }
    data.W_P = W;
    detail::distribute(model, data, W);
    backSubstitute(model, data, reactions);
    return {};
}

double JointLoad::rmsForce() const {
    return samples > 0 ? std::sqrt(sum_squared_force / static_cast<double>(samples)) : 0.0;
}

void JointLoads::add(double t, const Pose& p, const Reactions& reactions) {
    for (std::size_t j = 0; j < static_cast<std::size_t>(limbs); ++j) {
        for (std::size_t k = 0; k < 3; ++k) {
            JointLoad& load = joint[j][k];
            const Vector3& r = reactions.joint[j][k];
            const double f = r.head<2>().norm(), m = std::abs(r(2));
            if (load.samples == 0 || f > load.peak_force) {
                load.peak_force = f;
                load.peak_force_t = t;
                load.peak_force_pose = p;
            }
            if (load.samples == 0 || m > load.peak_moment) {
                load.peak_moment = m;
                load.peak_moment_t = t;
                load.peak_moment_pose = p;
            }
            load.sum_squared_force += f * f;
            ++load.samples;
        }
    }
}

void JointLoads::merge(const JointLoads& other) {
    for (std::size_t j = 0; j < static_cast<std::size_t>(limbs); ++j) {
        for (std::size_t k = 0; k < 3; ++k) {
            JointLoad& load = joint[j][k];
            const JointLoad& o = other.joint[j][k];
            if (o.samples == 0) continue;
            if (load.samples == 0 || o.peak_force > load.peak_force) {
                load.peak_force = o.peak_force;
                load.peak_force_t = o.peak_force_t;
                load.peak_force_pose = o.peak_force_pose;
            }
            if (load.samples == 0 || o.peak_moment > load.peak_moment) {
                load.peak_moment = o.peak_moment;
                load.peak_moment_t = o.peak_moment_t;
                load.peak_moment_pose = o.peak_moment_pose;
            }
            load.sum_squared_force += o.sum_squared_force;
            load.samples += o.samples;
        }
    }
}

}  // namespace nocdyn
