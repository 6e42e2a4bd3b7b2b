// Two-DOF planar robots (motion: translation, pose [x, y] of a point tool): the workspace of the
// tool point with both singularity curves (analysis/workspace.hpp, `nocdyn workspace`).
//   - The five-bar's region against the closed form: C is reachable iff
//     |l1 - l2| <= |C - A_i| <= l1 + l2 for both arms (A_i the motors, l1 the arms, l2 the
//     forearms); every grid point outside it is unreachable, every feasible one inside it.
//   - Its limb-singularity points lie on those circles, and a limb's J_j condition number grows
//     as d^-1/2 with the distance d to them (the limb stretched or folded).
//   - Its actuation-singularity points have the two forearms aligned (elbows and C collinear).
//   - The biglide's limb-singularity points: a link normal to the rail, |y| = l.
//   - The command line: the summary without theta, --theta refused.
//   - The stiffness and natural frequencies over [x, y] of a five-bar with springs at its motors
//     against K_t = A_t^T diag(k) A_t and det(K_t - w^2 M_t) = 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/analysis/workspace.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn::test {
namespace {

RobotDescription shipped(const std::string& name) {
    return io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml");
}

// robots/five-bar.yaml: motors at (-+0.1, 0), elbows at (-+0.2, 0.2), the tool point at (0, 0.35)
const Vector2 kMotor[2] = {Vector2(-0.1, 0.0), Vector2(0.1, 0.0)};
const double kArm = std::hypot(0.1, 0.2);       // l1 [m]
const double kForearm = std::hypot(0.2, 0.15);  // l2 [m]
// robots/biglide.yaml: links of 0.25 m from the sliders on y = 0
constexpr double kLink = 0.25;
// The curves are bisected to 2^-40 of a grid step (about 1e-15 m).
constexpr double kOnCurve = 1e-9;  // [m]

/// A robot's model with the condition limit lifted, to read J_j's condition near a singularity.
Model unlimited(const std::string& name) {
    RobotDescription robot = shipped(name);
    robot.max_condition = 1e12;
    return Model(robot);
}

/// The elbow of limb j: the point of its R joint 2, from the screw [1; y; -x] referred to O.
Vector2 elbow(const Data& data, int j) {
    const Twist& s = data.limb[static_cast<std::size_t>(j)].s[1];
    return {-s(2), s(1)};
}

double cross(const Vector2& a, const Vector2& b) { return a.x() * b.y() - a.y() * b.x(); }

TEST(TwoDofWorkspace, FiveBarRegionIsTheClosedFormReach) {
    const Model model(shipped("five-bar"));
    WorkspaceOptions options;
    options.resolution = 121;
    const WorkspaceMap map = workspaceMap(model, options);
    EXPECT_EQ(map.task_dimension, 2);
    int outside = 0, feasible = 0;
    for (int i = 0; i < map.n; ++i) {
        for (int k = 0; k < map.n; ++k) {
            const Vector2 c(map.x0 + i * map.step, map.y0 + k * map.step);
            bool reach = true, beyond = false;  // within both annuli; clearly outside one
            for (const Vector2& a : kMotor) {
                const double r = (c - a).norm();
                reach = reach && r >= kArm - kForearm && r <= kArm + kForearm;
                beyond = beyond || r > kArm + kForearm + kOnCurve || r < kForearm - kArm - kOnCurve;
            }
            const WorkspaceCell cell = map.cell(i, k);
            if (beyond) {
                ++outside;
                EXPECT_EQ(cell, WorkspaceCell::unreachable) << "x = " << c.x() << ", y = " << c.y();
            }
            if (cell == WorkspaceCell::feasible) {
                ++feasible;
                EXPECT_TRUE(reach) << "x = " << c.x() << ", y = " << c.y();
            }
        }
    }
    EXPECT_GT(outside, 100);
    EXPECT_GT(feasible, 1000);
    std::printf("five-bar grid %d x %d: %d points beyond an arm's reach, %d feasible\n", map.n, map.n, outside,
                feasible);
    // known points: home (0, 0.35) and a point beyond both arms' reach (0, 0.6)
    Data data(model);
    EXPECT_TRUE(inverseDisplacement(model, data, Pose(0.0, 0.0, 0.35)).ok());
    EXPECT_TRUE(velocityFromPlatformTwist(model, data, Twist::Zero()).ok());
    EXPECT_EQ(inverseDisplacement(model, data, Pose(0.0, 0.0, 0.6)).code, StatusCode::unreachable);
    const auto nearest = [&](double x, double y) {
        return map.cell(static_cast<int>(std::lround((x - map.x0) / map.step)),
                        static_cast<int>(std::lround((y - map.y0) / map.step)));
    };
    EXPECT_EQ(nearest(0.0, 0.35), WorkspaceCell::feasible);
    if (0.6 <= map.y0 + (map.n - 1) * map.step) {
        EXPECT_EQ(nearest(0.0, 0.6), WorkspaceCell::unreachable);
    }
}

TEST(TwoDofWorkspace, FiveBarLimbCurvesAreStretchedOrFoldedArms) {
    const Model model(shipped("five-bar"));
    WorkspaceOptions options;
    options.resolution = 81;
    const WorkspaceMap map = workspaceMap(model, options);
    ASSERT_GT(map.limb_singular.size(), 20U);
    const Model probe = unlimited("five-bar");
    Data data(probe);
    int blown = 0;
    double worst_ratio = 0.0;  // |cond(1e-8) / cond(1e-6) - 10|
    for (const Vector2& c : map.limb_singular) {
        // on a circle about a motor: the arm and forearm stretched or folded
        int limb = -1;
        double radius = 0.0;
        for (int j = 0; j < 2; ++j) {
            const double r = (c - kMotor[j]).norm();
            for (const double edge : {kArm + kForearm, kForearm - kArm}) {
                if (std::abs(r - edge) <= kOnCurve) limb = j, radius = edge;
            }
        }
        ASSERT_GE(limb, 0) << "x = " << c.x() << ", y = " << c.y() << " is on no circle of reach";
        // J_j's condition number at a distance d inside the reach, d = 1e-6 and 1e-8 m: ~ d^-1/2
        const Vector2 out = (c - kMotor[limb]).normalized();
        const double inward = radius == kArm + kForearm ? -1.0 : 1.0;
        double cond[2] = {0.0, 0.0};
        bool ok = true;
        for (int e = 0; e < 2; ++e) {
            const double d = e == 0 ? 1e-6 : 1e-8;
            const Vector2 at = kMotor[limb] + (radius + inward * d) * out;
            ok = ok && inverseDisplacement(probe, data, Pose(0.0, at.x(), at.y())).ok() &&
                 velocityFromPlatformTwist(probe, data, Twist::Zero()).code != StatusCode::singular_limb;
            cond[e] = data.limb[static_cast<std::size_t>(limb)].cond;
        }
        if (!ok) continue;  // the other limb does not reach there
        ++blown;
        EXPECT_GT(cond[1], 1e3) << "x = " << c.x() << ", y = " << c.y();
        EXPECT_NEAR(cond[1] / cond[0], 10.0, 1.0) << "x = " << c.x() << ", y = " << c.y();
        worst_ratio = std::max(worst_ratio, std::abs(cond[1] / cond[0] - 10.0));
    }
    EXPECT_GT(blown, 10);
    std::printf("%zu limb-singularity points, %d with both limbs reaching next to them: cond(J_j) ratio 10 +- %.3g\n",
                map.limb_singular.size(), blown, worst_ratio);
}

TEST(TwoDofWorkspace, FiveBarActuationCurvesHaveTheForearmsAligned) {
    const Model model(shipped("five-bar"));
    WorkspaceOptions options;
    options.resolution = 81;
    const WorkspaceMap map = workspaceMap(model, options);
    ASSERT_GT(map.actuation_singular.size(), 5U);
    const Model probe = unlimited("five-bar");
    Data data(probe);
    double worst = 0.0;
    for (const Vector2& c : map.actuation_singular) {
        ASSERT_TRUE(inverseDisplacement(probe, data, Pose(0.0, c.x(), c.y())).ok());
        const Vector2 f1 = c - elbow(data, 0), f2 = c - elbow(data, 1);
        EXPECT_NEAR(f1.norm(), kForearm, 1e-12);
        const double sine = std::abs(cross(f1, f2)) / (f1.norm() * f2.norm());
        EXPECT_LE(sine, 1e-9) << "x = " << c.x() << ", y = " << c.y();
        worst = std::max(worst, sine);
    }
    std::printf("%zu actuation-singularity points: |sin| of the forearms' angle <= %.3g\n",
                map.actuation_singular.size(), worst);
}

TEST(TwoDofWorkspace, BiglideLimbCurvesHaveALinkNormalToTheRail) {
    const Model model(shipped("biglide"));
    const WorkspaceMap map = workspaceMap(model, {.theta = 0.0, .resolution = 81});
    ASSERT_GT(map.limb_singular.size(), 10U);
    for (const Vector2& c : map.limb_singular) EXPECT_NEAR(std::abs(c.y()), kLink, kOnCurve) << "x = " << c.x();
    EXPECT_GT(map.area, 0.0);
}

TEST(TwoDofWorkspace, CommandGivesTheToolPointsRegionWithoutTheta) {
    const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/five-bar.yaml";
    CliResult r = runCli("workspace --robot " + robot + " --resolution 41");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.rfind("The feasible region of the tool point C", 0), 0U) << r.out;
    EXPECT_EQ(r.out.find("theta"), std::string::npos) << r.out;
    r = runCli("workspace --robot " + robot + " --resolution 41 --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.find("theta"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"actuation_singular_points\""), std::string::npos) << r.out;
    r = runCli("workspace --robot " + robot + " --theta 0.1");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("has no theta"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(TwoDofStiffness, FiveBarWithMotorSpringsIsAtDiagKA) {
    // springs k_1, k_2 at the motors, every other joint free: K_t = A_t^T diag(k) A_t with A_t =
    // du/dp_t by central differences of the inverse kinematics, M_t = A_t^T [tau(e_x) tau(e_y)]
    // from the inverse dynamics at rest under unit accelerations (no gravity: a horizontal
    // five-bar), and the natural frequencies from det(K_t - w^2 M_t) = 0 in closed form
    RobotDescription robot = shipped("five-bar");
    const double k[2] = {800.0, 1500.0};  // [N m/rad]
    robot.limbs[0].joints[0].stiffness = k[0];
    robot.limbs[1].joints[0].stiffness = k[1];
    const Model model(robot);
    ASSERT_EQ(model.task_dimension, 2);
    const StiffnessModel compliance(model);
    Data data(model);
    double worst_K = 0.0, worst_M = 0.0, worst_f = 0.0;
    for (const Vector2& c : {Vector2(0.0, 0.35), Vector2(0.05, 0.25), Vector2(-0.08, 0.3)}) {
        const Pose p(0.0, c.x(), c.y());
        StiffnessData stiffness;
        LumpedModes lumped;
        ASSERT_TRUE(stiffnessAndModes(model, compliance, data, p, stiffness, lumped).ok());
        TaskModes modes;
        taskModes(model, data, stiffness, lumped, modes);
        ASSERT_EQ(modes.K.rows(), 2);
        ASSERT_EQ(modes.frequency.size(), 2);
        // A_t by central differences of u(p_t)
        Eigen::Matrix2d A_t;
        const double h = 1e-6;
        for (int i = 0; i < 2; ++i) {
            Pose plus = p, minus = p;
            plus(1 + i) += h;
            minus(1 + i) -= h;
            ASSERT_TRUE(inverseDisplacement(model, data, plus).ok());
            const Vector2 u_plus(data.u(0), data.u(1));
            ASSERT_TRUE(inverseDisplacement(model, data, minus).ok());
            A_t.col(i) = (u_plus - Vector2(data.u(0), data.u(1))) / (2.0 * h);
        }
        const Eigen::Matrix2d K = A_t.transpose() * Eigen::Vector2d(k[0], k[1]).asDiagonal() * A_t;
        Eigen::Matrix2d tau;
        for (int i = 0; i < 2; ++i) {
            Twist ddp = Twist::Zero();
            ddp(1 + i) = 1.0;
            ASSERT_TRUE(inverseDynamics(model, data, p, Twist::Zero(), ddp).ok());
            tau.col(i) = Vector2(data.tau(0), data.tau(1));
        }
        const Eigen::Matrix2d M = A_t.transpose() * tau;
        // det(K - l M) = det M l^2 - (K00 M11 + K11 M00 - K01 M10 - K10 M01) l + det K
        const double a = M.determinant();
        const double b = -(K(0, 0) * M(1, 1) + K(1, 1) * M(0, 0) - K(0, 1) * M(1, 0) - K(1, 0) * M(0, 1));
        const double d = K.determinant();
        const double root = std::sqrt(b * b - 4.0 * a * d);
        const double l_lo = (-b - root) / (2.0 * a), l_hi = (-b + root) / (2.0 * a);
        const Vector2 f(std::sqrt(l_lo) / (2.0 * std::numbers::pi), std::sqrt(l_hi) / (2.0 * std::numbers::pi));
        worst_K = std::max(worst_K, (Eigen::Matrix2d(modes.K) - K).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff());
        worst_M = std::max(worst_M, (Eigen::Matrix2d(modes.M) - M).cwiseAbs().maxCoeff() / M.cwiseAbs().maxCoeff());
        worst_f = std::max(worst_f, (Vector2(modes.frequency) - f).cwiseAbs().maxCoeff() / f(1));
        EXPECT_GT(f(0), 1.0) << "x = " << c.x() << ", y = " << c.y();
        // the modes: M_t-normalised, K_t v = w^2 M_t v
        for (int i = 0; i < 2; ++i) {
            const Vector2 v = modes.shape.col(i);
            const double w = 2.0 * std::numbers::pi * modes.frequency(i);
            EXPECT_NEAR(v.dot(M * v), 1.0, 1e-6);
            EXPECT_LE((K * v - w * w * M * v).norm(), 1e-6 * K.norm() * v.norm());
        }
    }
    // measured: K_t to 1.7e-11, M_t to 1.5e-11 (both A_t's central differences), frequencies to 6e-12
    EXPECT_LE(worst_K, 1e-8);
    EXPECT_LE(worst_M, 1e-8);
    EXPECT_LE(worst_f, 1e-8);
    std::printf("five-bar, springs at the motors: K_t to %.3g, M_t to %.3g, frequencies to %.3g (relative)\n", worst_K,
                worst_M, worst_f);
}

}  // namespace
}  // namespace nocdyn::test
