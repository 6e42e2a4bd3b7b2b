// NOC dynamics of the general planar parallel robot (dynamics.hpp): full and lean paths.
#include "nocdyn/dynamics.hpp"

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "stages.hpp"

namespace nocdyn {

namespace {

[[nodiscard]] double sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

/// Joint friction to overcome, phi_k = damping q'_k + friction sign q'_k, for limb j.
[[nodiscard]] Vector3 frictionEffort(const LimbModel& limb, const LimbData& ld) {
    Vector3 phi;
    for (int k = 0; k < 3; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        phi(k) = limb.damping[kk] * ld.gamma_dot(k) + limb.friction[kk] * sign(ld.gamma_dot(k));
    }
    return phi;
}

/// tau from A^T tau = W (xi-coordinates): A^-T W, or the minimum-norm A (A^T A)^-1 W.
void distribute(const Model& model, Data& data, const Vector3& W) {
    if (model.coordinates == Coordinates::actuators) {
        data.tau.noalias() = data.Xi.transpose() * W;
    } else {
        const Matrix3 AtA = data.A.transpose() * data.A;
        const Vector3 lambda = AtA.ldlt().solve(W);
        data.tau.noalias() = data.A * lambda;
    }
}

/// Inertia wrench, less gravity, of a body with dyad M, c.o.m. x, twist xi and twist rate
/// alpha (both referred to O), itself referred to O: [n + x x f; f] (eqs. 11-12).
[[nodiscard]] Wrench bodyWrench(const InertiaDyad& M, const Vector2& gravity, const Vector2& x, const Twist& xi,
                                const Twist& alpha) {
    const double w = xi(0);
    const Vector2 x_dot(xi(1) - w * x.y(), xi(2) + w * x.x());
    // c.o.m. acceleration: d/dt (v_O + w E x) = dv_O + dw E x + w E dx
    const Vector2 a(alpha(1) - alpha(0) * x.y() - w * x_dot.y(), alpha(2) + alpha(0) * x.x() + w * x_dot.x());
    const Vector2 f = M.mass * (a - gravity);
    return {M.inertia * alpha(0) + cross(x, f), f.x(), f.y()};
}

}  // namespace

void jointSpaceDynamics(const Model& model, Data& data) {
    // eq. 23 over every body
    data.I.setZero();
    data.C.setZero();
    data.Q_gf.setZero();
    for (int i = 0; i < model.bodies; ++i) {
        const auto ii = static_cast<std::size_t>(i);
        const InertiaDyad& M = model.inertia(i);
        noc::addInertia(M, data.T[ii], data.I);
        noc::addCoriolis(M, data.T[ii], data.T_dot[ii], data.C);
        // gravity: the generalized force of the weight [0; m g] is T_i^T [0; m g]
        data.Q_gf.noalias() -= data.T[ii].bottomRows<2>().transpose() * (M.mass * model.gravity);
    }
    // friction: joint rates are gamma_dot_j = J_j^-1 Xi v
    Vector3 W = Vector3::Zero();
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        W.noalias() += ld.J_inv.transpose() * frictionEffort(model.limb[static_cast<std::size_t>(j)], ld);
    }
    data.Q_gf.noalias() += data.Xi.transpose() * W;
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
        // minimum-norm tau with A_p^T tau = Q, A_p = A Xi; as Xi is invertible this is
        // A (A^T A)^-1 Xi^-T Q
        const Vector3 W = data.Xi.transpose().partialPivLu().solve(data.Q);
        distribute(model, data, W);
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

Status inverseDynamicsFast(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp) {
    if (const Status status = detail::positionStage(model, data, p, false); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model, data, dp); !status) return status;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(ddp(i))) return {StatusCode::not_finite, -1, ddp(i)};
    }
    accelerationFromPlatform(model, data, ddp);
    // W_P = sum_i T_i^{xi T} w_i: each limb's bodies through J_j^-T, the platform directly
    Wrench W = bodyWrench(model.platform_M, model.gravity, data.x_P, data.xi_P, data.xi_P_dot);
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        const Twist alpha0 = ld.s[0] * ld.gamma_ddot(0);
        const Twist alpha1 = alpha0 + ld.s[1] * ld.gamma_ddot(1) + ld.s_dot[1] * ld.gamma_dot(1);
        const Wrench W0 = bodyWrench(limb.M[0], model.gravity, ld.x[0], ld.xi[0], alpha0);
        const Wrench W1 = bodyWrench(limb.M[1], model.gravity, ld.x[1], ld.xi[1], alpha1);
        // joint efforts: joint k carries every body outboard of it in the limb
        Vector3 f = frictionEffort(limb, ld);
        f(0) += ld.s[0].dot(W0 + W1);
        f(1) += ld.s[1].dot(W1);
        W.noalias() += ld.J_inv.transpose() * f;
    }
    data.W_P = W;
    distribute(model, data, W);
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
