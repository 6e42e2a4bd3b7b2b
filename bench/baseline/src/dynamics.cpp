// 3-PRR twist-shaping matrices (eqs. 24-31), their exact time derivatives, and the
// NOC dynamics (eqs. 20-23).
#include "nocdyn/prr3/dynamics.hpp"

#include <cmath>

#include "nocdyn/prr3/kinematics.hpp"

namespace nocdyn::prr3 {

void twistShaping(const Model& model, Data& data) {
    const double omega = data.t_M(0);
    const Vector2 c_dot = data.t_M.tail<2>();
    const double ratio = model.l_c / model.l;

    // dH/dt and dD/dt, row by row, from the rates of the limb geometry.
    for (int j = 0; j < kLimbs; ++j) {
        const double phi_A_dot = data.gamma_dot[j](1);
        const Vector2 f = data.m[j] / model.l;
        const Vector2 f_dot = phi_A_dot * perp(f);  // f_j turns at dphi_Aj
        const Vector2 a = -data.p_M[j];             // M_j - C
        const Vector2 a_dot = omega * perp(a);      // M_j - C turns with the MP
        data.H_dot(j, 0) = cross(a_dot, f) + cross(a, f_dot);
        data.H_dot.block<1, 2>(j, 1) = f_dot.transpose();
        data.D_dot(j) = -data.sin_phi_A(j) * phi_A_dot;  // d/dt cos phi_Aj
    }

    // eq. 31: T_7 = H^{-1} D, and dT_7 = H^{-1} (dD - dH T_7)
    ShapingMatrix& T_7 = data.T[kPlatformBody];
    ShapingMatrix& T_7_dot = data.T_dot[kPlatformBody];
    T_7.noalias() = data.H_inv * data.D.asDiagonal();
    Matrix3 rhs = data.D_dot.asDiagonal();
    rhs.noalias() -= data.H_dot * T_7;
    T_7_dot.noalias() = data.H_inv * rhs;

    for (int j = 0; j < kLimbs; ++j) {
        // eqs. 25-27: T_j = [0; e_j] in column j; constant, so dT_j = 0
        ShapingMatrix& T_slider = data.T[sliderBody(j)];
        T_slider.setZero();
        T_slider.col(j) = prismaticTwist(model.e[j]);
        data.T_dot[sliderBody(j)].setZero();

        // eq. 29: gamma_dot_j = J_j^{-1} H^{-1} D du = X du
        const Matrix3 X = data.J_inv[j] * T_7;
        // d/dt J_j: only its lower rows move, E dp_Aj (column 1) and E dp_Mj (column 2), so
        // dX = J_j^{-1} (dT_7 - dJ_j X) with dJ_j X = [0; E dp_Aj X(1,:) + E dp_Mj X(2,:)]
        const Vector2 p_A_dot = c_dot - data.du(j) * model.e[j];
        const Vector2 p_M_dot = omega * perp(data.p_M[j]);
        Matrix3 X_rhs = T_7_dot;
        X_rhs.bottomRows<2>().noalias() -= perp(p_A_dot) * X.row(1);
        X_rhs.bottomRows<2>().noalias() -= perp(p_M_dot) * X.row(2);
        const Matrix3 X_dot = data.J_inv[j] * X_rhs;

        // eq. 30: T_{j+3} = U_{j+3} X with eq. 28b, U_{j+3} = [0 1 0; e_j (l_c/l) E m_j 0]:
        // row 0 is X(1,:), rows 1-2 are e_j X(0,:) + (l_c/l) E m_j X(1,:)
        const Vector2 k = ratio * perp(data.m[j]);
        ShapingMatrix& T_link = data.T[linkBody(j)];
        T_link.row(0) = X.row(1);
        T_link.bottomRows<2>().noalias() = model.e[j] * X.row(0);
        T_link.bottomRows<2>().noalias() += k * X.row(1);
        // dT_{j+3} = dU_{j+3} X + U_{j+3} dX, where m_j turns at dphi_Aj, so the only moving
        // column of U_{j+3} has rate (l_c/l) dphi_Aj E E m_j = -(l_c/l) dphi_Aj m_j
        const Vector2 k_dot = -ratio * data.gamma_dot[j](1) * data.m[j];
        ShapingMatrix& T_link_dot = data.T_dot[linkBody(j)];
        T_link_dot.row(0) = X_dot.row(1);
        T_link_dot.bottomRows<2>().noalias() = model.e[j] * X_dot.row(0);
        T_link_dot.bottomRows<2>().noalias() += k * X_dot.row(1);
        T_link_dot.bottomRows<2>().noalias() += k_dot * X.row(1);
    }
}

void jointSpaceDynamics(const Model& model, Data& data) {
    // eq. 23, sliders (eqs. 25-27): T_j is [0; e_j] in column j alone, so its term of I is
    // m_j e_j . e_j = m_j at (j, j); dT_j = 0 adds nothing to C.
    data.I.setZero();
    data.C.setZero();
    for (int j = 0; j < kLimbs; ++j) data.I(j, j) = model.M[sliderBody(j)].mass * model.e[j].squaredNorm();
    // eq. 23, links and platform: the general NOC terms T_i^T M_i T_i and T_i^T M_i dT_i
    for (int i = linkBody(0); i < kBodies; ++i) {
        noc::addInertia(model.M[i], data.T[i], data.I);
        noc::addCoriolis(model.M[i], data.T[i], data.T_dot[i], data.C);
    }
}

void actuatorForces(Data& data) { noc::inverseDynamics(data.I, data.C, data.du, data.ddu, data.tau); }

Status inverseDynamics(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp) {
    if (const Status status = inverseDisplacement(model, data, p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model, data, dp); !status) return status;
    twistShaping(model, data);
    actuatorAccelerations(data, ddp);
    jointSpaceDynamics(model, data);
    actuatorForces(data);
    return {};
}

Status checkForce(const Model& model, const Data& data) {
    for (int j = 0; j < kLimbs; ++j) {
        if (!(std::abs(data.tau(j)) <= model.parameters.peak_force)) {
            return {StatusCode::force_exceeded, j, data.tau(j)};
        }
    }
    return {};
}

double kineticEnergy(const Model& model, const Data& data) {
    double energy = 0.0;
    for (int i = 0; i < kBodies; ++i) energy += nocdyn::kineticEnergy(model.M[i], data.T[i] * data.du);
    return energy;
}

}  // namespace nocdyn::prr3
