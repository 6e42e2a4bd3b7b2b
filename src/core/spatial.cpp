// The spatial model (the limbs' freedoms and bodies from a file), its inverse kinematics with
// the limbs' and the actuation's Jacobians and condition numbers, and the status words; the
// dynamics stages are in spatial_dynamics.cpp.
#include "nocdyn/spatial.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>

#include "nocdyn/detail/eigen_instances.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/spatial_limits.hpp"
#include "spatial_chain.hpp"
#include "spatial_closed_form.hpp"
#include "spatial_small.hpp"

namespace nocdyn::spatial {

namespace {

using chain::carriedScrew;
using chain::freedomMove;
using chain::Move;
using small::gramOf;
using small::invertInPlace;

constexpr int kNewtonIterations = 50;
/// The largest change of a joint variable [rad, m] from the previous solution still taken as the
/// same branch of a closed form (a sample's step is far smaller, another branch far larger)
constexpr double kBranchJump = 0.5;
/// The same from home when there is no previous solution [rad, m]
constexpr double kHomeReach = 1.5;
constexpr double kClosure = 1e-13;  ///< Newton's residual [m, rad], for displacements within 1 m
/// The small matrices decomposed here (Gram matrices, at most 6 x 6): one instantiation each.
using Work = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

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

bool finite(const TaskVector& v) { return v.allFinite(); }

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