// Position, velocity, acceleration and twist-shaping stages of the general model
// (kinematics.hpp), written once for every limb type with planar screws.
#include "nocdyn/kinematics.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/QR>

#include "limb_ik_impl.hpp"
#include "stages.hpp"

namespace nocdyn {

namespace detail {

NOCDYN_TARGET_CLONES
Status positionStage(const Model& model, Data& data, const Pose& p, bool angles, const int* branches) {
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
        const int branch = branches != nullptr ? branches[j] : limb.branch;
        if (const Status status = solveLimbData(limb, j, G, branch, angles, ld); !status) return status;
        limbScrews(limb, ld);
        for (int k = 0; k < 3; ++k) {
            if (const int a = limb.actuator[static_cast<std::size_t>(k)]; a >= 0) data.u(a) = ld.q(k);
        }
    }
    // the platform's c.o.m. turns with it from home: no second sine and cosine
    data.x_P = G.apply(model.platform_com_home);
    return {};
}

NOCDYN_TARGET_CLONES
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
    } else if (model.task_dimension == 2) {
        // translation: the actuation map is A S(c) E = the x, y columns of A (S(c) E = [0; I]);
        // B = As^T As with As = diag(w) A E L, cond_A = sqrt(cond_1 B), B 2 x 2
        double b00 = 0.0, b01 = 0.0, b11 = 0.0;
        for (int a = 0; a < n; ++a) {
            const auto aa = static_cast<std::size_t>(a);
            const double rx = w[aa] * L * rows[aa](1), ry = w[aa] * L * rows[aa](2);
            b00 += rx * rx, b01 += rx * ry, b11 += ry * ry;
        }
        const double det = b00 * b11 - b01 * b01;
        const double norm = std::max(std::abs(b00) + std::abs(b01), std::abs(b01) + std::abs(b11));
        data.cond_A = std::sqrt(norm * norm / std::abs(det));
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

NOCDYN_TARGET_CLONES
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
        data.ddu(a) = data.limb[static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)])].gamma_ddot(
            model.actuator_joint[static_cast<std::size_t>(a)]);
    }
}

}  // namespace detail

Status inverseDisplacement(const Model& model, Data& data, const Pose& p) {
    return detail::positionStage(model, data, p, true);
}

Status inverseDisplacement(const Model& model, Data& data, const Pose& p, const LimbBranches& branches) {
    return detail::positionStage(model, data, p, true, branches.data());
}

Status velocityFromPlatformTwist(const Model& model, Data& data, const Twist& t_M) {
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(t_M(i))) return {StatusCode::not_finite, -1, t_M(i)};
    }
    if (const Status status = detail::jacobianStage(model, data); !status) return status;
    data.t_M = t_M;
    // xi_P = S(c) t_M: the velocity of the platform point at O is dc/dt + omega E (O - C)
    data.xi_P = platformTwistOfPoseRate(data.p.tail<2>(), t_M);
    if (model.coordinates == Coordinates::platform) detail::platformCoordinates(data);
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
    data.t_M = poseRateOfPlatformTwist(data.p.tail<2>(), data.xi_P);
    detail::rateStage(model, data);
    return {};
}

Status velocityFromActuatorRatesLeastSquares(const Model& model, Data& data, const ActuatorVector& du, Twist& dp,
                                             double tolerance) {
    for (int a = 0; a < model.actuators; ++a) {
        if (!std::isfinite(du(a))) return {StatusCode::not_finite, -1, du(a)};
    }
    if (const Status status = velocityFromPlatformTwist(model, data, Twist::Zero()); !status) return status;
    // A xi_P = du in the least-squares sense; dp/dt = S(c)^-1 xi_P minimises |A S(c) dp/dt - du|
    // too, as S(c) is invertible. Fixed-capacity QR: no allocation.
    if (model.task_dimension == 2) {
        // translation: du = A S(c) E dp_t/dt with A S(c) E the x, y columns of A (n x 2);
        // dp/dt = E dp_t/dt keeps theta's rate at 0 (a rotation about C moves no actuator,
        // so the three-column problem would leave it free)
        using TaskActuation = Eigen::Matrix<double, Eigen::Dynamic, 2, 0, kMaxActuators, 2>;
        const TaskActuation A_t = data.A.rightCols<2>();
        const Eigen::ColPivHouseholderQR<TaskActuation> qr(A_t);
        const Vector2 dp_t = qr.solve(du);
        dp = Twist(0.0, dp_t(0), dp_t(1));
    } else {
        const Eigen::ColPivHouseholderQR<ActuationMatrix> qr(data.A);
        const Twist xi_P = qr.solve(du);
        dp = poseRateOfPlatformTwist(data.p.tail<2>(), xi_P);
    }
    if (const Status status = velocityFromPlatformTwist(model, data, dp); !status) return status;
    const double residual = (data.du - du).cwiseAbs().maxCoeff();
    if (!(residual <= tolerance * (1.0 + du.cwiseAbs().maxCoeff()))) {
        return {StatusCode::inconsistent_rates, -1, residual};
    }
    return {};
}

void accelerationFromPlatform(const Model& model, Data& data, const Twist& t_M_dot) {
    data.t_M_dot = t_M_dot;
    // d/dt of xi_P = S(c) t_M: S(c) dt_M/dt + dS/dt t_M
    const double w = data.t_M(0);
    data.xi_P_dot = platformTwistOfPoseRate(data.p.tail<2>(), t_M_dot) + Twist(0.0, w * data.t_M(2), -w * data.t_M(1));
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
    // dt_M/dt = S(c)^-1 (dxi_P/dt - dS/dt t_M)
    const double w = data.t_M(0);
    data.t_M_dot =
        poseRateOfPlatformTwist(data.p.tail<2>(), data.xi_P_dot) - Twist(0.0, w * data.t_M(2), -w * data.t_M(1));
    detail::jointAccelerations(model, data);
}

NOCDYN_TARGET_CLONES
void twistShaping(const Model& model, Data& data) {
    // dXi/dt: Xi = A^-1 (dXi = -Xi dA Xi, dA the actuated rows of d(J_j^-1) = -J_j^-1 dJ_j J_j^-1,
    // dJ_j = [0 ds_2 ds_3]), or Xi = S(c)
    if (model.coordinates == Coordinates::actuators) {
        Matrix3 A_dot;
        for (int a = 0; a < 3; ++a) {
            const LimbData& ld = data.limb[static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)])];
            const auto r = ld.J_inv.row(model.actuator_joint[static_cast<std::size_t>(a)]);
            const Eigen::RowVector3d r_J_dot(0.0, r.dot(ld.s_dot[1]), r.dot(ld.s_dot[2]));
            A_dot.row(a).noalias() = -r_J_dot * ld.J_inv;
        }
        data.Xi_dot.noalias() = -data.Xi * A_dot * data.Xi;
    } else {
        detail::platformCoordinates(data);
    }
    detail::shapeBodies(model, data);
    data.coordinates = model.coordinates;
}

namespace detail {

NOCDYN_TARGET_CLONES
void shapeBodies(const Model& model, Data& data) {
    // T_i = Ad(x_i) Y, Y = U_i J_j^-1 Xi (eqs. 28-30 generalised); dT_i = Ad(x_i) dY + dAd(x_i) Y.
    // Rows of Ad(x) Y: [Y_0; Y_12 + E x Y_0], and d/dt adds E dx Y_0.
    const auto shape = [](const Matrix3& Y, const Matrix3& Y_dot, const Vector2& x, const Vector2& x_dot,
                          ShapingMatrix3& T, ShapingMatrix3& T_dot) NOCDYN_INLINE_LAMBDA {
        T = Y;
        T.row(1) -= x.y() * Y.row(0);
        T.row(2) += x.x() * Y.row(0);
        T_dot = Y_dot;
        T_dot.row(1) -= x.y() * Y_dot.row(0) + x_dot.y() * Y.row(0);
        T_dot.row(2) += x.x() * Y_dot.row(0) + x_dot.x() * Y.row(0);
    };
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        // R = J_j^-1 Xi (joint rates per independent rate) and dR = J_j^-1 (dXi - dJ_j R)
        Matrix3 R;
        R.noalias() = ld.J_inv * data.Xi;
        Matrix3 rhs = data.Xi_dot;
        rhs.noalias() -= ld.s_dot[1] * R.row(1);
        rhs.noalias() -= ld.s_dot[2] * R.row(2);
        Matrix3 R_dot;
        R_dot.noalias() = ld.J_inv * rhs;
        // U_1 R = s_1 R_0 ; U_2 R = s_1 R_0 + s_2 R_1 (ds_1 = 0)
        Matrix3 Y = ld.s[0] * R.row(0);
        Matrix3 Y_dot = ld.s[0] * R_dot.row(0);
        const Vector2 x0_dot = twistAt(ld.xi[0], ld.x[0]).tail<2>();
        shape(Y, Y_dot, ld.x[0], x0_dot, data.T[static_cast<std::size_t>(model.body(j, 0))],
              data.T_dot[static_cast<std::size_t>(model.body(j, 0))]);
        Y.noalias() += ld.s[1] * R.row(1);
        Y_dot.noalias() += ld.s[1] * R_dot.row(1);
        Y_dot.noalias() += ld.s_dot[1] * R.row(1);
        const Vector2 x1_dot = twistAt(ld.xi[1], ld.x[1]).tail<2>();
        shape(Y, Y_dot, ld.x[1], x1_dot, data.T[static_cast<std::size_t>(model.body(j, 1))],
              data.T_dot[static_cast<std::size_t>(model.body(j, 1))]);
    }
    // eq. 31 generalised: the platform, t_7 = Ad(x_P) xi_P = Ad(x_P) Xi v
    const Vector2 xP_dot = twistAt(data.xi_P, data.x_P).tail<2>();
    shape(data.Xi, data.Xi_dot, data.x_P, xP_dot, data.T[static_cast<std::size_t>(model.platformBody())],
          data.T_dot[static_cast<std::size_t>(model.platformBody())]);
}

}  // namespace detail

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
