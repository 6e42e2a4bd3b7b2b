#include "nocdyn/spatial_reactions.hpp"

#include <algorithm>
#include <cstddef>

#include <Eigen/Geometry>
#include <Eigen/QR>

namespace nocdyn::spatial {

namespace {

/// Constraint wrenches of all limbs, at most six per limb.
constexpr int kMaxConstraints = 6 * 6;
using Constraints = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxConstraints>;
using ConstraintAmounts = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxConstraints, 1>;
using Square6 = Eigen::Matrix<double, 6, 6>;

/// Rank decisions on J_j's columns (unit rotation axes, lengths in metres).
constexpr double kRankTolerance = 1e-10;

char letterOf(const Limb& limb, int joint) {
    int count = 0;
    bool revolute = true;
    for (const Freedom& f : limb.freedoms) {
        if (f.joint != joint) continue;
        ++count;
        revolute = f.revolute;
    }
    if (count == 1) return revolute ? 'R' : 'P';
    return count == 2 ? 'U' : 'S';
}

}  // namespace

Reactions::Reactions(const Model& model)
    : joint(static_cast<std::size_t>(model.limbs())),
      platform(static_cast<std::size_t>(model.limbs()), Vector6::Zero()),
      nullity(static_cast<std::size_t>(model.limbs()), 0) {
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const int joints = limb.freedoms.back().joint + 1;
        auto& row = joint[static_cast<std::size_t>(j)];
        row.resize(static_cast<std::size_t>(joints));
        for (int k = 0; k < joints; ++k) row[static_cast<std::size_t>(k)].type = letterOf(limb, k);
    }
}

Status jointReactions(const Model& model, const Data& data, Reactions& out) {
    // F_j's particular part J_j^+T (tau_j - f_j), and a basis of null(J_j^T): the columns of
    // J_j's QR factor Q beyond its rank
    Constraints C(6, 0);
    Vector6 residual = data.platform_wrench;  // w_P - sum_j F_j
    for (int j = 0; j < model.limbs(); ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        FreedomVector g = -ld.effort;
        for (int a = 0; a < model.actuators; ++a) {
            const auto [limb_of, freedom] = model.actuator[static_cast<std::size_t>(a)];
            if (limb_of == j) g(freedom) += data.tau(a);
        }
        Vector6& F = out.platform[static_cast<std::size_t>(j)];
        F.noalias() = ld.J_plus.transpose() * g;
        residual -= F;
        Eigen::ColPivHouseholderQR<LimbJacobian> qr(ld.J);
        qr.setThreshold(kRankTolerance);
        const auto nullity = static_cast<int>(6 - qr.rank());
        out.nullity[static_cast<std::size_t>(j)] = nullity;
        if (nullity > 0) {
            const Square6 Q = qr.householderQ() * Square6::Identity();
            const Eigen::Index first = C.cols();
            C.conservativeResize(Eigen::NoChange, first + nullity);
            C.middleCols(first, nullity) = Q.rightCols(nullity);
        }
    }
    // the constraint wrenches' amounts: C lambda = w_P - sum_j F_j (least squares, minimum norm)
    ConstraintAmounts lambda = ConstraintAmounts::Zero(C.cols());
    if (C.cols() > 0) lambda = Eigen::CompleteOrthogonalDecomposition<Constraints>(C).solve(residual);
    Eigen::Index used = 0;
    Vector6 balance = data.platform_wrench;
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        Vector6& F = out.platform[static_cast<std::size_t>(j)];
        const int nullity = out.nullity[static_cast<std::size_t>(j)];
        if (nullity > 0) {
            F.noalias() += C.middleCols(used, nullity) * lambda.segment(used, nullity);
            used += nullity;
        }
        balance -= F;
        // the wrench through each listed joint, from the platform inwards: body k is outboard of
        // joint k, the last joint joins the last body to the platform
        Vector6 W = F;
        auto& reactions = out.joint[static_cast<std::size_t>(j)];
        const int joints = static_cast<int>(reactions.size());
        for (int k = joints - 1; k >= 0; --k) {
            if (k < joints - 1) W += ld.wrench[static_cast<std::size_t>(k)];
            JointReaction& r = reactions[static_cast<std::size_t>(k)];
            r.wrench = W;
            r.point = r.type != 'P'    ? ld.joint_point[static_cast<std::size_t>(k)]
                      : k < joints - 1 ? ld.com[static_cast<std::size_t>(k)]
                                       : data.position;
            r.force = W.tail<3>();
            r.moment = W.head<3>() - r.point.cross(r.force);
            // the efforts along the joint's freedoms out: its direction from the force, its
            // rotation axes (orthonormalised) from the moment
            Eigen::Matrix3d axes = Eigen::Matrix3d::Zero();
            int count = 0;
            for (int f = 0; f < limb.size(); ++f) {
                if (limb.freedoms[static_cast<std::size_t>(f)].joint != k) continue;
                if (!limb.freedoms[static_cast<std::size_t>(f)].revolute) {
                    const Eigen::Vector3d d = ld.J.col(f).tail<3>().normalized();
                    r.force -= d.dot(r.force) * d;
                    continue;
                }
                Eigen::Vector3d axis = ld.J.col(f).head<3>();
                for (int c = 0; c < count; ++c) axis -= axes.col(c).dot(axis) * axes.col(c);
                if (axis.norm() <= kRankTolerance) continue;
                axes.col(count++) = axis.normalized();
            }
            for (int c = 0; c < count; ++c) r.moment -= axes.col(c).dot(r.moment) * axes.col(c);
        }
    }
    out.balance_residual = balance.cwiseAbs().maxCoeff();
    for (const Vector6& F : out.platform) {
        if (!F.allFinite()) return {StatusCode::not_finite, -1, F.sum()};
    }
    return {};
}

}  // namespace nocdyn::spatial
