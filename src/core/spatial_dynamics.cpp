// The spatial NOC's velocity, acceleration and force stages: inverse dynamics, mass matrix,
// forward dynamics and energies, after the inverse kinematics of spatial.cpp.
#include "nocdyn/spatial.hpp"

#include <array>
#include <cmath>
#include <type_traits>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "nocdyn/detail/eigen_instances.hpp"
#include "spatial_small.hpp"

namespace nocdyn::spatial {

namespace {

using small::gramOf;
using small::invertInPlace;

using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// The motion cross product t x s = [w x a; w x m + v x a] (the rate of a screw s carried by a
/// body of twist t).
Vector6 cross(const Vector6& t, const Vector6& s) {
    Vector6 out;
    out.head<3>() = t.head<3>().cross(s.head<3>());
    out.tail<3>() = t.head<3>().cross(s.tail<3>()) + t.tail<3>().cross(s.head<3>());
    return out;
}

/// The inertia wrench less gravity of a body (mass m, c.o.m. c, inertia I about it, base frame)
/// of twist t and twist rate a referred to O, itself referred to O: [n_c + c x f; f].
Vector6 bodyWrench(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I, const Vector6& t, const Vector6& a,
                   const Eigen::Vector3d& g) {
    const Eigen::Vector3d w = t.head<3>();
    const Eigen::Vector3d v_c = t.tail<3>() + w.cross(c);
    const Eigen::Vector3d a_c = a.tail<3>() + a.head<3>().cross(c) + w.cross(v_c);
    const Eigen::Vector3d f = m * (a_c - g);
    const Eigen::Vector3d n = I * a.head<3>() + w.cross(I * w);
    Vector6 out;
    out.head<3>() = n + c.cross(f);
    out.tail<3>() = f;
    return out;
}

/// The spatial inertia about O of a body (mass m, c.o.m. c, inertia I about it, base frame): its
/// wrench [n_O; f] = M_b a at rest for a twist rate a = [dw; dv_O], with [c] the cross-product
/// matrix: f = m (dv_O - [c] dw), n_O = I dw + c x f.
Matrix6 spatialInertia(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I) {
    const Eigen::Matrix3d C = skew(c);
    Matrix6 out;
    out.topLeftCorner<3, 3>() = I - m * C * C;
    out.topRightCorner<3, 3>() = m * C;
    out.bottomLeftCorner<3, 3>() = -m * C;
    out.bottomRightCorner<3, 3>() = m * Eigen::Matrix3d::Identity();
    return out;
}

double kinetic(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I, const Vector6& t) {
    const Eigen::Vector3d w = t.head<3>();
    const Eigen::Vector3d v_c = t.tail<3>() + w.cross(c);
    return 0.5 * (m * v_c.squaredNorm() + w.dot(I * w));
}

/// The platform's angular velocity and its rate from the Euler angles' rates (R = Rz Ry Rx):
/// w = roll' u1 + pitch' u2 + yaw' e_z with u1 = Rz Ry e_x, u2 = Rz e_y.
void eulerAxes(const TaskVector& p, Eigen::Vector3d& u1, Eigen::Vector3d& u2) {
    const double pitch = p(4), yaw = p(5);
    const double cp = std::cos(pitch), sp = std::sin(pitch), cy = std::cos(yaw), sy = std::sin(yaw);
    u1 = Eigen::Vector3d(cy * cp, sy * cp, -sp);
    u2 = Eigen::Vector3d(-sy, cy, 0.0);
}
void angularRates(const TaskVector& p, const TaskVector& dp, const TaskVector& ddp, Eigen::Vector3d& w,
                  Eigen::Vector3d& dw) {
    Eigen::Vector3d u1, u2;
    eulerAxes(p, u1, u2);
    const Eigen::Vector3d ez = Eigen::Vector3d::UnitZ();
    w = dp(3) * u1 + dp(4) * u2 + dp(5) * ez;
    const Eigen::Vector3d w_zy = dp(5) * ez + dp(4) * u2;  // the frame Rz Ry's angular velocity
    dw = ddp(3) * u1 + ddp(4) * u2 + ddp(5) * ez + dp(3) * w_zy.cross(u1) + dp(4) * (dp(5) * ez.cross(u2));
}

/// The minimum-norm actuator forces A_E (A_E^T A_E)^-1 b of A_E^T tau = b (A_E^-T b when
/// square), A_E the last D columns of A; false when A_E^T A_E is singular.
template <int D>
bool actuatorForces(const ActuationMatrix& A, const Vector6& W_P, ActuatorVector& tau) {
    const auto AE = A.rightCols<D>();
    Eigen::Matrix<double, D, D, Eigen::RowMajor> G = gramOf<D>(AE);
    if (!invertInPlace<D>(G)) {
        tau.setConstant(std::numeric_limits<double>::quiet_NaN());
        return false;
    }
    const Eigen::Matrix<double, D, 1> lambda = G * W_P.tail<D>();
    tau.noalias() = AE * lambda;
    return true;
}

/// f(std::integral_constant<int, N>) for a limb of N freedoms (1 to 6): the per-limb stages at
/// fixed size.
template <class F>
void byFreedoms(int n, F&& f) {
    switch (n) {
        case 6:
            f(std::integral_constant<int, 6>{});
            break;
        case 5:
            f(std::integral_constant<int, 5>{});
            break;
        case 4:
            f(std::integral_constant<int, 4>{});
            break;
        case 3:
            f(std::integral_constant<int, 3>{});
            break;
        case 2:
            f(std::integral_constant<int, 2>{});
            break;
        default:
            f(std::integral_constant<int, 1>{});
            break;
    }
}

/// A limb's bodies' inertia at rest seen from the platform: K += sum_b T_b^T M_b T_b, with
/// T_b = J_(<=b) J^+ the body's twist per platform twist (eq. 3: the freedoms up to the body's last).
template <int N>
void addLimbInertia(const Limb& limb, const LimbData& ld, Matrix6& K) {
    const Eigen::Map<const Eigen::Matrix<double, 6, N>> J(ld.J.data());
    const Eigen::Map<const Eigen::Matrix<double, N, 6>> J_plus(ld.J_plus.data());
    Matrix6 T = Matrix6::Zero();
    int k = 0;
    for (std::size_t b = 0; b < limb.bodies.size(); ++b) {
        const Body& body = limb.bodies[b];
        for (; k <= body.last_freedom; ++k) T.noalias() += J.col(k) * J_plus.row(k);
        const Matrix6 MT = spatialInertia(body.mass, ld.com[b], ld.inertia[b]) * T;
        K.noalias() += T.transpose() * MT;
    }
}

/// One limb of N freedoms at fixed size: its rates, accelerations, bodies' twists and wrenches,
/// the joints' efforts f, and its part J^+T f of W_P.
template <int N>
void limbMotionAndForces(const Limb& limb, LimbData& ld, Data& data, const Eigen::Vector3d& g) {
    const Eigen::Map<const Eigen::Matrix<double, 6, N>> J(ld.J.data());
    const Eigen::Map<const Eigen::Matrix<double, N, 6>> J_plus(ld.J_plus.data());
    Eigen::Map<Eigen::Matrix<double, N, 1>> gd(ld.gd.data()), gdd(ld.gdd.data());
    // rates (eq. 3) and the screws' rates ds_k = t_(k-1) x s_k
    gd.noalias() = J_plus * data.t_P;
    Vector6 t = Vector6::Zero();
    Vector6 bias = Vector6::Zero();  // sum_k ds_k gd_k
    std::array<Vector6, N> ds_gd;
    for (int k = 0; k < N; ++k) {
        ds_gd[static_cast<std::size_t>(k)] = cross(t, J.col(k)) * gd(k);
        bias += ds_gd[static_cast<std::size_t>(k)];
        t += J.col(k) * gd(k);
    }
    gdd.noalias() = J_plus * (data.dt_P - bias);
    // the bodies' twists, twist rates and wrenches
    t.setZero();
    Vector6 alpha = Vector6::Zero();
    int k = 0;
    for (std::size_t b = 0; b < limb.bodies.size(); ++b) {
        const Body& body = limb.bodies[b];
        for (; k <= body.last_freedom; ++k) {
            t += J.col(k) * gd(k);
            alpha += J.col(k) * gdd(k) + ds_gd[static_cast<std::size_t>(k)];
        }
        ld.twist[b] = t;
        ld.twist_rate[b] = alpha;
        ld.wrench[b] = bodyWrench(body.mass, ld.com[b], ld.inertia[b], t, alpha, g);
    }
    // the joints' efforts: freedom k carries every body after it, plus its friction
    Eigen::Map<Eigen::Matrix<double, N, 1>> f(ld.effort.data());
    Vector6 outboard = Vector6::Zero();
    int b = static_cast<int>(limb.bodies.size()) - 1;
    for (int kk = N - 1; kk >= 0; --kk) {
        while (b >= 0 && limb.bodies[static_cast<std::size_t>(b)].last_freedom >= kk) {
            outboard += ld.wrench[static_cast<std::size_t>(b)];
            --b;
        }
        const Freedom& freedom = limb.freedoms[static_cast<std::size_t>(kk)];
        const double sign = gd(kk) > 0.0 ? 1.0 : (gd(kk) < 0.0 ? -1.0 : 0.0);
        f(kk) = J.col(kk).dot(outboard) + freedom.damping * gd(kk) + freedom.friction * sign;
    }
    data.W_P.noalias() += J_plus.transpose() * f;
}

/// The velocity, acceleration and force stages at (p, dp, ddp), after inverseKinematics(p):
/// the platform twist and its rate, every limb's rates, accelerations, bodies' twists and
/// wrenches, and W_P = w_P + sum_j J_j^+T f_j, with the weights of gravity g. With dp = 0 and
/// g = 0 (no friction at rest either), W_P is the inertia wrench of ddp alone: E^T W_P = M ddp.
void motionAndForces(const Model& model, Data& data, const TaskVector& p, const TaskVector& dp, const TaskVector& ddp,
                     const Eigen::Vector3d& g) {
    const int d = model.task_dimension;
    // the platform twist t_P = [w; v_O] and its rate, v_O = dp - w x p the velocity of the
    // platform point at O
    Eigen::Vector3d w = Eigen::Vector3d::Zero(), dw = Eigen::Vector3d::Zero();
    if (d == 6) angularRates(p, dp, ddp, w, dw);
    const Eigen::Vector3d r = p.head<3>(), v = dp.head<3>(), a = ddp.head<3>();
    data.t_P << w, v - w.cross(r);
    data.dt_P << dw, a - dw.cross(r) - w.cross(v);
    // the platform's own wrench
    const Eigen::Vector3d c_P = r + data.R * model.platform_com;
    const Eigen::Matrix3d I_P = data.R * model.platform_inertia * data.R.transpose();
    data.platform_wrench = bodyWrench(model.platform_mass, c_P, I_P, data.t_P, data.dt_P, g);
    data.W_P = data.platform_wrench;
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        byFreedoms(limb.size(), [&](auto n) { limbMotionAndForces<decltype(n)::value>(limb, ld, data, g); });
    }
    for (int a2 = 0; a2 < model.actuators; ++a2) {
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a2)];
        data.du(a2) = data.limb[static_cast<std::size_t>(j)].gd(k);
        data.ddu(a2) = data.limb[static_cast<std::size_t>(j)].gdd(k);
    }
}

}  // namespace

Status inverseDynamics(const Model& model, Data& data, const TaskVector& p, const TaskVector& dp,
                       const TaskVector& ddp) {
    const int d = model.task_dimension;
    if (dp.size() != d || ddp.size() != d || !dp.allFinite() || !ddp.allFinite()) {
        return {StatusCode::not_finite, -1, dp.sum() + ddp.sum()};
    }
    if (const Status status = inverseKinematics(model, data, p); !status) return status;
    motionAndForces(model, data, p, dp, ddp, model.gravity);
    // A_E^T tau = E^T W_P: the minimum-norm forces A_E (A_E^T A_E)^-1 E^T W_P (A_E^-T E^T W_P
    // when square)
    const bool solved =
        d == 6 ? actuatorForces<6>(data.A, data.W_P, data.tau) : actuatorForces<3>(data.A, data.W_P, data.tau);
    if (!solved || !data.tau.allFinite()) return {StatusCode::effort_exceeded, -1, data.tau.sum()};
    return {};
}

Status massMatrix(const Model& model, Data& data, const TaskVector& p, TaskMatrix& M) {
    if (const Status status = inverseKinematics(model, data, p); !status) return status;
    // At rest and without gravity W_P is linear in the platform's twist rate: W_P = K dt_P, with
    // K = M_P + sum_b T_b^T M_b T_b over every limb's bodies, and dt_P = E ddp =
    // [dw; a - dw x r], dw = ddp_3 u1 + ddp_4 u2 + ddp_5 e_z. Column i of M is W_P(p, 0, e_i)'s
    // last d rows: M = K E's.
    const int d = model.task_dimension;
    const Eigen::Vector3d r = p.head<3>();
    Matrix6 K = spatialInertia(model.platform_mass, r + data.R * model.platform_com,
                               data.R * model.platform_inertia * data.R.transpose());
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        byFreedoms(limb.size(), [&](auto n) { addLimbInertia<decltype(n)::value>(limb, ld, K); });
    }
    Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> E = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>::Zero(6, d);
    E.bottomLeftCorner<3, 3>().setIdentity();
    if (d == 6) {
        std::array<Eigen::Vector3d, 3> u;
        eulerAxes(p, u[0], u[1]);
        u[2] = Eigen::Vector3d::UnitZ();
        for (std::size_t k = 0; k < 3; ++k) {
            E.col(3 + static_cast<int>(k)).head<3>() = u[k];
            E.col(3 + static_cast<int>(k)).tail<3>() = r.cross(u[k]);
        }
    }
    M.noalias() = K.bottomRows(d) * E;
    return {};
}

Status forwardDynamics(const Model& model, Data& data, const TaskVector& p, const TaskVector& dp,
                       const ActuatorVector& tau, TaskVector& ddp) {
    const int d = model.task_dimension;
    if (dp.size() != d || !dp.allFinite() || tau.size() != model.actuators || !tau.allFinite()) {
        return {StatusCode::not_finite, -1, dp.sum() + tau.sum()};
    }
    // M, then the bias h = E^T W_P(p, dp, 0) with gravity and friction: E^T W_P(p, dp, ddp) =
    // M ddp + h
    TaskMatrix M;
    if (const Status status = massMatrix(model, data, p, M); !status) return status;
    const TaskVector rest = TaskVector::Zero(d);
    motionAndForces(model, data, p, dp, rest, model.gravity);
    const TaskVector h = data.W_P.tail(d);
    // M ddp = A_E^T tau - h
    const ActuationMatrix AE = data.A.rightCols(d);
    ddp = Eigen::PartialPivLU<TaskMatrix>(M).solve(AE.transpose() * tau - h);
    if (!ddp.allFinite()) return {StatusCode::not_finite, -1, ddp.sum()};
    motionAndForces(model, data, p, dp, ddp, model.gravity);
    data.tau = tau;
    return {};
}

double kineticEnergy(const Model& model, const Data& data) {
    const Eigen::Vector3d c_P = data.position + data.R * model.platform_com;
    const Eigen::Matrix3d I_P = data.R * model.platform_inertia * data.R.transpose();
    double energy = kinetic(model.platform_mass, c_P, I_P, data.t_P);
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        for (std::size_t b = 0; b < limb.bodies.size(); ++b) {
            energy += kinetic(limb.bodies[b].mass, ld.com[b], ld.inertia[b], ld.twist[b]);
        }
    }
    return energy;
}

double potentialEnergy(const Model& model, const Data& data) {
    double energy = -model.platform_mass * model.gravity.dot(data.position + data.R * model.platform_com);
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        for (std::size_t b = 0; b < limb.bodies.size(); ++b)
            energy -= limb.bodies[b].mass * model.gravity.dot(ld.com[b]);
    }
    return energy;
}

}  // namespace nocdyn::spatial
