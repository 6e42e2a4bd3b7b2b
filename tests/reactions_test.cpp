// Joint reactions against an independent solution of every body's Newton-Euler equations
// (the whole stacked system solved at once, the bodies' accelerations from the NOC's T_i and
// dT_i of eq. 22), the platform's balance, the weight carried at rest, and the convention.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/reactions.hpp"
#include "random_robots.hpp"

namespace nocdyn::test {
namespace {

/// Relative to the robot's peak transmitted force at the sample (double-precision rounding
/// of a 9n + 3 least-squares solve; measured below 1e-13).
constexpr double kAgreement = 1e-10;
constexpr int kSamples = 8;

/// The wrench body i needs (the full path's T_i and dT_i in `data`), referred to O, from t_i = [w; dx_i/dt] = T_i v and
/// its rate T_i dv + dT_i v (eq. 22): [I dw + x_i x f; f], f = m (d2x_i/dt2 - g).
Wrench neededWrench(const Model& model, const Data& data, int i, const Vector2& x) {
    const bool actuators = model.coordinates == Coordinates::actuators;
    const Vector3 v = actuators ? Vector3(data.du) : Vector3(data.t_M);
    const Vector3 dv = actuators ? Vector3(data.ddu) : Vector3(data.t_M_dot);
    const auto ii = static_cast<std::size_t>(i);
    const Vector3 rate = data.T[ii] * dv + data.T_dot[ii] * v;
    const InertiaDyad& M = model.inertia(i);
    const Vector2 f = M.mass * (rate.tail<2>() - model.gravity);
    return {M.inertia * rate(0) + x.x() * f.y() - x.y() * f.x(), f.x(), f.y()};
}

/// Every F_jk from the stacked equations: two body balances per limb, the three joints'
/// efforts s^T F = tau - phi (phi from the description's coefficients) and the platform's
/// balance. Returns the solution and the residual norm of the least-squares solve.
struct Stacked {
    Eigen::VectorXd F;
    double residual = 0.0, scale = 0.0;
};
Stacked solveStacked(const Model& model, const Data& data) {
    const int n = model.limbs;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(9 * n + 3, 9 * n);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(9 * n + 3);
    const auto col = [](int j, int k) { return 9 * j + 3 * k; };
    for (int j = 0; j < n; ++j) {
        const auto jj = static_cast<std::size_t>(j);
        const LimbData& ld = data.limb[jj];
        const LimbDescription& limb = model.description.limbs[jj];
        for (int body = 0; body < 2; ++body) {  // F_k - F_(k+1) = w
            const int row = 9 * j + 3 * body;
            A.block<3, 3>(row, col(j, body)) = Matrix3::Identity();
            A.block<3, 3>(row, col(j, body + 1)) = -Matrix3::Identity();
            b.segment<3>(row) = neededWrench(model, data, model.body(j, body), ld.x[static_cast<std::size_t>(body)]);
        }
        int actuator = 0;
        for (int jj2 = 0; jj2 < j; ++jj2)
            for (const JointDescription& joint : model.description.limbs[static_cast<std::size_t>(jj2)].joints)
                actuator += joint.actuated ? 1 : 0;
        for (int k = 0; k < 3; ++k) {
            const JointDescription& joint = limb.joints[static_cast<std::size_t>(k)];
            const double rate = ld.gamma_dot(k);
            double effort = -(joint.damping * rate + joint.friction * (rate > 0 ? 1.0 : (rate < 0 ? -1.0 : 0.0)));
            if (joint.actuated) effort += data.tau(actuator++);
            A.block<1, 3>(9 * j + 6 + k, col(j, k)) = ld.s[static_cast<std::size_t>(k)].transpose();
            b(9 * j + 6 + k) = effort;
        }
        A.block<3, 3>(9 * n, col(j, 2)) = Matrix3::Identity();
    }
    b.tail<3>() = neededWrench(model, data, model.platformBody(), data.x_P);
    Stacked s;
    s.F = A.colPivHouseholderQr().solve(b);
    s.residual = (A * s.F - b).norm();
    s.scale = b.cwiseAbs().maxCoeff();
    return s;
}

/// The example robots and random robots of every limb type, with gravity, friction and
/// redundancy, each with a random motion about home.
struct Case {
    std::string label;
    RobotDescription robot;
};
std::vector<Case> cases() {
    std::vector<Case> out;
    for (const std::string& name : io::exampleRobotNames()) {
        RobotDescription robot = io::exampleRobot(name);
        out.push_back({name, robot});
        robot.gravity = Vector2(0.0, -9.81);
        for (LimbDescription& limb : robot.limbs)
            for (JointDescription& joint : limb.joints) {
                joint.damping = 3.0;
                joint.friction = 0.7;
            }
        out.push_back({name + "-gravity-friction", robot});
    }
    std::mt19937 rng(17);
    for (const std::string& type : limbTypes()) {
        for (const RandomRobotSpec& spec : {RandomRobotSpec{{type, type, type}, 3, true, true},
                                            RandomRobotSpec{{type, type, type, type}, 5, true, true}}) {
            for (int tries = 0; tries < 50; ++tries) {
                if (auto robot = randomRobot(spec, rng)) {
                    out.push_back({"random-" + type + "-" + std::to_string(spec.actuators), *robot});
                    break;
                }
            }
        }
    }
    return out;
}

TEST(JointReactions, EqualTheStackedNewtonEulerSolutionOnEveryRobot) {
    int checked = 0;
    for (const Case& c : cases()) {
        const Model model(c.robot);
        Data data(model), full(model);
        Reactions reactions;
        std::mt19937 rng(3);
        const PoseTrajectory trajectory = trajectoryAround(model.home, rng, 0.5);
        for (int s = 0; s < kSamples; ++s) {
            Pose p, dp, ddp;
            trajectory.evaluate(0.037 * s, p, dp, ddp);
            if (!inverseDynamicsWithReactions(model, data, p, dp, ddp, reactions)) continue;
            // the reference: the full path's T_i, dT_i and tau (eqs. 20-23)
            ASSERT_TRUE(inverseDynamics(model, full, p, dp, ddp).ok());
            const double tau_scale = 1.0 + full.tau.cwiseAbs().maxCoeff();
            // the lean kernel's tau (its minimum-norm solve by the normal equations when redundant):
            // the lean path's agreement with the full path (model_test, LeanPathEqualsFullPath)
            EXPECT_LT((data.tau - full.tau).cwiseAbs().maxCoeff(), 1e-10 * tau_scale)
                << c.label << " t = " << 0.037 * s << ": tau differs from the full path's";
            const Stacked ref = solveStacked(model, full);
            ASSERT_LT(ref.residual, 1e-9 * (1.0 + ref.scale))
                << c.label << " t = " << 0.037 * s << ": the forces do not balance the bodies";
            double peak = 1.0;
            for (int j = 0; j < model.limbs; ++j)
                for (int k = 0; k < 3; ++k)
                    peak = std::max(peak, ref.F.segment<3>(9 * j + 3 * k).cwiseAbs().maxCoeff());
            for (int j = 0; j < model.limbs; ++j) {
                for (int k = 0; k < 3; ++k) {
                    const Wrench& F = reactions.transmitted[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
                    EXPECT_LT((F - ref.F.segment<3>(9 * j + 3 * k)).cwiseAbs().maxCoeff(), kAgreement * peak)
                        << c.label << ", " << model.limbName(j) << " joint " << k + 1 << ", t = " << 0.037 * s;
                }
            }
            ++checked;
        }
    }
    EXPECT_GE(checked, 150) << "too few samples were checked";
}

TEST(JointReactions, PlatformBalanceHoldsOverAllLimbs) {
    int checked = 0;
    for (const Case& c : cases()) {
        const Model model(c.robot);
        Data data(model);
        Reactions reactions;
        std::mt19937 rng(5);
        const PoseTrajectory trajectory = trajectoryAround(model.home, rng, 0.5);
        Pose p, dp, ddp;
        trajectory.evaluate(0.11, p, dp, ddp);
        if (!inverseDynamicsWithReactions(model, data, p, dp, ddp, reactions)) continue;
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());  // T_i and dT_i for w_P
        Wrench sum = Wrench::Zero();
        double peak = 1.0;
        for (int j = 0; j < model.limbs; ++j) {
            sum += reactions.transmitted[static_cast<std::size_t>(j)][2];
            peak = std::max(peak, reactions.transmitted[static_cast<std::size_t>(j)][2].cwiseAbs().maxCoeff());
        }
        const Wrench w_P = neededWrench(model, data, model.platformBody(), data.x_P);
        EXPECT_LT((sum - w_P).cwiseAbs().maxCoeff(), 1e-11 * peak) << c.label;
        ++checked;
    }
    EXPECT_GE(checked, 20);
}

TEST(JointReactions, AtRestUnderGravityTheBaseJointsCarryTheWeight) {
    int checked = 0;
    for (const Case& c : cases()) {
        RobotDescription robot = c.robot;
        robot.gravity = Vector2(1.5, -9.81);
        const Model model(robot);
        Data data(model);
        Reactions reactions;
        if (!inverseDynamicsWithReactions(model, data, model.home, Twist::Zero(), Twist::Zero(), reactions)) continue;
        double mass = model.platform_M.mass;
        Vector2 first_moment = mass * data.x_P;
        for (int j = 0; j < model.limbs; ++j)
            for (int b = 0; b < 2; ++b) {
                const double m = model.limb[static_cast<std::size_t>(j)].M[static_cast<std::size_t>(b)].mass;
                mass += m;
                first_moment += m * data.limb[static_cast<std::size_t>(j)].x[static_cast<std::size_t>(b)];
            }
        Wrench sum = Wrench::Zero();
        for (int j = 0; j < model.limbs; ++j) sum += reactions.transmitted[static_cast<std::size_t>(j)][0];
        // sum F_1 + weight = 0: the force -M g and the moment -(sum m x) x g about O
        const Vector2 g = model.gravity;
        EXPECT_NEAR(sum(1), -mass * g.x(), 1e-11 * mass * g.norm()) << c.label;
        EXPECT_NEAR(sum(2), -mass * g.y(), 1e-11 * mass * g.norm()) << c.label;
        EXPECT_NEAR(sum(0), -(first_moment.x() * g.y() - first_moment.y() * g.x()), 1e-11 * mass * g.norm()) << c.label;
        ++checked;
    }
    EXPECT_GE(checked, 20);
}

TEST(JointReactions, FollowTheConventionRevoluteForceOnlyPrismaticNormalForceAndCouple) {
    int revolute = 0, prismatic = 0;
    for (const Case& c : cases()) {
        const Model model(c.robot);
        Data data(model);
        Reactions reactions;
        std::mt19937 rng(9);
        const PoseTrajectory trajectory = trajectoryAround(model.home, rng, 0.5);
        Pose p, dp, ddp;
        trajectory.evaluate(0.07, p, dp, ddp);
        if (!inverseDynamicsWithReactions(model, data, p, dp, ddp, reactions)) continue;
        for (int j = 0; j < model.limbs; ++j) {
            const auto jj = static_cast<std::size_t>(j);
            for (std::size_t k = 0; k < 3; ++k) {
                const Vector3& r = reactions.joint[jj][k];
                const Wrench& F = reactions.transmitted[jj][k];
                const Twist& s = data.limb[jj].s[k];
                const double scale = 1.0 + F.cwiseAbs().maxCoeff();
                if (model.limb[jj].type[k] == JointType::revolute) {
                    // the force at the axis; the moment about the axis is the effort s^T F
                    EXPECT_EQ(r(2), 0.0);
                    EXPECT_LT((r.head<2>() - F.tail<2>()).norm(), 1e-15 * scale) << c.label;
                    ++revolute;
                } else {
                    const Vector2 d = s.tail<2>();
                    EXPECT_NEAR(r.head<2>().dot(d), 0.0, 1e-12 * scale) << c.label;
                    // r with the effort as a force along d through the outboard c.o.m. gives F back
                    const Vector2 x = k == 2 ? data.x_P : data.limb[jj].x[k];
                    const Vector2 f = r.head<2>() + s.dot(F) * d;
                    const double n_O = r(2) + x.x() * f.y() - x.y() * f.x();
                    EXPECT_LT((Wrench(n_O, f.x(), f.y()) - F).cwiseAbs().maxCoeff(), 1e-12 * scale) << c.label;
                    ++prismatic;
                }
            }
        }
    }
    EXPECT_GE(revolute, 50);
    EXPECT_GE(prismatic, 20);
}

}  // namespace
}  // namespace nocdyn::test
