// Forward dynamics of the general planar parallel robot in the platform coordinates
// (forward_dynamics.hpp).
#include "nocdyn/sim/forward_dynamics.hpp"

#include <cmath>

#include <Eigen/Cholesky>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/kinematics.hpp"
#include "../core/stages.hpp"

namespace nocdyn {

void platformDynamics(const Model& model, Data& data) {
    // eq. 23 with the shaping matrices of v = dp/dt: xi_P = S(c) dp/dt. Xi and dXi/dt keep the
    // model's coordinates (the actuator-rate stages use them); T_i, I, C and Q_gf are in the
    // platform coordinates, as data.coordinates says.
    const Matrix3 Xi = data.Xi;
    const Matrix3 Xi_dot = data.Xi_dot;
    detail::platformCoordinates(data);
    detail::shapeBodies(model, data);
    data.coordinates = Coordinates::platform;
    jointSpaceDynamics(model, data);
    data.M_p = data.I;
    data.h_p.noalias() = data.C * data.t_M;
    data.h_p += data.Q_gf;
    if (model.coordinates == Coordinates::actuators) {
        data.Xi = Xi;
        data.Xi_dot = Xi_dot;
    }
}

Status forwardDynamics(const Model& model, Data& data, const Pose& p, const Twist& dp, const ActuatorVector& tau) {
    if (const Status status = inverseDisplacement(model, data, p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model, data, dp); !status) return status;
    for (int a = 0; a < model.actuators; ++a) {
        if (!std::isfinite(tau(a))) return {StatusCode::not_finite, -1, tau(a)};
    }
    platformDynamics(model, data);
    // generalized actuator force A_p^T tau = S(c)^T (A^T tau)
    Vector3 w = Vector3::Zero();
    for (int a = 0; a < model.actuators; ++a) w.noalias() += tau(a) * data.A.row(a).transpose();
    const Vector3 rhs = poseForceOfPlatformWrench(data.p.tail<2>(), w) - data.h_p;
    Twist ddp;
    if (model.task_dimension == 2) {
        // translation: theta is no coordinate (its row and column of M_p are zero: a rotation
        // about C moves no body), so M_t ddp_t = E^T (A_p^T tau - h_p), M_t = E^T M_p E, and
        // ddp = E ddp_t: theta's acceleration is exactly 0
        const Matrix2 M_t = data.M_p.bottomRightCorner<2, 2>();
        const Eigen::LLT<Matrix2> llt(M_t);
        if (llt.info() != Eigen::Success) return {StatusCode::singular_mass_matrix, -1, M_t.diagonal().minCoeff()};
        const Vector2 ddp_t = llt.solve(rhs.tail<2>());
        ddp = Twist(0.0, ddp_t(0), ddp_t(1));
    } else {
        const Eigen::LLT<Matrix3> llt(data.M_p);
        if (llt.info() != Eigen::Success) return {StatusCode::singular_mass_matrix, -1, data.M_p.diagonal().minCoeff()};
        ddp = llt.solve(rhs);
    }
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(ddp(i))) return {StatusCode::not_finite, -1, ddp(i)};
    }
    data.tau = tau;
    accelerationFromPlatform(model, data, ddp);
    return {};
}

}  // namespace nocdyn
