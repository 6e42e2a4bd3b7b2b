// Joint reaction forces by Newton-Euler back-substitution along each limb (reactions.hpp).
#include "nocdyn/detail/sanitizer.hpp"
#include "nocdyn/reactions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lean_kernel.hpp"
#include "nocdyn/detail/fast_math.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/parallel.hpp"
#include "nocdyn/detail/index.hpp"
#include "stages.hpp"

// the lean kernel's packets appear only in its inlined templates (as in dynamics.cpp)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace nocdyn {

namespace {

using detail::sign;

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

/// The stages' path: every stage, the bodies' wrenches, tau from the platform's balance, the
/// back-substitution. Gives the exact Status of a sample the lean path rejects.
#if defined(__GNUC__)
__attribute__((noinline, cold))
#endif
Status
stagedReactions(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
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

namespace lean = detail::lean;

/// The lean kernel's terms of limb `limb` (its kind read at run time) with their capture.
NOCDYN_ALWAYS_INLINE bool leanLimb(const LimbModel& limb, const lean::Frame<double>& frame,
                                   const lean::Out<double>& out, lean::V3<double>& W, lean::V3<double>* rows,
                                   double* weight, double* scale, lean::LimbTerms<double>& terms) {
    switch (limb.kind) {
        case LimbKind::RRR:
            return lean::limbTerms<LimbKind::RRR, lean::kAnyActuation>(limb, frame, out, W, rows, weight, scale,
                                                                       &terms);
        case LimbKind::PRR:
            return lean::limbTerms<LimbKind::PRR, lean::kAnyActuation>(limb, frame, out, W, rows, weight, scale,
                                                                       &terms);
        case LimbKind::RPR:
            return lean::limbTerms<LimbKind::RPR, lean::kAnyActuation>(limb, frame, out, W, rows, weight, scale,
                                                                       &terms);
        case LimbKind::RRP:
            return lean::limbTerms<LimbKind::RRP, lean::kAnyActuation>(limb, frame, out, W, rows, weight, scale,
                                                                       &terms);
        case LimbKind::PRP:
            return lean::limbTerms<LimbKind::PRP, lean::kAnyActuation>(limb, frame, out, W, rows, weight, scale,
                                                                       &terms);
        case LimbKind::RPP:
            return lean::limbTerms<LimbKind::RPP, lean::kAnyActuation>(limb, frame, out, W, rows, weight, scale,
                                                                       &terms);
        case LimbKind::PPR:
            return lean::limbTerms<LimbKind::PPR, lean::kAnyActuation>(limb, frame, out, W, rows, weight, scale,
                                                                       &terms);
        case LimbKind::PPP:
            break;  // rejected by validate()
    }
    return false;
}

NOCDYN_ALWAYS_INLINE Wrench wrenchOf(const lean::V3<double>& v) { return {v.w, v.x, v.y}; }

#if !NOCDYN_ASAN()
/// Lane l of a packet's terms (limb l of a robot run in lanes).
NOCDYN_ALWAYS_INLINE lean::LimbTerms<double> laneOf(const lean::LimbTerms<fastmath::Pack>& t, int l) {
    const auto v = [l](const lean::V3<fastmath::Pack>& x) NOCDYN_INLINE_LAMBDA {
        return lean::V3<double>{x.w[l], x.x[l], x.y[l]};
    };
    lean::LimbTerms<double> out;
    for (std::size_t k = 0; k < 3; ++k) {
        out.s[k] = v(t.s[k]);
        out.j[k] = v(t.j[k]);
        out.gd[k] = t.gd[k][l];
        out.gdd[k] = t.gdd[k][l];
        out.f[k] = t.f[k][l];
    }
    for (std::size_t b = 0; b < 2; ++b) {
        out.w[b] = v(t.w[b]);
        out.xi[b] = v(t.xi[b]);
        out.x[b] = t.x[b][l];
        out.y[b] = t.y[b][l];
    }
    return out;
}

/// The limbs of a uniform robot (Model::limbsInLanes), limb l in lane l of one packet, as
/// inverseDynamicsFast runs them (lean_kernel.hpp, sampleLanes): their share of W_P, rows of A
/// and actuator values, and each limb's terms. False where a limb is rejected.
template <LimbKind K>
NOCDYN_ALWAYS_INLINE bool limbsInLanes(const Model& model, const lean::Frame<double>& f, const lean::Out<double>& out,
                                       lean::V3<double>& W, lean::V3<double>* rows, double* weights, double* scales,
                                       std::array<lean::LimbTerms<double>, kMaxLimbs>& terms) {
    using fastmath::Pack;
    using fastmath::splat;
    const auto wide = [](const lean::V3<double>& v) NOCDYN_INLINE_LAMBDA {
        return lean::V3<Pack>{splat<Pack>(v.w), splat<Pack>(v.x), splat<Pack>(v.y)};
    };
    const lean::Frame<Pack> frame{
        detail::PlatformMove<Pack>{
            splat<Pack>(f.G.cos_dtheta), splat<Pack>(f.G.sin_dtheta), {splat<Pack>(f.G.C.x()), splat<Pack>(f.G.C.y())}},
        wide(f.xi_P),
        wide(f.xi_P_dot),
        f.gx,
        f.gy,
        f.L,
        f.inv_L,
        f.max_condition};
    Pack u{}, du{}, ddu{};
    lean::V3<Pack> row{Pack{}, Pack{}, Pack{}};
    lean::V3<Pack> W_limbs{Pack{}, Pack{}, Pack{}};
    double weight = 1.0, scale = 1.0;
    lean::LimbTerms<Pack> lanes;
    const lean::Out<Pack> lane_out{&u, &du, &ddu, nullptr, 0};
    const fastmath::Mask<Pack> ok =
        lean::limbTerms<K, lean::kAnyActuation>(detail::LaneLimb{detail::ModelKernel::lanes(model), model.limb[0]},
                                                frame, lane_out, W_limbs, &row, &weight, &scale, &lanes);
    for (int j = 0; j < model.limbs; ++j) {
        if (ok[j] == 0) return false;
    }
    for (int j = 0; j < model.limbs; ++j) {
        // lanes past the last limb repeat limb 0: neither their test nor their share counts
        W.w += W_limbs.w[j], W.x += W_limbs.x[j], W.y += W_limbs.y[j];
        out.u[j] = u[j];
        out.du[j] = du[j];
        out.ddu[j] = ddu[j];
        rows[j] = {row.w[j], row.x[j], row.y[j]};
        weights[j] = weight;
        scales[j] = scale;
        terms[static_cast<std::size_t>(j)] = laneOf(lanes, j);
    }
    return true;
}

template <int... kKinds>
NOCDYN_ALWAYS_INLINE bool anyLimbsInLanes(const Model& model, const lean::Frame<double>& f,
                                          const lean::Out<double>& out, lean::V3<double>& W, lean::V3<double>* rows,
                                          double* weights, double* scales,
                                          std::array<lean::LimbTerms<double>, kMaxLimbs>& terms,
                                          std::integer_sequence<int, kKinds...>) {
    const int kind = model.uniform_limbs / 3;
    bool ok = false;
    (void)((kind == kKinds &&
            (ok = limbsInLanes<static_cast<LimbKind>(kKinds)>(model, f, out, W, rows, weights, scales, terms), true)) ||
           ...);
    return ok;
}
#endif

}  // namespace

void jointReactions(const Model& model, const Data& data, Reactions& reactions) {
    bodyWrenches(model, data, reactions);
    backSubstitute(model, data, reactions);
}

// The lean inverse dynamics (lean_kernel.hpp: closed-form limb IK, J_j^-1 by cofactors, no
// T_i, I or C) with each limb's terms kept, then F_3 = J_j^-T (e - f) = sum_k (e_k - f_k) j_k
// (j_k the rows of J_j^-1), F_2 = F_3 + w_2, F_1 = F_2 + w_1. A sample the kernel rejects takes
// the stages' path, which gives its exact Status. On x86-64 with GCC an AVX2+FMA clone is built
// beside the baseline one, as for inverseDynamicsFast.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(NOCDYN_NO_TARGET_CLONES)
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
Status
inverseDynamicsWithReactions(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                             Reactions& reactions) {
    double zero = 0.0;  // 0 for finite inputs, NaN otherwise
    // NOLINTNEXTLINE(misc-redundant-expression): x - x is the finiteness test
    for (int i = 0; i < 3; ++i) zero += (p(i) - p(i)) + (dp(i) - dp(i)) + (ddp(i) - ddp(i));
    const double dtheta = p(0) - model.home(0);
    if (!(zero == 0.0) || !(std::abs(dtheta) < 1.0e6)) [[unlikely]]
        return stagedReactions(model, data, p, dp, ddp, reactions);
    double sn, cs;
    fastmath::sinCos(dtheta, sn, cs);
    // xi_P = S(c) dp/dt and its rate; the platform's c.o.m. and its wrench w_P
    const double cx = p(1), cy = p(2), w = dp(0);
    const lean::V3<double> xi_P{w, dp(1) + w * cy, dp(2) - w * cx};
    const lean::V3<double> xi_P_dot{ddp(0), ddp(1) + ddp(0) * cy + w * dp(2), ddp(2) - ddp(0) * cx - w * dp(1)};
    const Vector2& com = model.platform_com_home;
    const double px = cx + cs * com.x() - sn * com.y(), py = cy + sn * com.x() + cs * com.y();
    const double gx = model.gravity.x(), gy = model.gravity.y();
    lean::V3<double> W =
        lean::bodyWrench(model.platform_M.inertia, model.platform_M.mass, gx, gy, px, py, xi_P, xi_P_dot);
    reactions.body[static_cast<std::size_t>(model.platformBody())] = wrenchOf(W);
    const lean::Frame<double> frame{detail::PlatformMove<double>{cs, sn, {cx, cy}},
                                    xi_P,
                                    xi_P_dot,
                                    gx,
                                    gy,
                                    model.length_scale,
                                    1.0 / model.length_scale,
                                    model.max_condition};
    const lean::Out<double> out{data.u.data(), data.du.data(), data.ddu.data(), data.tau.data(), 1};
    lean::V3<double> rows[kMaxActuators];
    double weight[kMaxActuators], scale[kMaxActuators];
    std::array<lean::LimbTerms<double>, kMaxLimbs> terms;
#if !NOCDYN_ASAN()
    if (model.limbsInLanes()) {
        // a uniform robot's limbs in the lanes of one packet, as inverseDynamicsFast
        if (!anyLimbsInLanes(model, frame, out, W, rows, weight, scale, terms,
                             std::make_integer_sequence<int, static_cast<int>(LimbKind::PPP)>{})) [[unlikely]]
            return stagedReactions(model, data, p, dp, ddp, reactions);
    } else
#endif
    {
        for (int j = 0; j < model.limbs; ++j) {
            const auto jj = static_cast<std::size_t>(j);
            if (!leanLimb(model.limb[jj], frame, out, W, rows, weight, scale, terms[jj])) [[unlikely]]
                return stagedReactions(model, data, p, dp, ddp, reactions);
        }
    }
    if (!lean::actuation<false>(model, rows, weight, scale, W, out)) [[unlikely]]
        return stagedReactions(model, data, p, dp, ddp, reactions);

    data.p = p;
    data.t_M = dp;
    data.t_M_dot = ddp;
    data.W_P = wrenchOf(W);
    data.xi_P = wrenchOf(xi_P);
    data.xi_P_dot = wrenchOf(xi_P_dot);
    data.x_P = Vector2(px, py);
    for (int j = 0; j < model.limbs; ++j) {
        const auto jj = static_cast<std::size_t>(j);
        const LimbModel& limb = model.limb[jj];
        const lean::LimbTerms<double>& t = terms[jj];
        LimbData& ld = data.limb[jj];
        // what jointReactions and a caller read of the stages
        for (std::size_t k = 0; k < 3; ++k) {
            ld.s[k] = wrenchOf(t.s[k]);
            ld.J_inv.row(static_cast<Eigen::Index>(k)) << t.j[k].w, t.j[k].x, t.j[k].y;
        }
        ld.x[0] = Vector2(t.x[0], t.y[0]);
        ld.x[1] = Vector2(t.x[1], t.y[1]);
        ld.xi[0] = wrenchOf(t.xi[0]);
        ld.xi[1] = wrenchOf(t.xi[1]);
        // ds_k/dt = [xi of the body carrying joint k, s_k]: s_1 is fixed to the base
        ld.s_dot[0].setZero();
        const auto sd1 = lean::bracket(t.xi[0], t.s[1]), sd2 = lean::bracket(t.xi[1], t.s[2]);
        ld.s_dot[1] << 0.0, sd1.x, sd1.y;
        ld.s_dot[2] << 0.0, sd2.x, sd2.y;
        ld.gamma_dot << t.gd[0], t.gd[1], t.gd[2];
        ld.gamma_ddot << t.gdd[0], t.gdd[1], t.gdd[2];
        reactions.body[static_cast<std::size_t>(model.body(j, 0))] = wrenchOf(t.w[0]);
        reactions.body[static_cast<std::size_t>(model.body(j, 1))] = wrenchOf(t.w[1]);

        // F_3 = sum_k (e_k - f_k) j_k, e_k the actuator's force (friction is in f_k)
        lean::V3<double> F3{0.0, 0.0, 0.0};
        for (std::size_t k = 0; k < 3; ++k) {
            const double e = limb.actuator[k] >= 0 ? data.tau(limb.actuator[k]) : 0.0;
            F3 = F3 + (e - t.f[k]) * t.j[k];
        }
        const lean::V3<double> F2 = F3 + t.w[1], F1 = F2 + t.w[0];
        std::array<Wrench, 3>& F = reactions.transmitted[jj];
        F[0] = wrenchOf(F1);
        F[1] = wrenchOf(F2);
        F[2] = wrenchOf(F3);
        const lean::V3<double>* const Fk[3] = {&F1, &F2, &F3};
        for (std::size_t k = 0; k < 3; ++k) {
            const lean::V3<double>& f = *Fk[k];
            Vector3& r = reactions.joint[jj][k];
            if (limb.type[k] == JointType::revolute) {
                r << f.x, f.y, 0.0;
            } else {
                // the force normal to d (a P screw is [0; d]); the couple about the outboard c.o.m.
                const double dx = t.s[k].x, dy = t.s[k].y;
                const double along = dx * f.x + dy * f.y;
                const std::size_t b = std::min<std::size_t>(k, 1);
                const double ox = k == 2 ? px : t.x[b], oy = k == 2 ? py : t.y[b];
                r << f.x - along * dx, f.y - along * dy, f.w - (ox * f.y - oy * f.x);
            }
        }
    }
    return {};
}

namespace {

/// Samples [begin, end) of reactionsBatch on the calling thread: one Data and one Reactions
/// for the whole range (fixed capacity), nothing allocated per sample.
BatchResult reactionsChunk(const Model& model, const BatchInput& p, const BatchInput& dp, const BatchInput& ddp,
                           BatchOutput& out, Eigen::Index begin, Eigen::Index end, PoseColumns order) {
    BatchResult result;
    Data data(model);
    Reactions reactions;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (Eigen::Index k = begin; k < end; ++k) {
        const Status status = inverseDynamicsWithReactions(model, data, poseRow(p, k, order), poseRow(dp, k, order),
                                                           poseRow(ddp, k, order), reactions);
        if (!status && result.failed++ == 0) {
            result.first_failure = k;
            result.status = status;
        }
        Eigen::Index c = 0;
        for (int j = 0; j < model.limbs; ++j) {
            for (const Vector3& r : reactions.joint[static_cast<std::size_t>(j)]) {
                for (int i = 0; i < 3; ++i) out(k, c++) = status ? r(i) : nan;
            }
        }
    }
    return result;
}

void requireBatchShape(const char* name, Eigen::Index rows, Eigen::Index cols, Eigen::Index n, Eigen::Index m) {
    if (rows != n || cols != m) {
        throw Error(std::string("reactionsBatch: ") + name + " is " + std::to_string(rows) + " x " +
                    std::to_string(cols) + ", expected " + std::to_string(n) + " x " + std::to_string(m));
    }
}

}  // namespace

BatchResult reactionsBatch(const Model& model, const BatchInput& p, const BatchInput& dp, const BatchInput& ddp,
                           BatchOutput out, unsigned threads, PoseColumns order) {
    const Eigen::Index n = p.rows();
    requireBatchShape("p", p.rows(), p.cols(), n, 3);
    requireBatchShape("dp", dp.rows(), dp.cols(), n, 3);
    requireBatchShape("ddp", ddp.rows(), ddp.cols(), n, 3);
    requireBatchShape("out", out.rows(), out.cols(), n, Eigen::Index{9} * model.limbs);
    const ParallelSplit split = splitRange(n, threads, 8);  // inverseDynamicsBatch's split
    if (split.workers == 1) return reactionsChunk(model, p, dp, ddp, out, 0, n, order);
    std::vector<BatchResult> results(split.workers);
    parallelFor("reactionsBatch", split, [&](unsigned w, Eigen::Index begin, Eigen::Index end) {
        results[w] = reactionsChunk(model, p, dp, ddp, out, begin, end, order);
    });
    return combineChunks(results);
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
