#include "nocdyn/spatial.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <type_traits>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>

#include "nocdyn/error.hpp"
#include "nocdyn/spatial_limits.hpp"
#include "spatial_chain.hpp"
#include "spatial_closed_form.hpp"

namespace nocdyn::spatial {

namespace {

using chain::carriedScrew;
using chain::freedomMove;
using chain::Move;

constexpr int kNewtonIterations = 50;
/// The largest change of a joint variable [rad, m] from the previous solution still taken as the
/// same branch of a closed form (a sample's step is far smaller, another branch far larger)
constexpr double kBranchJump = 0.5;
/// The same from home when there is no previous solution [rad, m]
constexpr double kHomeReach = 1.5;
constexpr double kClosure = 1e-13;  ///< Newton's residual [m, rad], for displacements within 1 m
/// The small matrices decomposed here (Gram matrices, at most 6 x 6): one instantiation each.
using Work = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
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

/// The largest over the smallest singular value of a matrix from the eigenvalues of its Gram
/// matrix (infinity when singular).
double conditionOf(const Work& gram) {
    const Eigen::SelfAdjointEigenSolver<Work> eig(gram, Eigen::EigenvaluesOnly);
    const double lo = eig.eigenvalues()(0), hi = eig.eigenvalues()(eig.eigenvalues().size() - 1);
    if (!(lo > 0.0)) return std::numeric_limits<double>::infinity();
    return std::sqrt(hi / lo);
}

/// The condition number of a limb's J with its twists referred to the platform's point p.
double limbCondition(const LimbData& ld, const Eigen::Vector3d& p) {
    LimbJacobian at_point = ld.J;
    for (int k = 0; k < at_point.cols(); ++k) {
        at_point.col(k).tail<3>() -= p.cross(Eigen::Vector3d(ld.J.col(k).head<3>()));
    }
    return conditionOf(at_point.transpose() * at_point);
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

bool finite(const TaskVector& v) { return v.allFinite(); }

/// The inverse of a small fixed-size matrix in place by Eigen's partial-pivoting LU at its fixed
/// size (no allocation; the dynamic-size LU and triangular solves go through their blocked
/// general paths); false when a pivot is zero or not finite.
template <int N>
bool invertInPlace(Eigen::Matrix<double, N, N, Eigen::RowMajor>& a) {
    const Eigen::PartialPivLU<Eigen::Matrix<double, N, N>> lu(a);
    const auto pivots = lu.matrixLU().diagonal().array();
    if (!pivots.isFinite().all() || !(pivots.abs() > 0.0).all()) return false;
    a = lu.inverse();
    return true;
}

/// The Gram matrix G = B^T B of an m x D matrix (m at most kMaxActuators), by rows.
template <int D, typename Matrix>
Eigen::Matrix<double, D, D, Eigen::RowMajor> gramOf(const Matrix& B) {
    Eigen::Matrix<double, D, D, Eigen::RowMajor> G = Eigen::Matrix<double, D, D, Eigen::RowMajor>::Zero();
    for (Eigen::Index r = 0; r < B.rows(); ++r) {
        const Eigen::Matrix<double, 1, D> row = B.row(r);
        G.noalias() += row.transpose() * row;
    }
    return G;
}

/// J^+ of a limb of N freedoms: J^-1 for six, (J^T J)^-1 J^T for fewer; NaN when singular (the
/// condition check then takes the exact value).
template <int N>
void leftInverse(LimbData& ld) {
    const Eigen::Map<const Eigen::Matrix<double, 6, N>> J(ld.J.data());
    Eigen::Matrix<double, N, N, Eigen::RowMajor> G;
    if constexpr (N == 6) {
        G = J;
    } else {
        G.noalias() = J.transpose() * J;
    }
    if (!invertInPlace<N>(G)) {
        ld.J_plus.setConstant(std::numeric_limits<double>::quiet_NaN());
        return;
    }
    if constexpr (N == 6) {
        ld.J_plus = G;
    } else {
        ld.J_plus.noalias() = G * J.transpose();
    }
}

/// The upper bound sqrt(trace G trace G^-1) of the condition number of the m x D actuation
/// map, G = A_task^T A_task; NaN when G is singular.
template <int D>
double actuationBound(const ActuationMatrix& A_task) {
    Eigen::Matrix<double, D, D, Eigen::RowMajor> G = gramOf<D>(A_task);
    const double trace = G.trace();
    if (!invertInPlace<D>(G)) return std::numeric_limits<double>::quiet_NaN();
    return std::sqrt(trace * G.trace());
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

/// One limb closed at the platform displacement D by Newton from q (J_j's left inverse for five
/// freedoms); false when it does not converge. On success, the current screws in ld.J.
bool closeLimb(const Limb& limb, const Move& D, LimbData& ld, double& residual) {
    const int n = limb.size();
    // the current screws into J, and the chain's displacement g(q)
    const auto chain = [&]() {
        Move g;
        for (int k = 0; k < n; ++k) {
            ld.J.col(k) = carriedScrew(limb.freedoms[static_cast<std::size_t>(k)], g);
            g = g.then(freedomMove(limb.freedoms[static_cast<std::size_t>(k)], ld.q(k)));
        }
        return g;
    };
    for (int iteration = 0; iteration < kNewtonIterations; ++iteration) {
        const Move g = chain();
        // the error twist d with exp(d) g = D: w = log(R_D R_g^T), v = t_D - t_g - w x t_g
        const Eigen::AngleAxisd rotation_error(D.R * g.R.transpose());
        Vector6 d;
        d.head<3>() = rotation_error.angle() * rotation_error.axis();
        d.tail<3>() = D.t - g.t - d.head<3>().cross(g.t);
        residual = d.cwiseAbs().maxCoeff();
        if (!std::isfinite(residual)) return false;
        // relative to the size of the displacement (rounding grows with it)
        const bool converged = residual <= kClosure * (1.0 + D.t.cwiseAbs().maxCoeff());
        const Eigen::HouseholderQR<LimbJacobian> qr(ld.J);
        const FreedomVector step = qr.solve(d);
        if (!step.allFinite()) return false;
        ld.q += step;
        // one step past convergence: q to rounding whatever the start (the previous sample's or
        // home), so that a sample's result does not depend on the samples before it
        if (converged) {
            (void)chain();
            return true;
        }
    }
    return false;
}

}  // namespace

Eigen::Matrix3d rotation(double roll, double pitch, double yaw) {
    return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
}

Model::Model(const SpatialRobotDescription& d)
    : name(d.name),
      motion(d.motion),
      task_dimension(d.taskDimension()),
      max_condition(d.max_condition),
      gravity(d.gravity),
      platform_mass(d.platform.mass),
      platform_com(d.platform.com),
      platform_inertia(d.platform.inertia) {
    home = d.home.head(task_dimension);
    home_rotation = rotation(d.home(3), d.home(4), d.home(5));
    for (std::size_t j = 0; j < d.limbs.size(); ++j) {
        const SpatialLimbDescription& ld = d.limbs[j];
        Limb limb;
        limb.name = ld.name;
        const auto add = [&](bool revolute, const Eigen::Vector3d& axis, const Eigen::Vector3d& point, int joint,
                             const SpatialJointDescription* source) {
            Freedom f;
            f.revolute = revolute;
            f.axis = axis.normalized();
            f.point = point;
            f.joint = joint;
            f.screw = carriedScrew(f, Move{});
            if (source != nullptr) {
                f.damping = source->damping;
                f.friction = source->friction;
                f.limits = source->limits;
                if (source->actuated) {
                    f.actuator = static_cast<int>(actuator.size());
                    actuator.emplace_back(static_cast<int>(j), static_cast<int>(limb.freedoms.size()));
                }
            }
            limb.freedoms.push_back(f);
        };
        for (std::size_t k = 0; k < ld.joints.size(); ++k) {
            const SpatialJointDescription& joint = ld.joints[k];
            const int jk = static_cast<int>(k);
            switch (joint.type) {
                case SpatialJointType::revolute:
                    add(true, joint.axis, joint.point, jk, &joint);
                    break;
                case SpatialJointType::prismatic:
                    add(false, joint.direction, Eigen::Vector3d::Zero(), jk, &joint);
                    break;
                case SpatialJointType::universal:
                    add(true, joint.axis1, joint.point, jk, nullptr);
                    add(true, joint.axis2, joint.point, jk, nullptr);
                    break;
                case SpatialJointType::spherical:
                    for (int e = 0; e < 3; ++e) add(true, Eigen::Vector3d::Unit(e), joint.point, jk, nullptr);
                    break;
            }
            if (k + 1 < ld.joints.size()) {  // body k moves with every freedom of joints 0..k
                const SpatialBodyDescription& b = ld.bodies[k];
                limb.bodies.push_back({b.mass, b.com, b.inertia, static_cast<int>(limb.freedoms.size()) - 1});
            }
        }
        std::vector<SpatialJointType> types(ld.joints.size());
        std::transform(ld.joints.begin(), ld.joints.end(), types.begin(),
                       [](const SpatialJointDescription& joint) { return joint.type; });
        closed_form::detect(limb, types);
        if (limb.size() > kMaxFreedoms || static_cast<int>(limb.bodies.size()) > kMaxBodies) {
            throw Error(d.source + ": " + ld.name + ": more than " + std::to_string(kMaxFreedoms) + " joint freedoms");
        }
        this->limb.push_back(std::move(limb));
    }
    actuators = static_cast<int>(actuator.size());
    if (actuators > kMaxActuators) {
        throw Error(d.source + ": more than " + std::to_string(kMaxActuators) + " actuators");
    }
    if (actuators < task_dimension) {
        throw Error(d.source + ": " + std::to_string(actuators) + " actuators for " + std::to_string(task_dimension) +
                    " pose coordinates");
    }
}

std::vector<std::string> Model::coordinates() const {
    if (task_dimension == 3) return {"x", "y", "z"};
    return {"x", "y", "z", "roll", "pitch", "yaw"};
}

Data::Data(const Model& model)
    : limb(static_cast<std::size_t>(model.limbs())),
      A(model.actuators, 6),
      A_task(model.actuators, model.task_dimension),
      u(model.actuators),
      du(model.actuators),
      ddu(model.actuators),
      tau(model.actuators) {
    for (int j = 0; j < model.limbs(); ++j) {
        const int n = model.limb[static_cast<std::size_t>(j)].size();
        LimbData& ld = limb[static_cast<std::size_t>(j)];
        ld.q = FreedomVector::Zero(n);
        ld.gd = FreedomVector::Zero(n);
        ld.gdd = FreedomVector::Zero(n);
        ld.J = LimbJacobian::Zero(6, n);
        ld.J_plus = LimbInverse::Zero(n, 6);
        ld.effort = FreedomVector::Zero(n);
        ld.joint_point.fill(Eigen::Vector3d::Zero());
    }
    A.setZero();
    u.setZero();
    du.setZero();
    ddu.setZero();
    tau.setZero();
}

Status inverseKinematics(const Model& model, Data& data, const TaskVector& p) {
    if (p.size() != model.task_dimension || !finite(p)) return {StatusCode::not_finite, -1, p.sum()};
    const bool full = model.task_dimension == 6;
    if (full && !(std::abs(std::cos(p(4))) > 1e-9)) return {StatusCode::not_finite, -1, p(4)};
    data.R = full ? rotation(p(3), p(4), p(5)) : Eigen::Matrix3d::Identity();
    data.position = p.head<3>();
    // D: the platform's displacement from home, x -> R R_h^T (x - p_h) + p
    Move D;
    D.R = data.R * model.home_rotation.transpose();
    D.t = data.position - D.R * model.home.head<3>();
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        const int n = limb.size();
        // the closed form where the limb has one; it must close the chain as Newton would
        const FreedomVector previous = ld.q;
        bool closed = limb.solver != LimbSolver::newton && closed_form::solve(limb, D, ld.q);
        // Newton's branch decides where the closed form's root may not be it: away from the
        // previous solution (another assembly or working mode), or with no previous solution a
        // quarter turn or more from home
        if (closed) {
            const double distance = ld.closed ? (ld.q - previous).cwiseAbs().maxCoeff() : ld.q.cwiseAbs().maxCoeff();
            if (!(distance < (ld.closed ? kBranchJump : kHomeReach))) closed = false;
        }
        for (int pass = 0; pass < 2; ++pass) {
            if (!closed) {
                ld.q = previous;
                double residual = 0.0;
                if (!ld.closed || !closeLimb(limb, D, ld, residual)) {
                    ld.q.setZero();  // again from home
                    if (!closeLimb(limb, D, ld, residual)) {
                        ld.closed = false;
                        return {StatusCode::unreachable, j, residual};
                    }
                }
            }
            // one pass down the chain: the current screws s_k into J, the bodies' c.o.m. and
            // inertia (body b moves with the freedoms up to its last, and so does the point of
            // the joint after it)
            Move g;
            std::size_t b = 0;
            ld.joint_point[0] = limb.freedoms.front().point;
            for (int k = 0; k < n; ++k) {
                const Freedom& f = limb.freedoms[static_cast<std::size_t>(k)];
                ld.J.col(k) = carriedScrew(f, g);
                g = g.then(freedomMove(f, ld.q(k)));
                if (b < limb.bodies.size() && limb.bodies[b].last_freedom == k) {
                    const Body& body = limb.bodies[b];
                    ld.com[b] = g.R * body.com + g.t;
                    ld.inertia[b] = g.R * body.inertia * g.R.transpose();
                    ld.joint_point[b + 1] = g.R * limb.freedoms[static_cast<std::size_t>(k) + 1].point + g.t;
                    ++b;
                }
            }
            if (!closed) break;
            // the closed form's chain closes at D to Newton's tolerance, or Newton takes over
            const double error = std::max((g.R - D.R).cwiseAbs().maxCoeff(), (g.t - D.t).cwiseAbs().maxCoeff());
            if (error <= kClosure * (1.0 + D.t.cwiseAbs().maxCoeff())) break;
            closed = false;
        }
        ld.closed = true;
        ld.closed_form = closed;
        // J^+ = J^-1 for six freedoms, (J^T J)^-1 J^T for fewer
        if (n == 6) {
            leftInverse<6>(ld);
        } else if (n == 5) {
            leftInverse<5>(ld);
        } else {
            const Work gram = ld.J.transpose() * ld.J;
            ld.J_plus = Eigen::PartialPivLU<Work>(gram).solve(Work(ld.J.transpose()));
        }
        // the condition number of J with its twists referred to the platform's point
        // (J_P = X J, s = [a; m - p x a]), which does not depend on where O is: at most
        // ||J_P||_F ||L||_F for its left inverse L = J^+ X^-1 (rows [l_w + l_v x p, l_v]); the
        // exact value only when that bound exceeds the limit
        double J_norm = 0.0, L_norm = 0.0;
        for (int k = 0; k < n; ++k) {
            const Eigen::Vector3d a = ld.J.col(k).head<3>(), m = ld.J.col(k).tail<3>();
            const Eigen::Vector3d l_w = ld.J_plus.row(k).head<3>().transpose();
            const Eigen::Vector3d l_v = ld.J_plus.row(k).tail<3>().transpose();
            J_norm += a.squaredNorm() + (m - data.position.cross(a)).squaredNorm();
            L_norm += (l_w + l_v.cross(data.position)).squaredNorm() + l_v.squaredNorm();
        }
        ld.condition = std::sqrt(J_norm * L_norm);
        if (!(ld.condition <= model.max_condition)) {
            ld.condition = limbCondition(ld, data.position);
            if (!(ld.condition <= model.max_condition)) return {StatusCode::singular_limb, j, ld.condition};
        }
    }
    for (int a = 0; a < model.actuators; ++a) {
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        data.u(a) = ld.q(k);
        data.A.row(a) = ld.J_plus.row(k);
    }
    // the actuation map over the task's rates at the platform's point, and its condition number:
    // t_P = [w; v - w x p] gives du = A_v . v + (A_w + A_v x p) . w
    const int d = model.task_dimension;
    data.A_task.resize(model.actuators, d);
    for (int a = 0; a < model.actuators; ++a) {
        const Eigen::Vector3d A_w = data.A.row(a).head<3>().transpose(), A_v = data.A.row(a).tail<3>().transpose();
        data.A_task.row(a).head<3>() = A_v.transpose();
        if (d == 6) data.A_task.row(a).tail<3>() = (A_w + A_v.cross(data.position)).transpose();
    }
    // its condition number at most sqrt(trace G trace G^-1), G = A_task^T A_task (the sum of
    // the squared singular values times that of their inverses); the exact value only when
    // that bound exceeds the limit
    data.actuation_condition = d == 6 ? actuationBound<6>(data.A_task) : actuationBound<3>(data.A_task);
    if (!(data.actuation_condition <= model.max_condition)) {
        data.actuation_condition = conditionOf(Work(data.A_task.transpose() * data.A_task));
        if (!(data.actuation_condition <= model.max_condition)) {
            return {StatusCode::singular_actuation, -1, data.actuation_condition};
        }
    }
    return {};
}

void conditionNumbers(const Model& model, Data& data) {
    for (LimbData& ld : data.limb) ld.condition = limbCondition(ld, data.position);
    data.actuation_condition = conditionOf(Work(data.A_task.transpose() * data.A_task));
    (void)model;
}

namespace {

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
    if (dp.size() != d || ddp.size() != d || !finite(dp) || !finite(ddp)) {
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
    if (dp.size() != d || !finite(dp) || tau.size() != model.actuators || !tau.allFinite()) {
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

std::string describe(const Status& status, const Model& model) {
    std::ostringstream out;
    out.precision(6);
    const std::string limb = status.limb >= 0 && status.limb < model.limbs()
                                 ? "limb " + std::to_string(status.limb + 1) + " (" +
                                       model.limb[static_cast<std::size_t>(status.limb)].name + ")"
                                 : std::string("the robot");
    switch (status.code) {
        case StatusCode::ok:
            return "ok";
        case StatusCode::unreachable:
            out << "pose out of reach: " << limb << " cannot close (residual " << status.value << " m or rad)";
            return out.str();
        case StatusCode::singular_limb:
            out << "singular posture: " << limb << ": its Jacobian J has condition number " << status.value
                << " (limit " << model.max_condition << ")";
            return out.str();
        case StatusCode::singular_actuation:
            out << "actuation singularity: the map from the platform twist to the actuator rates has condition number "
                << status.value << " (limit " << model.max_condition << ")";
            return out.str();
        case StatusCode::not_finite:
            return "a pose, rate or acceleration is not finite, or the pitch is at +-90 degrees";
        case StatusCode::joint_limit_exceeded:
        case StatusCode::velocity_exceeded:
        case StatusCode::effort_exceeded:
            return describeLimit(status, model);  // spatial_limits.hpp
        default:
            out << "the inverse dynamics failed (" << status.value << ")";
            return out.str();
    }
}

}  // namespace nocdyn::spatial
