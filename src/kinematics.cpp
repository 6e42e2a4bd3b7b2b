// Position, velocity, acceleration and twist-shaping stages of the general model
// (kinematics.hpp), written once for every limb type with planar screws.
#include "nocdyn/kinematics.hpp"

#include <array>
#include <cmath>

#include "nocdyn/limb_ik.hpp"
#include "stages.hpp"

namespace nocdyn {

namespace detail {

Status positionStage(const Model& model, Data& data, const Pose& p, bool angles) {
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(p(i))) return {StatusCode::not_finite, -1, p(i)};
    }
    data.p = p;
    PlatformDisplacement G;
    G.dtheta = p(0) - model.home(0);
    G.cos_dtheta = std::cos(G.dtheta);
    G.sin_dtheta = std::sin(G.dtheta);
    G.C = p.tail<2>();
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        if (const Status status = solveLimb(limb, j, G, angles, ld); !status) return status;
        limbScrews(limb, ld);
        for (int k = 0; k < 3; ++k) {
            if (const int a = limb.actuator[static_cast<std::size_t>(k)]; a >= 0) data.u(a) = ld.q(k);
        }
    }
    // the platform's c.o.m. turns with it from home: no second sine and cosine
    data.x_P = G.apply(model.platform_com_home);
    return {};
}

Status jacobianStage(const Model& model, Data& data) {
    const double L = model.length_scale;
    const double inv_L = 1.0 / L;
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        // eq. 4a generalised: the columns of J_j are the joints' planar Pluecker arrays
        for (int k = 0; k < 3; ++k) ld.J.col(k) = ld.s[static_cast<std::size_t>(k)];
        Matrix3 adj;
        const double det = adjugateOfColumns(ld.s[0], ld.s[1], ld.s[2], adj);
        ld.J_inv = adj / det;
        // scaled 1-norm condition number of J_j (joint variables in rad and L, twists in
        // rad/s and L rad/s): ||R J diag(c)||_1 ||diag(1/c) J^-1 R^-1||_1, R = diag(1, 1/L, 1/L)
        const ConditionNorms norms = limbConditionNorms(limb, L, inv_L, ld.J, adj);
        ld.cond = norms.norm * norms.adj_norm / std::abs(det);
        if (!(ld.cond <= model.max_condition)) return {StatusCode::singular_limb, j, ld.cond};
    }
    // eq. 5 generalised: du_a = (row k of J_j^-1) xi_P for actuator a at joint k of limb j
    const int n = model.actuators;
    std::array<Vector3, kMaxActuators> rows;
    std::array<double, kMaxActuators> w{};
    for (int a = 0; a < n; ++a) {
        const auto aa = static_cast<std::size_t>(a);
        const auto j = static_cast<std::size_t>(model.actuator_limb[aa]);
        const int k = model.actuator_joint[aa];
        rows[aa] = data.limb[j].J_inv.row(k).transpose();
        data.A.row(a) = rows[aa].transpose();
        w[aa] = model.limb[j].inv_joint_scale[static_cast<std::size_t>(k)];
    }
    if (model.coordinates == Coordinates::actuators) {
        Matrix3 adj;
        const double det = actuationAdjugate(rows.data(), adj);
        data.Xi = adj / det;
        const ConditionNorms norms = actuationConditionNorms(rows.data(), w.data(), L, inv_L, adj);
        data.cond_A = norms.norm * norms.adj_norm / std::abs(det);
    } else {
        // B = As^T As, As = diag(w) A diag(1, L, L): cond_A = sqrt(cond_1 B)
        Matrix3 B = Matrix3::Zero();
        const Vector3 col_scale(1.0, L, L);
        for (int a = 0; a < n; ++a) {
            const auto aa = static_cast<std::size_t>(a);
            const Vector3 r = w[aa] * rows[aa].cwiseProduct(col_scale);
            B.noalias() += r * r.transpose();
        }
        Matrix3 adj;
        const double det = symmetricAdjugate(B, adj);
        data.cond_A = std::sqrt(norm1(B) * norm1(adj) / std::abs(det));
    }
    if (!(data.cond_A <= model.max_condition)) return {StatusCode::singular_actuation, -1, data.cond_A};
    return {};
}

void rateStage(const Model& model, Data& data) {
    for (int j = 0; j < model.limbs; ++j) {
        LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        // eq. 3: gamma_dot_j = J_j^-1 xi_P; eq. 28 generalised: body twists
        ld.gamma_dot.noalias() = ld.J_inv * data.xi_P;
        ld.xi[0] = ld.s[0] * ld.gamma_dot(0);
        ld.xi[1] = ld.xi[0] + ld.s[1] * ld.gamma_dot(1);
        // screws move with the body that carries them: ds_k/dt = [xi_(k-1), s_k]
        ld.s_dot[0].setZero();
        ld.s_dot[1] = bracket(ld.xi[0], ld.s[1]);
        ld.s_dot[2] = bracket(ld.xi[1], ld.s[2]);
    }
    data.du.noalias() = data.A * data.xi_P;
}

/// dJ_j/dt gamma_dot_j = sum_k ds_k/dt gamma_dot_k.
[[nodiscard]] Twist jacobianRateTimesRates(const LimbData& ld) {
    return ld.s_dot[1] * ld.gamma_dot(1) + ld.s_dot[2] * ld.gamma_dot(2);
}

void jointAccelerations(const Model& model, Data& data) {
    for (int j = 0; j < model.limbs; ++j) {
        LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        // d/dt of eq. 3: J_j gamma_ddot_j = dxi_P - dJ_j gamma_dot_j
        ld.gamma_ddot.noalias() = ld.J_inv * (data.xi_P_dot - jacobianRateTimesRates(ld));
    }
    for (int a = 0; a < model.actuators; ++a) {
        data.ddu(a) = data.limb[static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)])]
                          .gamma_ddot(model.actuator_joint[static_cast<std::size_t>(a)]);
    }
}

}  // namespace detail

Status inverseDisplacement(const Model& model, Data& data, const Pose& p) {
    return detail::positionStage(model, data, p, true);
}

Status velocityFromPlatformTwist(const Model& model, Data& data, const Twist& t_M) {
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(t_M(i))) return {StatusCode::not_finite, -1, t_M(i)};
    }
    if (const Status status = detail::jacobianStage(model, data); !status) return status;
    data.t_M = t_M;
    // xi_P = S(c) t_M: the velocity of the platform point at O is dc/dt + omega E (O - C)
    const Vector2 c = data.p.tail<2>();
    data.xi_P = Twist(t_M(0), t_M(1) + t_M(0) * c.y(), t_M(2) - t_M(0) * c.x());
    if (model.coordinates == Coordinates::platform) {
        data.Xi << 1.0, 0.0, 0.0, c.y(), 1.0, 0.0, -c.x(), 0.0, 1.0;
    }
    detail::rateStage(model, data);
    return {};
}

Status velocityFromActuatorRates(const Model& model, Data& data, const ActuatorVector& du) {
    if (model.coordinates != Coordinates::actuators) return {StatusCode::singular_actuation, -1, 0.0};
    for (int a = 0; a < model.actuators; ++a) {
        if (!std::isfinite(du(a))) return {StatusCode::not_finite, -1, du(a)};
    }
    if (const Status status = detail::jacobianStage(model, data); !status) return status;
    data.xi_P.noalias() = data.Xi * du;
    const Vector2 c = data.p.tail<2>();
    data.t_M = Twist(data.xi_P(0), data.xi_P(1) - data.xi_P(0) * c.y(), data.xi_P(2) + data.xi_P(0) * c.x());
    detail::rateStage(model, data);
    return {};
}

void accelerationFromPlatform(const Model& model, Data& data, const Twist& t_M_dot) {
    data.t_M_dot = t_M_dot;
    // d/dt of xi_P = S(c) t_M
    const Vector2 c = data.p.tail<2>();
    const double w = data.t_M(0);
    data.xi_P_dot = Twist(t_M_dot(0), t_M_dot(1) + t_M_dot(0) * c.y() + w * data.t_M(2),
                          t_M_dot(2) - t_M_dot(0) * c.x() - w * data.t_M(1));
    detail::jointAccelerations(model, data);
}

void accelerationFromActuators(const Model& model, Data& data, const ActuatorVector& ddu) {
    // d/dt of du = A xi_P: ddu_a = (J_j^-1 (dxi_P - dJ_j gamma_dot_j))_k
    Vector3 rhs;
    for (int a = 0; a < 3; ++a) {
        const auto j = static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)]);
        const int k = model.actuator_joint[static_cast<std::size_t>(a)];
        const LimbData& ld = data.limb[j];
        rhs(a) = ddu(a) + ld.J_inv.row(k).dot(detail::jacobianRateTimesRates(ld));
    }
    data.xi_P_dot.noalias() = data.Xi * rhs;
    const Vector2 c = data.p.tail<2>();
    const double w = data.t_M(0);
    data.t_M_dot = Twist(data.xi_P_dot(0), data.xi_P_dot(1) - data.xi_P_dot(0) * c.y() - w * data.t_M(2),
                         data.xi_P_dot(2) + data.xi_P_dot(0) * c.x() + w * data.t_M(1));
    detail::jointAccelerations(model, data);
}

void twistShaping(const Model& model, Data& data) {
    // dXi/dt: Xi = A^-1 (dXi = -Xi dA Xi, dA the actuated rows of d(J_j^-1)), or Xi = S(c)
    std::array<Matrix3, kMaxLimbs> J_inv_dot;
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        Matrix3 J_dot;
        for (int k = 0; k < 3; ++k) J_dot.col(k) = ld.s_dot[static_cast<std::size_t>(k)];
        J_inv_dot[static_cast<std::size_t>(j)].noalias() = -ld.J_inv * J_dot * ld.J_inv;
    }
    if (model.coordinates == Coordinates::actuators) {
        Matrix3 A_dot;
        for (int a = 0; a < 3; ++a) {
            A_dot.row(a) = J_inv_dot[static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)])]
                               .row(model.actuator_joint[static_cast<std::size_t>(a)]);
        }
        data.Xi_dot.noalias() = -data.Xi * A_dot * data.Xi;
    } else {
        data.Xi_dot << 0.0, 0.0, 0.0, data.t_M(2), 0.0, 0.0, -data.t_M(1), 0.0, 0.0;
    }

    // T_i = Ad(x_i) U_i J_j^-1 Xi (eqs. 28-30 generalised), dT_i by the product rule
    const auto shape = [&](const Matrix3& X, const Matrix3& X_dot, const Vector2& x, const Vector2& x_dot,
                           ShapingMatrix3& T, ShapingMatrix3& T_dot) {
        // rows of Ad(x) X: [X_0; X_12 + E x X_0], and d/dt adds E dx X_0
        Matrix3 TX = X;
        TX.row(1) -= x.y() * X.row(0);
        TX.row(2) += x.x() * X.row(0);
        Matrix3 TX_dot = X_dot;
        TX_dot.row(1) -= x.y() * X_dot.row(0) + x_dot.y() * X.row(0);
        TX_dot.row(2) += x.x() * X_dot.row(0) + x_dot.x() * X.row(0);
        T.noalias() = TX * data.Xi;
        T_dot.noalias() = TX_dot * data.Xi;
        T_dot.noalias() += TX * data.Xi_dot;
    };
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        const Matrix3& Ji = ld.J_inv;
        const Matrix3& Ji_dot = J_inv_dot[static_cast<std::size_t>(j)];
        // U_1 J^-1 = s_1 (J^-1)_0 ; U_2 J^-1 = s_1 (J^-1)_0 + s_2 (J^-1)_1
        Matrix3 X = ld.s[0] * Ji.row(0);
        Matrix3 X_dot = ld.s[0] * Ji_dot.row(0);
        const Vector2 x0_dot = twistAt(ld.xi[0], ld.x[0]).tail<2>();
        shape(X, X_dot, ld.x[0], x0_dot, data.T[static_cast<std::size_t>(model.body(j, 0))],
              data.T_dot[static_cast<std::size_t>(model.body(j, 0))]);
        X.noalias() += ld.s[1] * Ji.row(1);
        X_dot.noalias() += ld.s[1] * Ji_dot.row(1) + ld.s_dot[1] * Ji.row(1);
        const Vector2 x1_dot = twistAt(ld.xi[1], ld.x[1]).tail<2>();
        shape(X, X_dot, ld.x[1], x1_dot, data.T[static_cast<std::size_t>(model.body(j, 1))],
              data.T_dot[static_cast<std::size_t>(model.body(j, 1))]);
    }
    // eq. 31 generalised: the platform, t_7 = Ad(x_P) xi_P
    const Vector2 xP_dot = twistAt(data.xi_P, data.x_P).tail<2>();
    shape(Matrix3::Identity(), Matrix3::Zero(), data.x_P, xP_dot, data.T[static_cast<std::size_t>(model.platformBody())],
          data.T_dot[static_cast<std::size_t>(model.platformBody())]);
}

Status checkJointLimits(const Model& model, const Data& data) {
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        for (int k = 0; k < 3; ++k) {
            const JointLimits& lim = limb.limits[static_cast<std::size_t>(k)];
            const double q = ld.q(k);
            if (!(q >= lim.lower && q <= lim.upper)) {
                Status s{StatusCode::joint_limit_exceeded, j, q};
                s.joint = k;
                return s;
            }
            if (!(std::abs(ld.gamma_dot(k)) <= lim.velocity)) {
                Status s{StatusCode::velocity_exceeded, j, ld.gamma_dot(k)};
                s.joint = k;
                return s;
            }
        }
    }
    return {};
}

}  // namespace nocdyn
