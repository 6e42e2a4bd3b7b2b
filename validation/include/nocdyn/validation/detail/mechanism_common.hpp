// Engine-independent bookkeeping shared by the Simbody and MuJoCo models of a general planar
// parallel robot: how each limb is cut into a tree plus one loop-closure constraint, the rate
// of every joint as a row over the engine's generalized speeds, and the distribution of the
// required platform generalized force over the actuators (minimum norm when redundant).
// Nothing here is kinematics or dynamics of the robot: positions, velocities, accelerations,
// constraint Jacobians, mass matrices and bias forces all come from the engine.
//
// Tree of limb j (links 0 = ground, 1 = body 1, 2 = body 2, 3 = platform; joint k joins link
// k-1 (inboard) to link k (outboard)), loop closed at the revolute joint c:
//   joints k < c  are mobilizers from link k-1 to link k (forward, mobility = q_k);
//   joints k > c  are mobilizers from link k to link k-1 (reversed, mobility = -q_k);
//   joint c       is a point coincidence of links c-1 and c at its axis (2 equations).
// Every body frame coincides with the base frame at home, so home data go in unchanged and
// every mobility is 0 at home.
//
// Inverse dynamics by virtual work. With v the engine's generalized speeds, the platform
// speeds v_p = dp/dt (pose order [theta, x, y]) independent and G the closure Jacobian
// (G v = 0), v = N dp with N = [-G_f^{-1} G_p; I]. Each joint rate is q'_k = r_k v (r_k a
// constant row). With h = M v' + c - Q_gravity from the engine and the friction forces f_k
// (added here from the rows, or already among the engine's applied forces):
//   N^T (h - sum_k r_k^T f_k) = A^T tau,   A = [r_k N] over the actuated joints (n x 3),
// and tau = the minimum-norm solution of this 3 x n system (unique when n = 3).
// A translating point tool (PlatformMotion::translation) has the task rates dp_task = [x', y']:
// the engines prescribe the platform's angle at home (a point mass, every limb's last R joint
// at it: the angle moves no body and takes no moment), so only the columns E = [0 0; 1 0; 0 1]
// of the balance are equations: E^T N^T (h - ...) = (A E)^T tau, a 2 x n system.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SVD>

#include "nocdyn/description.hpp"
#include "nocdyn/detail/eigen_instances.hpp"
#include "nocdyn/error.hpp"

namespace nocdyn::validation::detail {

/// Index (0..2) of the revolute joint where the loop of `limb` is closed: an unactuated R joint
/// when there is one, else an actuated one; the first such joint or the last (the two engines
/// pick differently, so that their trees differ). Throws nocdyn::Error for a limb without R.
inline int closureJoint(const RobotDescription& robot, int limb_index, bool prefer_last) {
    const LimbDescription& limb = robot.limbs[static_cast<std::size_t>(limb_index)];
    int best = -1;
    for (int pass = 0; pass < 2 && best < 0; ++pass) {
        for (int i = 0; i < 3; ++i) {
            const int k = prefer_last ? 2 - i : i;
            const JointDescription& jt = limb.joints[static_cast<std::size_t>(k)];
            if (jt.type != JointType::revolute) continue;
            if (pass == 0 && jt.actuated) continue;
            best = k;
            break;
        }
    }
    if (best < 0) {
        throw Error(where(robot, limb.line) + "limb " + std::to_string(limb_index + 1) +
                    " has no revolute joint at which to close its loop");
    }
    return best;
}

/// Where the engine put the tree of the robot: the generalized-speed index of each limb
/// joint's mobility (-1 for the closure joint) and of the platform's [theta, x, y].
struct TreeIndices {
    std::vector<std::array<int, 3>> joint_v;  ///< per limb, per joint
    std::array<int, 3> platform_v{};          ///< pose order
    int nv = 0;
};

/// Rows r_k (3 L x nv, limb-major): q'_k = r_k v, and since every mobility is an angle or a
/// displacement integrated from home, also q_k = r_k q. A tree joint's row is +-1 at its
/// mobility; the closure joint's row is the angle row of its outboard link minus its inboard
/// link's, a link's angle being the sum of the revolute mobilities on its path from ground.
inline Eigen::MatrixXd jointRateRows(const RobotDescription& robot, const std::vector<int>& closure,
                                     const TreeIndices& tree) {
    const int L = static_cast<int>(robot.limbs.size());
    Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * L, tree.nv);
    for (int j = 0; j < L; ++j) {
        const LimbDescription& limb = robot.limbs[static_cast<std::size_t>(j)];
        const int c = closure[static_cast<std::size_t>(j)];
        const auto& v = tree.joint_v[static_cast<std::size_t>(j)];
        std::array<Eigen::RowVectorXd, 4> angle;  // links 0..3
        angle[0] = Eigen::RowVectorXd::Zero(tree.nv);
        angle[3] = Eigen::RowVectorXd::Zero(tree.nv);
        angle[3](tree.platform_v[0]) = 1.0;
        for (int k = 1; k <= c; ++k) {  // forward: joint k (0-based k-1) carries link k
            const int jk = k - 1;
            angle[static_cast<std::size_t>(k)] = angle[static_cast<std::size_t>(k - 1)];
            if (limb.joints[static_cast<std::size_t>(jk)].type == JointType::revolute) {
                angle[static_cast<std::size_t>(k)](v[static_cast<std::size_t>(jk)]) += 1.0;
            }
        }
        for (int k = 2; k >= c + 1; --k) {  // reversed: joint k (0-based) carries link k
            angle[static_cast<std::size_t>(k)] = angle[static_cast<std::size_t>(k + 1)];
            if (limb.joints[static_cast<std::size_t>(k)].type == JointType::revolute) {
                angle[static_cast<std::size_t>(k)](v[static_cast<std::size_t>(k)]) += 1.0;
            }
        }
        for (int k = 0; k < 3; ++k) {
            if (k == c) {
                R.row(3 * j + k) = angle[static_cast<std::size_t>(k + 1)] - angle[static_cast<std::size_t>(k)];
            } else {
                R(3 * j + k, v[static_cast<std::size_t>(k)]) = k < c ? 1.0 : -1.0;
            }
        }
    }
    return R;
}

inline double conditionNumber(const Eigen::MatrixXd& A) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A);
    const auto& s = svd.singularValues();
    if (s.size() == 0) return 0.0;
    const double smin = s(s.size() - 1);
    return smin > 0.0 ? s(0) / smin : std::numeric_limits<double>::infinity();
}

/// Friction force of a joint on its outboard body: -(damping q' + friction sign q'), sign 0 = 0.
inline double jointFriction(const JointDescription& joint, double rate) {
    const double sign = rate > 0.0 ? 1.0 : (rate < 0.0 ? -1.0 : 0.0);
    return -(joint.damping * rate + joint.friction * sign);
}

/// Whether the engine's h already contains the joint friction forces (as applied forces) or
/// distributeForces adds them from the joint rows.
enum class Friction { inApplied, fromRows };

/// Result of distributeForces.
struct ForceDistribution {
    Eigen::VectorXd tau;       ///< actuator forces, file order
    double dissipation = 0.0;  ///< power lost in joint friction [W] (Friction::fromRows only)
    double condition = 0.0;    ///< max(cond G_f, cond A)
};

/// The platform-force balance of the header: G (2 L x nv) the closure Jacobian, R the joint
/// rows, v the generalized speeds, h = M v' + c - Q_gravity (- Q_friction with
/// Friction::inApplied). Throws nocdyn::Error naming the
/// time when G_f or A is singular beyond robot.max_condition.
inline ForceDistribution distributeForces(const RobotDescription& robot, const TreeIndices& tree,
                                          const Eigen::MatrixXd& G, const Eigen::MatrixXd& R, const Eigen::VectorXd& v,
                                          const Eigen::VectorXd& h, double t, const char* engine, Friction friction) {
    const int nv = tree.nv;
    const int nc = static_cast<int>(G.rows());
    // Free (passive tree) speeds: every speed but the platform's.
    std::vector<int> free_v;
    for (int i = 0; i < nv; ++i) {
        if (i != tree.platform_v[0] && i != tree.platform_v[1] && i != tree.platform_v[2]) free_v.push_back(i);
    }
    if (static_cast<int>(free_v.size()) != nc) {
        throw Error(std::string(engine) + " model: " + std::to_string(nc) + " closure equations for " +
                    std::to_string(free_v.size()) + " passive speeds");
    }
    Eigen::MatrixXd Gf(nc, nc), Gp(nc, 3);
    for (int c = 0; c < nc; ++c) Gf.col(c) = G.col(free_v[static_cast<std::size_t>(c)]);
    for (int c = 0; c < 3; ++c) Gp.col(c) = G.col(tree.platform_v[static_cast<std::size_t>(c)]);
    ForceDistribution out;
    const double cond_G = conditionNumber(Gf);
    // v = N dp
    Eigen::MatrixXd N = Eigen::MatrixXd::Zero(nv, 3);
    const Eigen::MatrixXd X = Gf.fullPivLu().solve(-Gp);
    for (int r = 0; r < nc; ++r) N.row(free_v[static_cast<std::size_t>(r)]) = X.row(r);
    for (int c = 0; c < 3; ++c) N(tree.platform_v[static_cast<std::size_t>(c)], c) = 1.0;
    // Friction of every joint as generalized forces, and the actuation map A.
    Eigen::VectorXd Q_friction = Eigen::VectorXd::Zero(nv);
    const int n = robot.actuatorCount();
    Eigen::MatrixXd A(n, 3);
    int a = 0;
    for (std::size_t j = 0; j < robot.limbs.size(); ++j) {
        for (std::size_t k = 0; k < 3; ++k) {
            const JointDescription& joint = robot.limbs[j].joints[k];
            const auto row = R.row(static_cast<Eigen::Index>(3 * j + k));
            const double rate = row.dot(v);
            if (friction == Friction::fromRows) {
                const double f = jointFriction(joint, rate);
                Q_friction += f * row.transpose();
                out.dissipation -= f * rate;
            }
            if (joint.actuated) A.row(a++) = row * N;
        }
    }
    // N^T (h - Q_friction) = A^T tau over the task columns, minimum-norm tau.
    const int first_task = robot.motion == PlatformMotion::translation ? 1 : 0;
    const int task = 3 - first_task;
    const Eigen::VectorXd F = (N.transpose() * (h - Q_friction)).tail(task);
    const Eigen::MatrixXd A_task = A.rightCols(task);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A_task.transpose(), Eigen::ComputeThinU | Eigen::ComputeThinV);
    const auto& s = svd.singularValues();
    const double s_min = s(task - 1);
    const double cond_A = s_min > 0.0 ? s(0) / s_min : std::numeric_limits<double>::infinity();
    out.condition = std::max(cond_G, cond_A);
    if (!(out.condition <= robot.max_condition)) {
        std::ostringstream msg;
        msg << engine << " model: singular at t=" << t << " s: condition number of the "
            << (cond_G >= cond_A ? "loop closure" : "actuation map") << " is " << out.condition << " > "
            << robot.max_condition;
        throw Error(msg.str());
    }
    out.tau = svd.solve(F);
    return out;
}

}  // namespace nocdyn::validation::detail
