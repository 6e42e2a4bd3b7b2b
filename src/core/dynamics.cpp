// NOC dynamics of the general planar parallel robot (dynamics.hpp): full and lean paths.
#include "nocdyn/dynamics.hpp"

#include <array>
#include <cmath>

#include "lean_kernel.hpp"
#include "nocdyn/detail/fast_math.hpp"
#include "nocdyn/detail/index.hpp"
#include "stages.hpp"

// The lean kernel runs a uniform robot's limbs in the lanes of a packet that lives in
// registers (everything it calls is inlined): the note that a 32-byte vector's ABI depends
// on AVX does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace nocdyn {

namespace {

using detail::sign;

/// Joint friction to overcome, phi_k = damping q'_k + friction sign q'_k, for limb j.
[[nodiscard]] Vector3 frictionEffort(const LimbModel& limb, const LimbData& ld) {
    Vector3 phi;
    for (int k = 0; k < 3; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        phi(k) = limb.damping[kk] * ld.gamma_dot(k) + limb.friction[kk] * sign(ld.gamma_dot(k));
    }
    return phi;
}

/// Minimum-norm solution of A^T tau = W for n > 3 actuators with rows a_a of A:
/// tau = A (A^T A)^-1 W, the 3 x 3 system solved by cofactors.
void minimumNorm(const Vector3* rows, int n, const Vector3& W, ActuatorVector& tau) {
    Matrix3 AtA = Matrix3::Zero();
    for (int a = 0; a < n; ++a) AtA.noalias() += rows[a] * rows[a].transpose();
    Matrix3 adj;
    const double det = detail::symmetricAdjugate(AtA, adj);
    const Vector3 lambda = (adj * W) / det;
    for (int a = 0; a < n; ++a) tau(a) = rows[a].dot(lambda);
}

}  // namespace

namespace detail {

/// tau from A^T tau = W (xi-coordinates): A^-T W, or the minimum-norm A (A^T A)^-1 W.
void distribute(const Model& model, Data& data, const Vector3& W) {
    if (model.coordinates == Coordinates::actuators) {
        data.tau.noalias() = data.Xi.transpose() * W;
    } else if (model.task_dimension == 2) {
        // translation: (A S(c) E)^T tau = E^T S(c)^T W, with S(c) E = [0; I] the force part of W:
        // the minimum-norm tau = A_E (A_E^T A_E)^-1 f, A_E the x, y columns of A (n x 2)
        double n00 = 0.0, n01 = 0.0, n11 = 0.0;
        for (int a = 0; a < model.actuators; ++a) {
            const double rx = data.A(a, 1), ry = data.A(a, 2);
            n00 += rx * rx, n01 += rx * ry, n11 += ry * ry;
        }
        const double inv_det = 1.0 / (n00 * n11 - n01 * n01);
        const double lx = (n11 * W(1) - n01 * W(2)) * inv_det;
        const double ly = (n00 * W(2) - n01 * W(1)) * inv_det;
        for (int a = 0; a < model.actuators; ++a) data.tau(a) = data.A(a, 1) * lx + data.A(a, 2) * ly;
    } else {
        std::array<Vector3, kMaxActuators> rows;
        for (int a = 0; a < model.actuators; ++a) rows[static_cast<std::size_t>(a)] = data.A.row(a).transpose();
        minimumNorm(rows.data(), model.actuators, W, data.tau);
    }
}

}  // namespace detail

NOCDYN_TARGET_CLONES
void jointSpaceDynamics(const Model& model, Data& data) {
    // eq. 23 over every body, with W_i = M_i T_i formed once per body
    data.I.setZero();
    data.C.setZero();
    data.Q_gf.setZero();
    const bool gravity = !model.gravity.isZero();
    const auto add = [&](const InertiaDyad& M, const ShapingMatrix3& T, const ShapingMatrix3& T_dot)
                         NOCDYN_INLINE_LAMBDA {
                             const ShapingMatrix3 W = noc::applyInertia(M, T);
                             data.I.noalias() += T.transpose().lazyProduct(W);
                             data.C.noalias() += W.transpose().lazyProduct(T_dot);
                             // gravity: the generalized force of the weight [0; m g] is T_i^T [0; m g]
                             if (gravity) data.Q_gf.noalias() -= W.bottomRows<2>().transpose() * model.gravity;
                         };
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        for (int b = 0; b < 2; ++b) {
            const auto i = static_cast<std::size_t>(model.body(j, b));
            add(limb.M[static_cast<std::size_t>(b)], data.T[i], data.T_dot[i]);
        }
    }
    const auto platform = static_cast<std::size_t>(model.platformBody());
    add(model.platform_M, data.T[platform], data.T_dot[platform]);
    // friction: joint rates are gamma_dot_j = J_j^-1 Xi v
    Vector3 W = Vector3::Zero();
    bool friction = false;
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        if (limb.frictionless) continue;
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        W.noalias() += ld.J_inv.transpose() * frictionEffort(limb, ld);
        friction = true;
    }
    if (friction) data.Q_gf.noalias() += data.Xi.transpose() * W;
}

void actuatorForces(const Model& model, Data& data) {
    // eq. 20 with gravity and friction: Q = I dv + C v + Q_gf
    if (model.coordinates == Coordinates::actuators) {
        const Vector3 v = data.du;
        const Vector3 v_dot = data.ddu;
        data.Q.noalias() = data.I * v_dot;
        data.Q.noalias() += data.C * v;
        data.Q += data.Q_gf;
        data.tau = data.Q;
    } else {
        data.Q.noalias() = data.I * data.t_M_dot;
        data.Q.noalias() += data.C * data.t_M;
        data.Q += data.Q_gf;
        // minimum-norm tau with A_p^T tau = Q, A_p = A Xi; as Xi = S(c) is invertible this is
        // A (A^T A)^-1 S(c)^-T Q
        detail::distribute(model, data, platformWrenchOfPoseForce(data.p.tail<2>(), data.Q));
    }
}

Status inverseDynamics(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp) {
    if (const Status status = inverseDisplacement(model, data, p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model, data, dp); !status) return status;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(ddp(i))) return {StatusCode::not_finite, -1, ddp(i)};
    }
    accelerationFromPlatform(model, data, ddp);
    twistShaping(model, data);
    jointSpaceDynamics(model, data);
    actuatorForces(model, data);
    return {};
}

Status inverseDynamicsFromActuators(const Model& model, Data& data, const Pose& p, const ActuatorVector& du,
                                    const ActuatorVector& ddu) {
    if (const Status status = inverseDisplacement(model, data, p); !status) return status;
    if (const Status status = velocityFromActuatorRates(model, data, du); !status) return status;
    for (int a = 0; a < model.actuators; ++a) {
        if (!std::isfinite(ddu(a))) return {StatusCode::not_finite, -1, ddu(a)};
    }
    accelerationFromActuators(model, data, ddu);
    twistShaping(model, data);
    jointSpaceDynamics(model, data);
    actuatorForces(model, data);
    return {};
}

namespace {

/// A sample the lean path rejected (non-finite input, out of reach, or a condition number
/// beyond the limit by its division-free test): the full path gives its exact Status, and
/// its values should it accept the sample (within rounding of a threshold). Out of line, so
/// that the common path stays short.
#if defined(__GNUC__)
__attribute__((noinline, cold))
#endif
Status
rejected(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp) {
    const Status status = inverseDynamics(model, data, p, dp, ddp);
    if (status) data.W_P.noalias() = data.A.transpose() * data.tau;
    return status;
}

}  // namespace

// On x86-64 with GCC an AVX2+FMA clone is built beside the baseline one and chosen at load
// time when the CPU has it (three-operand instructions and 16 more registers' worth of
// fewer spills for the kernel's many scalars), as for the 3-PRR kernel (bench/baseline/src/fast.cpp).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(NOCDYN_NO_TARGET_CLONES)
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
Status
inverseDynamicsFast(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp) {
    // x - x is 0 for a finite x and NaN otherwise: one test for the nine inputs
    double zero = 0.0;
    // NOLINTNEXTLINE(misc-redundant-expression): x - x is the finiteness test
    for (int i = 0; i < 3; ++i) zero += (p(i) - p(i)) + (dp(i) - dp(i)) + (ddp(i) - ddp(i));
    if (!(zero == 0.0)) [[unlikely]]
        return rejected(model, data, p, dp, ddp);
    const double dtheta = p(0) - model.home(0);
    double s, c;
    if (std::abs(dtheta) < 1.0e6) [[likely]] {
        fastmath::sinCos(dtheta, s, c);  // branch-free, exact below 1.6e6 rad
    } else {
        s = std::sin(dtheta);
        c = std::cos(dtheta);
    }
    const detail::lean::Out<double> out{data.u.data(), data.du.data(), data.ddu.data(), data.tau.data(), 1};
    detail::lean::V3<double> W;
    if (!detail::lean::sample(model, c, s, p.data(), dp.data(), ddp.data(), out, W)) [[unlikely]]
        return rejected(model, data, p, dp, ddp);
    data.p = p;
    data.t_M = dp;
    data.t_M_dot = ddp;
    data.W_P = Wrench(W.w, W.x, W.y);
    return {};
}

double kineticEnergy(const Model& model, const Data& data) {
    double energy = nocdyn::kineticEnergy(model.platform_M, twistAt(data.xi_P, data.x_P));
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        for (std::size_t b = 0; b < 2; ++b) energy += nocdyn::kineticEnergy(limb.M[b], twistAt(ld.xi[b], ld.x[b]));
    }
    return energy;
}

double potentialEnergy(const Model& model, const Data& data) {
    double energy = -model.platform_M.mass * model.gravity.dot(data.x_P);
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        for (std::size_t b = 0; b < 2; ++b) energy -= limb.M[b].mass * model.gravity.dot(ld.x[b]);
    }
    return energy;
}

double frictionPower(const Model& model, const Data& data) {
    double power = 0.0;
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        power += frictionEffort(model.limb[static_cast<std::size_t>(j)], ld).dot(ld.gamma_dot);
    }
    return power;
}

Status checkEffort(const Model& model, const Data& data) {
    for (int a = 0; a < model.actuators; ++a) {
        const int j = model.actuator_limb[static_cast<std::size_t>(a)];
        const int k = model.actuator_joint[static_cast<std::size_t>(a)];
        const double limit = model.limb[static_cast<std::size_t>(j)].limits[static_cast<std::size_t>(k)].effort;
        if (!(std::abs(data.tau(a)) <= limit)) {
            Status s{StatusCode::effort_exceeded, j, data.tau(a)};
            s.joint = k;
            return s;
        }
    }
    return {};
}

}  // namespace nocdyn
