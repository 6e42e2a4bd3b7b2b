// 3-PRR inverse displacement (Appendix A, eqs. 35-42) and velocity kinematics (eqs. 3-8, 29).
#include "nocdyn/prr3/kinematics.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/LU>

namespace nocdyn::prr3 {

Status inverseDisplacement(const Model& model, Data& data, const Pose& p) {
    data.p = p;
    const double c = std::cos(p(0));
    const double s = std::sin(p(0));
    const Vector2 centre = p.tail<2>();
    for (int j = 0; j < kLimbs; ++j) {
        const Vector2& v = model.M_local[j];
        // eq. 41: M_j = C + r [cos, sin](theta + phi_j - pi/6)
        data.Mj[j] = centre + Vector2(c * v.x() - s * v.y(), s * v.x() + c * v.y());
        // eqs. 37-38, signed: d_j^M = n_j . (M_j - B_j), positive inside the base triangle
        const double d = model.n[j].dot(data.Mj[j] - model.B[j]);
        data.d_M(j) = d;
        if (!(d > 0.0 && d < model.l)) return {StatusCode::outside_workspace, j, d};
        // eq. 39: phi_Aj = asin(d_j^M / l) in (0, pi/2); phi_Mj = pi + theta - phi_Aj
        const double sin_A = d / model.l;
        const double cos_A = std::sqrt((1.0 - sin_A) * (1.0 + sin_A));
        data.sin_phi_A(j) = sin_A;
        data.cos_phi_A(j) = cos_A;
        data.phi_A(j) = std::asin(sin_A);
        data.phi_M(j) = std::numbers::pi + p(0) - data.phi_A(j);
        // eq. 40: m_j = l [cos, sin](phi_Aj + phi_j)
        data.m[j] = model.l * (cos_A * model.e[j] + sin_A * model.n[j]);
        data.A[j] = data.Mj[j] - data.m[j];
        data.u(j) = model.e[j].dot(data.A[j] - model.B[j]) - model.s_ref[j];
        // eqs. 41-42: p_Mj = M_j C, p_Aj = A_j C = m_j + p_Mj
        data.p_M[j] = centre - data.Mj[j];
        data.p_A[j] = centre - data.A[j];
    }
    return {};
}

namespace {

/// J_j (eq. 4a), H and D (eqs. 6-7), their inverses and conditioning.
Status jacobians(const Model& model, Data& data) {
    for (int j = 0; j < kLimbs; ++j) {
        // eq. 4a: J_j = [0 1 1; e_j E p_Aj E p_Mj]
        data.J[j].col(0) = prismaticTwist(model.e[j]);
        data.J[j].col(1) = revoluteTwist(data.p_A[j]);
        data.J[j].col(2) = revoluteTwist(data.p_M[j]);
        // eq. 7 as a reciprocal product: row j of H is the wrench of a unit force along
        // f_j = m_j / l through M_j, expressed at C: [(M_j - C) x f_j, f_j^T]; the
        // moment equals r sin(phi_Mj - pi/6) and f_j = [cos, sin](phi_Aj + phi_j).
        const Vector2 f = data.m[j] / model.l;
        data.H(j, 0) = cross(-data.p_M[j], f);
        data.H(j, 1) = f.x();
        data.H(j, 2) = f.y();
        // eq. 6: d_j = cos phi_Aj
        data.D(j) = data.cos_phi_A(j);
    }
    // D is singular when a link is normal to its rail (then J_j is singular too:
    // det J_j = e_j . m_j = l d_j).
    int weakest = 0;
    data.D.minCoeff(&weakest);
    data.cond_D = data.D.maxCoeff() / data.D(weakest);
    if (!(data.cond_D <= model.parameters.max_condition)) {
        return {StatusCode::singular_inverse_jacobian, weakest, data.cond_D};
    }
    // 1-norm condition number of H diag(1/r, 1, 1): the first column of H is a length.
    data.H_inv = data.H.inverse();
    const Vector3 scale(1.0 / model.r, 1.0, 1.0);
    const double norm_H = (data.H * scale.asDiagonal()).cwiseAbs().colwise().sum().maxCoeff();
    const double norm_H_inv = (scale.cwiseInverse().asDiagonal() * data.H_inv).cwiseAbs().colwise().sum().maxCoeff();
    data.cond_H = norm_H * norm_H_inv;
    if (!(data.cond_H <= model.parameters.max_condition)) {
        return {StatusCode::singular_forward_jacobian, -1, data.cond_H};
    }
    for (int j = 0; j < kLimbs; ++j) data.J_inv[j] = data.J[j].inverse();
    return {};
}

/// eq. 3: gamma_dot_j = J_j^{-1} t_M (the passive joint rates of eq. 29).
void limbRates(Data& data) {
    for (int j = 0; j < kLimbs; ++j) data.gamma_dot[j].noalias() = data.J_inv[j] * data.t_M;
}

}  // namespace

Status velocityFromPlatformTwist(const Model& model, Data& data, const Twist& t_M) {
    if (const Status status = jacobians(model, data); !status) return status;
    data.t_M = t_M;
    // eq. 5: du = D^{-1} H t_M
    data.du = (data.H * t_M).cwiseQuotient(data.D);
    limbRates(data);
    return {};
}

Status velocityFromActuatorRates(const Model& model, Data& data, const JointVector& du) {
    if (const Status status = jacobians(model, data); !status) return status;
    data.du = du;
    // eq. 5: t_M = H^{-1} D du
    data.t_M.noalias() = data.H_inv * data.D.cwiseProduct(du);
    limbRates(data);
    return {};
}

void actuatorAccelerations(Data& data, const Twist& t_M_dot) {
    data.t_M_dot = t_M_dot;
    // d/dt of eq. 5: D ddu = H dt_M + dH t_M - dD du
    data.ddu = (data.H * t_M_dot + data.H_dot * data.t_M - data.D_dot.cwiseProduct(data.du)).cwiseQuotient(data.D);
}

void platformAcceleration(Data& data, const JointVector& ddu) {
    data.ddu = ddu;
    // d/dt of eq. 5: H dt_M = D ddu + dD du - dH t_M
    data.t_M_dot.noalias() =
        data.H_inv * (data.D.cwiseProduct(ddu) + data.D_dot.cwiseProduct(data.du) - data.H_dot * data.t_M);
}

Status checkStroke(const Model& model, const Data& data) {
    const double half = 0.5 * model.parameters.stroke;
    for (int j = 0; j < kLimbs; ++j) {
        if (!(std::abs(data.u(j)) <= half)) return {StatusCode::stroke_exceeded, j, data.u(j)};
    }
    return {};
}

}  // namespace nocdyn::prr3
