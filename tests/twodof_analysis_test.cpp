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
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/analysis/workspace.hpp"
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
    if (0.6 <= map.y0 + (map.n - 1) * map.step) EXPECT_EQ(nearest(0.0, 0.6), WorkspaceCell::unreachable);
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

}  // namespace
}  // namespace nocdyn::test
