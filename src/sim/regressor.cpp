// The regressor Y of tau = Y pi, body by body through the NOC (regressor.hpp).
#include "nocdyn/sim/regressor.hpp"

#include <cmath>

#include <Eigen/LU>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/detail/index.hpp"

namespace nocdyn {

namespace {

using WrenchRegressor = Eigen::Matrix<double, 3, kBodyParameters>;
using PlatformRegressor = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxParameters>;

using detail::at;
using detail::sign;

/// Y_w of one body (see the header): frame at r turned by phi (cos, sin), body twist referred to
/// O xi = [omega; v_O] and its rate, gravity g.
[[nodiscard]] WrenchRegressor bodyWrenchRegressor(double cos_phi, double sin_phi, const Vector2& r, const Twist& xi,
                                                  const Twist& xi_dot, const Vector2& g) {
    const double w = xi(0), dw = xi_dot(0);
    // acceleration of the body point at r: dv_O + domega E r + omega E v_O - omega^2 r
    const Vector2 a = xi_dot.tail<2>() + dw * perp(r) + w * perp(xi.tail<2>()) - w * w * r;
    const Vector2 a_bar = a - g;
    WrenchRegressor Yw;
    Yw.col(0) << cross(r, a_bar), a_bar;
    const Vector2 e[2] = {Vector2(cos_phi, sin_phi), Vector2(-sin_phi, cos_phi)};
    for (int k = 0; k < 2; ++k) {
        const Vector2 f = dw * perp(e[k]) - w * w * e[k];
        Yw.col(1 + k) << cross(e[k], a_bar) + cross(r, f), f;
    }
    Yw.col(3) << dw, 0.0, 0.0;
    return Yw;
}

}  // namespace

void regressor(const Model& model, const Data& data, RegressorMatrix& Y) {
    const int P = parameterCount(model);
    // W: the generalized force on xi_P per parameter (the lean path's W_P, column by column)
    PlatformRegressor W = PlatformRegressor::Zero(3, P);
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[at(j)];
        const LimbData& ld = data.limb[at(j)];
        // body twists xi_b and rates: xi_1 = s_1 q'_1, xi_2 = xi_1 + s_2 q'_2 (ds_1/dt = 0)
        const Twist xi_dot0 = ld.s[0] * ld.gamma_ddot(0);
        const Twist xi_dot1 = xi_dot0 + ld.s_dot[1] * ld.gamma_dot(1) + ld.s[1] * ld.gamma_ddot(1);
        // frame rotations: the R joint angles before each body
        const double c0 = ld.cos_q(0), s0 = ld.sin_q(0);
        const double c1 = c0 * ld.cos_q(1) - s0 * ld.sin_q(1), s1 = s0 * ld.cos_q(1) + c0 * ld.sin_q(1);
        const Vector2 r0 = ld.x[0] - Vector2(c0 * limb.com_home[0].x() - s0 * limb.com_home[0].y(),
                                             s0 * limb.com_home[0].x() + c0 * limb.com_home[0].y());
        const Vector2 r1 = ld.x[1] - Vector2(c1 * limb.com_home[1].x() - s1 * limb.com_home[1].y(),
                                             s1 * limb.com_home[1].x() + c1 * limb.com_home[1].y());
        const WrenchRegressor Y0 = bodyWrenchRegressor(c0, s0, r0, ld.xi[0], xi_dot0, model.gravity);
        const WrenchRegressor Y1 = bodyWrenchRegressor(c1, s1, r1, ld.xi[1], xi_dot1, model.gravity);
        // U_i^T Y_w,i with U_1 = s_1 e_1^T J_j^-1, U_2 = (s_1 e_1^T + s_2 e_2^T) J_j^-1
        const Vector3 row0 = ld.J_inv.row(0).transpose(), row1 = ld.J_inv.row(1).transpose();
        W.middleCols<kBodyParameters>(bodyParameterIndex(model.body(j, 0))) = row0 * (ld.s[0].transpose() * Y0);
        W.middleCols<kBodyParameters>(bodyParameterIndex(model.body(j, 1))) =
            row0 * (ld.s[0].transpose() * Y1) + row1 * (ld.s[1].transpose() * Y1);
        // joint friction to overcome: J_j^-T e_k (damping q'_k + friction sign q'_k)
        // (a two-DOF robot's last R joint turns with the fictitious theta, which the pose [x, y]
        // does not set: it takes no friction, and its columns stay zero)
        for (int k = 0; k < (model.task_dimension == 2 ? 2 : 3); ++k) {
            const int index = jointParameterIndex(model, j, k);
            W.col(index) = ld.J_inv.row(k).transpose() * ld.gamma_dot(k);
            W.col(index + 1) = ld.J_inv.row(k).transpose() * sign(ld.gamma_dot(k));
        }
    }
    W.middleCols<kBodyParameters>(bodyParameterIndex(model.platformBody())) = bodyWrenchRegressor(
        std::cos(data.p(0)), std::sin(data.p(0)), data.p.tail<2>(), data.xi_P, data.xi_P_dot, model.gravity);
    // tau from A^T tau = W: A^-T W = Xi^T W, or the minimum-norm A (A^T A)^-1 W
    Y.resize(model.actuators, P);
    if (model.coordinates == Coordinates::actuators) {
        Y.noalias() = data.Xi.transpose() * W;
    } else if (model.task_dimension == 2) {
        // translation: as detail::distribute, tau = A_E (A_E^T A_E)^-1 E^T S(c)^T W with S(c) E = [0; I]:
        // the force rows of W, A_E the x, y columns of A (the moment row is taken up by the last R joints)
        const Eigen::Matrix<double, Eigen::Dynamic, 2, 0, kMaxActuators, 2> A_E = data.A.rightCols<2>();
        const Eigen::Matrix2d N = A_E.transpose() * A_E;
        const Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, kMaxParameters> L = N.inverse() * W.bottomRows<2>();
        Y.noalias() = A_E * L;
    } else {
        const Matrix3 AtA = data.A.transpose() * data.A;
        const Matrix3 AtA_inv = AtA.inverse();
        PlatformRegressor L = AtA_inv * W;
        Y.noalias() = data.A * L;
    }
}

Status inverseDynamicsRegressor(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp,
                                RegressorMatrix& Y) {
    if (const Status status = inverseDisplacement(model, data, p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model, data, dp); !status) return status;
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(ddp(i))) return {StatusCode::not_finite, -1, ddp(i)};
    }
    accelerationFromPlatform(model, data, ddp);
    regressor(model, data, Y);
    return {};
}

}  // namespace nocdyn
