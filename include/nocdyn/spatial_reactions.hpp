// Joint reactions of a spatial robot (nocdyn/spatial.hpp): the wrench each listed joint passes
// from its inboard body to its outboard body, after the inverse or the forward dynamics.
//
// Limb j's bodies need the efforts f_j (LimbData::effort); the actuators give tau_j at their
// freedoms (0 elsewhere). The wrench F_j that the limb's last body exerts on the platform
// satisfies J_j^T F_j = tau_j - f_j (each freedom passes its effort): F_j = J_j^+T (tau_j - f_j)
// plus, for a limb of fewer than six independent freedoms (the Delta's R-U-U arm), a wrench of
// null(J_j^T) that no freedom feels (its constraint wrench); their amounts are those for which
// the platform balances, sum_j F_j = w_P (least squares, the smallest for a platform held by
// more constraint wrenches than it needs). Through listed joint k of limb j passes
// W_k = F_j + sum of the wrenches w_b of the bodies outboard of k (Newton-Euler on each body).
// A joint's reaction is W_k at the joint's point (a P joint: at its outboard body's c.o.m.)
// with the efforts along its freedoms taken out: an R joint carries no moment about its axis,
// a U none about its two axes (only about the normal of its cross), an S no moment at all, a P
// no force along its direction.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "nocdyn/spatial.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn::spatial {

/// One listed joint's reaction, base frame, the inboard body on the outboard body.
struct JointReaction {
    char type = 'R';                                   ///< R, P, U or S
    Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< where the moment is taken [m]
    Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< [N]
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();  ///< about point [N m]
    Vector6 wrench = Vector6::Zero();                  ///< W_k before the efforts are taken out, about O
};

struct Reactions {
    /// Sized once from the model.
    explicit Reactions(const Model& model);
    std::vector<std::vector<JointReaction>> joint;  ///< [limb][listed joint]
    std::vector<Vector6> platform;                  ///< F_j, limb j on the platform, about O
    /// |sum_j F_j - w_P| (largest entry): 0 to rounding when the platform balances.
    double balance_residual = 0.0;
    /// Per limb: the dimension of null(J_j^T), its constraint wrenches (scratch).
    std::vector<int> nullity;
};

/// Every joint's reaction after inverseDynamics or forwardDynamics (which leave the limbs'
/// efforts, wrenches and data.tau); out.balance_residual says how well the platform balances
/// (not at all where the limbs' constraint wrenches cannot hold it: a constraint singularity).
/// Returns not_finite for a non-finite result. Allocation-free.
[[nodiscard]] Status jointReactions(const Model& model, const Data& data, Reactions& out);

}  // namespace nocdyn::spatial
