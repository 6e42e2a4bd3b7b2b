// Spatial robot files (space: spatial): the shipped robots read with their numbers, every error
// class of the schema refused in one line naming the file, line, limb, joint or body, and the
// commands' one-line refusal.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial_description.hpp"
#include "nocdyn/text.hpp"
#include "skip.hpp"

namespace nocdyn {
namespace {

std::string shipped(const std::string& name) { return std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name; }

/// A Cartesian gantry (three P joints) and a guiding RUS chain: it translates only.
const std::string kBase =
    "name: cartesian\n"                                                                                          // 1
    "space: spatial\n"                                                                                           // 2
    "motion: translation\n"                                                                                      // 3
    "gravity: [0.0, 0.0, -9.81]\n"                                                                               // 4
    "home: [0.0, 0.0, 0.5]\n"                                                                                    // 5
    "platform: {mass: 2.0, inertia: [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.1]]}\n"                      // 6
    "limbs:\n"                                                                                                   // 7
    "  - name: gantry\n"                                                                                         // 8
    "    joints:\n"                                                                                              // 9
    "      - {type: P, direction: [2.0, 0.0, 0.0], actuated: true, limits: {lower: -0.5, upper: 0.5}}\n"         // 10
    "      - {type: P, direction: [0.0, 1.0, 0.0], actuated: true}\n"                                            // 11
    "      - {type: P, direction: [0.0, 0.0, 1.0], actuated: true}\n"                                            // 12
    "    bodies:\n"                                                                                              // 13
    "      - {mass: 5.0, com: [0.0, 0.0, 0.0], inertia: [[0.2, 0.0, 0.0], [0.0, 0.2, 0.0], [0.0, 0.0, 0.2]]}\n"  // 14
    "      - {mass: 3.0, com: [0.0, 0.0, 0.2], inertia: [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.1]]}\n"  // 15
    "  - name: guide\n"                                                                                          // 16
    "    joints:\n"                                                                                              // 17
    "      - {type: R, point: [1.0, 0.0, 0.0], axis: [0.0, 0.0, 3.0]}\n"                                         // 18
    "      - {type: U, point: [1.0, 0.2, 0.3], axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]}\n"                      // 19
    "      - {type: S, point: [0.0, 0.0, 0.5]}\n"                                                                // 20
    "    bodies:\n"                                                                                              // 21
    "      - {mass: 1.0, com: [1.0, 0.1, 0.15], inertia: [[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.001]]}\n"  // 22
    "      - {mass: 1.0, com: [0.5, 0.1, 0.4], inertia: [[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.001]]}\n";  // 23

/// kBase with `from` (which must occur) replaced by `to`.
std::string edited(const std::string& from, const std::string& to, std::string text = kBase) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

/// The error reading `text` gives, in one line, with every fragment in it.
void expectRefused(const std::string& text, std::initializer_list<std::string> fragments) {
    try {
        (void)io::parseSpatialRobotDescription(text, "cartesian.yaml");
        ADD_FAILURE() << "accepted, expected an error with '" << *fragments.begin() << "'";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        for (const std::string& fragment : fragments) EXPECT_NE(message.find(fragment), std::string::npos) << message;
    }
}

TEST(SpatialRobotFile, TheBaseFileReadsWithItsNumbersNormalised) {
    const SpatialRobotDescription robot = io::parseSpatialRobotDescription(kBase, "cartesian.yaml");
    EXPECT_EQ(robot.motion, PlatformMotion::translation);
    EXPECT_EQ(robot.taskDimension(), 3);
    ASSERT_EQ(robot.limbs.size(), 2u);
    EXPECT_EQ(robot.limbs[0].type(), "PPP");
    EXPECT_EQ(robot.limbs[1].type(), "RUS");
    EXPECT_EQ(robot.limbs[1].freedoms(), 6);
    EXPECT_EQ(robot.actuatorCount(), 3);
    EXPECT_DOUBLE_EQ(robot.totalMass(), 12.0);
    EXPECT_EQ(robot.limbs[0].joints[0].direction, Eigen::Vector3d::UnitX());  // [2, 0, 0] normalised
    EXPECT_EQ(robot.limbs[1].joints[0].axis, Eigen::Vector3d::UnitZ());       // [0, 0, 3] normalised
    EXPECT_EQ(robot.limbs[0].joints[0].limits.lower, -0.5);
    EXPECT_TRUE(std::isinf(robot.limbs[0].joints[0].limits.effort));
    EXPECT_EQ(robot.limbs[1].joints[1].line, 19);
    EXPECT_EQ(robot.home, (Eigen::Matrix<double, 6, 1>() << 0.0, 0.0, 0.5, 0.0, 0.0, 0.0).finished());
    EXPECT_EQ(freeRotationsAtHome(robot).cols(), 0);
}

TEST(SpatialRobotFile, TheDeltaReadsAndClosesAtHome) {
    const SpatialRobotDescription robot = io::loadSpatialRobotDescription(shipped("delta.yaml"));
    EXPECT_EQ(robot.name, "delta");
    EXPECT_EQ(robot.motion, PlatformMotion::translation);
    ASSERT_EQ(robot.limbs.size(), 3u);
    EXPECT_EQ(robot.actuatorCount(), 3);
    EXPECT_NEAR(robot.totalMass(), 0.6 + 3.0 * (0.6 + 0.25), 1e-12);
    EXPECT_EQ(robot.home(2), -0.8);
    EXPECT_EQ(robot.gravity, Eigen::Vector3d(0.0, 0.0, -9.81));
    const Eigen::Vector3d home = robot.home.head<3>();
    for (const SpatialLimbDescription& limb : robot.limbs) {
        EXPECT_EQ(limb.type(), "RUU");
        EXPECT_EQ(limb.freedoms(), 5);
        EXPECT_EQ(limb.bodies.size(), 2u);
        const SpatialJointDescription& motor = limb.joints[0];
        EXPECT_TRUE(motor.actuated);
        EXPECT_NEAR(motor.point.norm(), 0.2, 1e-15);                                    // base circle
        EXPECT_NEAR((limb.joints[1].point - motor.point).norm(), 0.35, 1e-15);          // arm
        EXPECT_NEAR((limb.joints[2].point - limb.joints[1].point).norm(), 0.8, 1e-15);  // forearm
        EXPECT_NEAR((limb.joints[2].point - home).norm(), 0.05, 1e-15);                 // platform
        EXPECT_NEAR(motor.axis.norm(), 1.0, 1e-15);
        // the Delta's pattern: the elbow's a1 and the platform's a2 along the motor axis
        EXPECT_NEAR((limb.joints[1].axis1 - motor.axis).norm(), 0.0, 1e-15);
        EXPECT_NEAR((limb.joints[2].axis2 - motor.axis).norm(), 0.0, 1e-15);
        EXPECT_NEAR((limb.joints[1].axis2 - limb.joints[2].axis1).norm(), 0.0, 1e-15);
    }
    EXPECT_EQ(freeRotationsAtHome(robot).cols(), 0);
}

TEST(SpatialRobotFile, TheStewartPlatformReadsAndClosesAtHome) {
    const SpatialRobotDescription robot = io::loadSpatialRobotDescription(shipped("stewart.yaml"));
    EXPECT_EQ(robot.motion, PlatformMotion::full);
    EXPECT_EQ(robot.taskDimension(), 6);
    ASSERT_EQ(robot.limbs.size(), 6u);
    EXPECT_EQ(robot.actuatorCount(), 6);
    EXPECT_NEAR(robot.totalMass(), 300.0 + 6.0 * (25.0 + 8.0), 1e-12);
    EXPECT_EQ(robot.platform.com, Eigen::Vector3d(0.0, 0.0, 0.05));
    EXPECT_NEAR(robot.platform.inertia(2, 2), 300.0 * 0.49 / 2.0, 1e-12);
    for (const SpatialLimbDescription& limb : robot.limbs) {
        EXPECT_EQ(limb.type(), "UPS");
        EXPECT_EQ(limb.freedoms(), 6);
        const Eigen::Vector3d leg = limb.joints[2].point - limb.joints[0].point;
        EXPECT_NEAR(leg.norm(), 1.2, 1e-15);
        EXPECT_NEAR(limb.joints[0].point.norm(), 1.0, 1e-15);
        EXPECT_NEAR((limb.joints[2].point - robot.home.head<3>()).norm(), 0.6, 1e-15);
        const SpatialJointDescription& cylinder = limb.joints[1];
        EXPECT_TRUE(cylinder.actuated);
        EXPECT_NEAR(cylinder.direction.norm(), 1.0, 1e-15);
        EXPECT_NEAR((cylinder.direction - leg / 1.2).norm(), 0.0, 1e-15);  // along the leg
        EXPECT_EQ(cylinder.limits.lower, -0.15);
        EXPECT_EQ(cylinder.limits.upper, 0.15);
        EXPECT_EQ(cylinder.limits.effort, 1.0e4);
        EXPECT_NEAR(limb.joints[0].axis1.dot(limb.joints[0].axis2), 0.0, 1e-15);
    }
    // six-freedom legs allow every twist: the full platform turns
    EXPECT_EQ(freeRotationsAtHome(robot).cols(), 3);
}

TEST(SpatialRobotFile, TheSixRusReadsAndClosesAtHome) {
    const SpatialRobotDescription robot = io::loadSpatialRobotDescription(shipped("hexa-6rus.yaml"));
    ASSERT_EQ(robot.limbs.size(), 6u);
    EXPECT_EQ(robot.actuatorCount(), 6);
    EXPECT_NEAR(robot.totalMass(), 1.0 + 6.0 * (0.3 + 0.1), 1e-12);
    for (const SpatialLimbDescription& limb : robot.limbs) {
        EXPECT_EQ(limb.type(), "RUS");
        EXPECT_TRUE(limb.joints[0].actuated);
        EXPECT_NEAR((limb.joints[1].point - limb.joints[0].point).norm(), 0.1, 1e-15);
        EXPECT_NEAR((limb.joints[2].point - limb.joints[1].point).norm(), 0.35, 1e-15);
        EXPECT_NEAR((limb.joints[2].point - robot.home.head<3>()).norm(), 0.15, 1e-15);
    }
}

TEST(SpatialRobotFile, ALimbsScrewsAreTheJointAxesAtHome) {
    const SpatialRobotDescription robot = io::parseSpatialRobotDescription(kBase, "cartesian.yaml");
    const Eigen::Matrix<double, 6, Eigen::Dynamic> screws = limbScrews(robot.limbs[1]);
    ASSERT_EQ(screws.cols(), 6);
    // R about z through (1, 0, 0): [0, 0, 1; p x a = (0, -1, 0)]
    Eigen::Matrix<double, 6, 1> r;
    r << 0.0, 0.0, 1.0, 0.0, -1.0, 0.0;
    EXPECT_EQ(screws.col(0), r);
    // the S's third screw: z through (0, 0, 0.5), no moment
    EXPECT_EQ(screws.col(5), r.cwiseProduct((Eigen::Matrix<double, 6, 1>() << 1, 1, 1, 0, 0, 0).finished()));
    EXPECT_EQ(limbScrews(robot.limbs[0]).topRows<3>().norm(), 0.0);  // P: no rotation
}

TEST(SpatialRobotFile, UnknownKeysAreRefusedWithTheirLineAndJoint) {
    expectRefused(edited("[0.0, 1.0, 0.0], actuated: true}", "[0.0, 1.0, 0.0], actuated: true, speed: 1.0}"),
                  {"cartesian.yaml:11:", "limbs[0] (gantry).joints[1].speed: unknown key"});
    expectRefused(edited("name: cartesian\n", "name: cartesian\ndamping_ratio: 0.02\n"),
                  {"cartesian.yaml:2:", "damping_ratio: unknown key"});
    expectRefused(edited("{mass: 1.0, com: [1.0, 0.1, 0.15],", "{mass: 1.0, size: 2, com: [1.0, 0.1, 0.15],"),
                  {"cartesian.yaml:22:", "limbs[1] (guide).bodies[0].size: unknown key"});
}

TEST(SpatialRobotFile, MissingAndNonFiniteNumbersAreRefused) {
    expectRefused(edited("{mass: 5.0,", "{mass: .nan,"), {"cartesian.yaml:14:", "limbs[0] (gantry).bodies[0].mass"});
    expectRefused(edited("point: [0.0, 0.0, 0.5]}", "point: [0.0, .inf, 0.5]}"),
                  {"cartesian.yaml:20:", "limbs[1] (guide).joints[2].point[1]"});
    expectRefused(edited("{mass: 3.0, com: [0.0, 0.0, 0.2], ", "{com: [0.0, 0.0, 0.2], "),
                  {"cartesian.yaml:15:", "limbs[0] (gantry).bodies[1].mass: required number is missing"});
    expectRefused(edited(", axis: [0.0, 0.0, 3.0]}", "}"),
                  {"cartesian.yaml:18:", "limbs[1] (guide).joints[0].axis: required [x, y, z] is missing"});
    expectRefused(edited("inertia: [[0.2, 0.0, 0.0], [0.0, 0.2, 0.0], [0.0, 0.0, 0.2]]",
                         "inertia: [[0.2, 0.0, 0.0], [0.0, 0.2, 0.0], [0.0, 0.0]]"),
                  {"cartesian.yaml:14:", "limbs[0] (gantry).bodies[0].inertia: expected the 3x3 tensor"});
}

TEST(SpatialRobotFile, ZeroAxesAndDirectionsAreRefused) {
    expectRefused(edited("axis: [0.0, 0.0, 3.0]", "axis: [0.0, 0.0, 0.0]"),
                  {"cartesian.yaml:18:", "limbs[1] (guide).joints[0].axis: must be a non-zero vector"});
    expectRefused(edited("direction: [0.0, 1.0, 0.0]", "direction: [0.0, 0.0, 0.0]"),
                  {"cartesian.yaml:11:", "limbs[0] (gantry).joints[1].direction: must be a non-zero vector"});
    expectRefused(edited("axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]", "axes: [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]]"),
                  {"cartesian.yaml:19:", "limbs[1] (guide).joints[1].axes[1]: must be a non-zero vector"});
}

TEST(SpatialRobotFile, AUniversalJointWithParallelAxesIsRefused) {
    expectRefused(edited("axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]", "axes: [[1.0, 0.0, 0.0], [-2.0, 0.0, 1.0e-10]]"),
                  {"cartesian.yaml:19:", "limbs[1] (guide).joints[1].axes: a U joint's two axes must not be parallel"});
    // at the bound the sine is 1e-9 and the axes are taken
    (void)io::parseSpatialRobotDescription(
        edited("axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]", "axes: [[1.0, 0.0, 0.0], [1.0, 2.0e-9, 0.0]]"), "ok.yaml");
}

TEST(SpatialRobotFile, KeysAUniversalOrSphericalJointDoesNotTakeAreRefused) {
    expectRefused(edited("{type: S, point: [0.0, 0.0, 0.5]}", "{type: S, point: [0.0, 0.0, 0.5], damping: 1.0}"),
                  {"cartesian.yaml:20:", "limbs[1] (guide).joints[2].damping: an S joint takes no actuated, limits"});
    expectRefused(
        edited("{type: U, point: [1.0, 0.2, 0.3],", "{type: U, limits: {lower: -1, upper: 1}, point: [1.0, 0.2, 0.3],"),
        {"cartesian.yaml:19:", "limbs[1] (guide).joints[1].limits: a U joint takes no"});
    expectRefused(
        edited("{type: U, point: [1.0, 0.2, 0.3],", "{type: U, axis: [1.0, 0.0, 0.0], point: [1.0, 0.2, 0.3],"),
        {"cartesian.yaml:19:", "limbs[1] (guide).joints[1].axis: a U joint takes a point and two axes"});
    expectRefused(
        edited("{type: R, point: [1.0, 0.0, 0.0],", "{type: R, direction: [1.0, 0.0, 0.0], point: [1.0, 0.0, 0.0],"),
        {"cartesian.yaml:18:", "joints[0].direction: an R joint takes a point and an axis"});
    expectRefused(edited("{type: P, direction: [0.0, 1.0, 0.0],",
                         "{type: P, point: [0.0, 0.0, 0.0], direction: [0.0, 1.0, 0.0],"),
                  {"cartesian.yaml:11:", "joints[1].point: a P joint takes a direction"});
    expectRefused(edited("{type: S, point:", "{type: Q, point:"),
                  {"cartesian.yaml:20:", "joints[2].type: unknown joint type 'Q' (expected R, P, U or S)"});
}

TEST(SpatialRobotFile, AnActuatedUniversalOrSphericalJointIsRefused) {
    expectRefused(edited("{type: U, point: [1.0, 0.2, 0.3],", "{type: U, actuated: true, point: [1.0, 0.2, 0.3],"),
                  {"cartesian.yaml:19:", "limbs[1] (guide).joints[1].actuated: a U joint cannot be actuated"});
    expectRefused(edited("{type: S, point: [0.0, 0.0, 0.5]}", "{type: S, point: [0.0, 0.0, 0.5], actuated: true}"),
                  {"cartesian.yaml:20:", "limbs[1] (guide).joints[2].actuated: an S joint cannot be actuated"});
}

TEST(SpatialRobotFile, ANegativeMassIsRefused) {
    expectRefused(edited("{mass: 1.0, com: [1.0, 0.1, 0.15],", "{mass: -1.0, com: [1.0, 0.1, 0.15],"),
                  {"cartesian.yaml:22:", "limbs[1] (guide).bodies[0].mass: must be in [0,", "got -1"});
    expectRefused(edited("platform: {mass: 2.0,", "platform: {mass: -0.5,"),
                  {"cartesian.yaml:6:", "platform.mass: must be in [0,"});
}

TEST(SpatialRobotFile, AnImpossibleInertiaIsRefused) {
    const std::string body = "[[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.001]]}\n      - {mass: 1.0, com: [0.5";
    const auto with = [&](const std::string& tensor) {
        return edited(body, tensor + "}\n      - {mass: 1.0, com: [0.5");
    };
    expectRefused(with("[[0.01, 0.001, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.001]]"),
                  {"cartesian.yaml:22:", "limbs[1] (guide).bodies[0].inertia: the tensor must be symmetric"});
    expectRefused(with("[[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, -0.001]]"),
                  {"cartesian.yaml:22:", "bodies[0].inertia: the tensor must be positive semi-definite"});
    expectRefused(with("[[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.03]]"),
                  {"cartesian.yaml:22:", "bodies[0].inertia: the principal moments", "triangle inequality"});
    // the inequality's bound is a thin rod's tensor (0, m l^2 / 12, m l^2 / 12): taken
    (void)io::parseSpatialRobotDescription(with("[[0.0, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.01]]"), "ok.yaml");
    // the off-diagonal entries count: Ixy = 0.02 makes [[0.01, 0.02], [0.02, 0.01]] indefinite
    expectRefused(edited("platform: {mass: 2.0, inertia: [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0]",
                         "platform: {mass: 2.0, inertia: [[0.1, 0.2, 0.0], [0.2, 0.1, 0.0]"),
                  {"cartesian.yaml:6:", "platform.inertia: the tensor must be positive semi-definite"});
}

TEST(SpatialRobotFile, BodiesAreOneFewerThanTheListedJoints) {
    const std::string last =
        "      - {mass: 1.0, com: [0.5, 0.1, 0.4], inertia: [[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.001]]}\n";
    expectRefused(edited(last, ""), {"cartesian.yaml:22:",
                                     "limbs[1] (guide).bodies: a limb of 3 listed joints (RUS) has 2 "
                                     "bodies",
                                     "got 1"});
    expectRefused(edited(last, last + last), {"limbs[1] (guide).bodies:", "got 3"});
}

TEST(SpatialRobotFile, FullMotionNeedsSixFreedomsPerLimb) {
    const std::string full = edited("home: [0.0, 0.0, 0.5]", "home: [0.0, 0.0, 0.5, 0.0, 0.0, 0.0]",
                                    edited("motion: translation", "motion: full"));
    expectRefused(full, {"cartesian.yaml:10:",
                         "limbs[0] (gantry).joints: motion full needs exactly six joint "
                         "freedoms per limb",
                         "PPP has 3"});
    // more than six anywhere is refused at the joint that exceeds them
    expectRefused(
        edited("{type: S, point: [0.0, 0.0, 0.5]}",
               "{type: S, point: [0.0, 0.0, 0.5]}\n      - {type: S, point: [0.0, 0.0, 0.6]}"),
        {"cartesian.yaml:21:", "limbs[1] (guide).joints[3]: a limb has at most six joint freedoms", "RUSS has 9"});
}

TEST(SpatialRobotFile, AHomeAtPitchNinetyDegreesIsRefused) {
    const std::string full = edited("motion: translation", "motion: full");
    expectRefused(edited("home: [0.0, 0.0, 0.5]", "home: [0.0, 0.0, 0.5, 0.1, 1.5707963267948966, 0.2]", full),
                  {"cartesian.yaml:5:", "home[4]: pitch = +-90 degrees"});
    expectRefused(edited("home: [0.0, 0.0, 0.5]", "home: [0.0, 0.0, 0.5, 0.1, -1.5707963267948966, 0.2]", full),
                  {"cartesian.yaml:5:", "home[4]: pitch = +-90 degrees"});
    expectRefused(edited("home: [0.0, 0.0, 0.5]", "home: [0.0, 0.0, 0.5, 0.0, 0.0, 0.0]"),
                  {"cartesian.yaml:5:", "home: expected [x, y, z] (motion translation)"});
}

TEST(SpatialRobotFile, ATranslationRobotThatLeavesARotationFreeIsRefused) {
    // the gantry's vertical slide replaced by a vertical axis: both limbs then allow a turn about z
    expectRefused(edited("{type: P, direction: [0.0, 0.0, 1.0], actuated: true}",
                         "{type: R, point: [0.0, 0.0, 0.5], axis: [0.0, 0.0, 1.0], actuated: true}"),
                  {"cartesian.yaml:3:",
                   "motion: translation, but at home the limbs leave the platform free to turn "
                   "about [0, 0, 1]"});
    // a Delta whose platform joints are balls (3-RUS): every rotation is free
    std::string delta = io::readRobotFileText(shipped("delta.yaml"));
    delta = std::regex_replace(
        delta, std::regex(R"(\{type: U, point: (\[[^\]]*\]), axes: \[\[[^\]]*\], \[[^\]]*\]\]\}   # platform)"),
        "{type: S, point: $1}   # platform");
    try {
        (void)io::parseSpatialRobotDescription(delta, "delta-rus.yaml");
        ADD_FAILURE() << "a 3-RUS accepted as a translation robot";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("delta-rus.yaml:11: motion: translation, but at home the limbs leave the platform free "
                               "to turn about any axis"),
                  std::string::npos)
            << message;
    }
}

TEST(SpatialRobotFile, TwoFreeRotationsAreNamedByTheirPlanesNormal) {
    // balls at the platform on arms 1 and 2: only arm 3's constraint is left, a couple along
    // u_3 x w_3 (normal to both its cross axes), so the platform turns about any axis normal to it
    std::string text = io::readRobotFileText(shipped("delta.yaml"));
    text = std::regex_replace(
        text, std::regex(R"(\{type: U, point: (\[[^\]]*\]), axes: \[\[[^\]]*\], \[[^\]]*\]\]\}   # platform)"),
        "{type: S, point: $1}   # platform", std::regex_constants::format_first_only);
    text = std::regex_replace(
        text, std::regex(R"(\{type: U, point: (\[[^\]]*\]), axes: \[\[[^\]]*\], \[[^\]]*\]\]\}   # platform)"),
        "{type: S, point: $1}   # platform", std::regex_constants::format_first_only);
    const SpatialRobotDescription delta = io::loadSpatialRobotDescription(shipped("delta.yaml"));
    const SpatialJointDescription& elbow = delta.limbs[2].joints[1];
    Eigen::Vector3d normal = elbow.axis1.cross(elbow.axis2).normalized();
    Eigen::Index largest = 0;
    normal.cwiseAbs().maxCoeff(&largest);
    if (normal(largest) < 0.0) normal = -normal;
    char expected[128];
    std::snprintf(expected, sizeof expected, "free to turn about any axis normal to [%.6g, %.6g, %.6g]", normal(0),
                  normal(1), normal(2));
    try {
        (void)io::parseSpatialRobotDescription(text, "delta-2rus.yaml");
        ADD_FAILURE() << "a Delta with two ball-jointed arms accepted as a translation robot";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(std::string("delta-2rus.yaml:11: motion: translation, but at home the "
                                                         "limbs leave the platform ") +
                                             expected),
                  std::string::npos)
            << e.what() << "\nexpected " << expected;
    }
}

enum class PlatformAxes { tsai, same_order, radial };

/// Tsai's 3-UPU: base U (a1 tangent, a2 across the leg), the leg's P, platform U with the same
/// two axes in the other order; or in the same order; or with a radial axis instead of a1.
std::string tsai(PlatformAxes platform) {
    const auto vec = [](const Eigen::Vector3d& v) {
        return "[" + text::shortest(v.x()) + ", " + text::shortest(v.y()) + ", " + text::shortest(v.z()) + "]";
    };
    const Eigen::Vector3d home(0.0, 0.0, 0.4);
    std::string out = "space: spatial\nmotion: translation\nhome: " + vec(home) + "\nplatform: {mass: 1.0}\nlimbs:\n";
    for (int i = 0; i < 3; ++i) {
        const double phi = 2.0 * 3.14159265358979 * i / 3.0;
        const Eigen::Vector3d radial(std::cos(phi), std::sin(phi), 0.0), tangent(-std::sin(phi), std::cos(phi), 0.0);
        const Eigen::Vector3d base = 0.3 * radial, top = home + 0.1 * radial;
        const Eigen::Vector3d leg = (top - base).normalized();
        const Eigen::Vector3d a1 = tangent, a2 = leg.cross(a1).normalized();
        const Eigen::Vector3d mid = 0.5 * (base + top);
        out += "  - joints:\n";
        out += "      - {type: U, point: " + vec(base) + ", axes: [" + vec(a1) + ", " + vec(a2) + "]}\n";
        out += "      - {type: P, direction: " + vec(leg) + ", actuated: true}\n";
        const std::string axes = platform == PlatformAxes::tsai         ? vec(a2) + ", " + vec(a1)
                                 : platform == PlatformAxes::same_order ? vec(a1) + ", " + vec(a2)
                                                                        : vec(a2) + ", " + vec(radial);
        out += "      - {type: U, point: " + vec(top) + ", axes: [" + axes + "]}\n";
        out += "    bodies:\n";
        for (int b = 0; b < 2; ++b) {
            out += "      - {mass: 0.5, com: " + vec(b == 0 ? 0.5 * (base + mid) : 0.5 * (mid + top)) +
                   ", inertia: [[0.001, 0.0, 0.0], [0.0, 0.001, 0.0], [0.0, 0.0, 0.001]]}\n";
        }
    }
    return out;
}

TEST(SpatialRobotFile, TsaisThreeUpuKeepsTheOrientationAndATwistedOneDoesNot) {
    const SpatialRobotDescription robot = io::parseSpatialRobotDescription(tsai(PlatformAxes::tsai), "3-upu.yaml");
    EXPECT_EQ(robot.limbs[0].type(), "UPU");
    EXPECT_EQ(robot.limbs[0].freedoms(), 5);
    EXPECT_EQ(freeRotationsAtHome(robot).cols(), 0);
    // the check sees the joint screws at home, not which body carries which U axis: the same
    // lines in the other order pass it (keeping the orientation away from home is the model's
    // check at every sample)
    EXPECT_EQ(
        freeRotationsAtHome(io::parseSpatialRobotDescription(tsai(PlatformAxes::same_order), "3-upu.yaml")).cols(), 0);
    // a radial platform axis instead of the base's tangent one: the limbs' screws span rotations
    try {
        (void)io::parseSpatialRobotDescription(tsai(PlatformAxes::radial), "3-upu.yaml");
        ADD_FAILURE() << "a 3-UPU with radial platform axes accepted as a translation robot";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("3-upu.yaml:2: motion: translation, but at home the limbs leave the "
                                             "platform free to turn about"),
                  std::string::npos)
            << e.what();
    }
}

TEST(SpatialRobotFile, ParametersAndTheirOverridesWorkAsInThePlanarForm) {
    const std::string text = edited("home: [0.0, 0.0, 0.5]", "parameters: {h: 0.5}\nhome: [0.0, 0.0, h]",
                                    edited("{type: S, point: [0.0, 0.0, 0.5]}", "{type: S, point: [0.0, 0.0, h]}"));
    EXPECT_EQ(io::parseSpatialRobotDescription(text, "p.yaml").home(2), 0.5);
    const SpatialRobotDescription lower = io::parseSpatialRobotDescription(text, "p.yaml", {{"h", 0.4}});
    EXPECT_EQ(lower.home(2), 0.4);
    EXPECT_EQ(lower.limbs[1].joints[2].point.z(), 0.4);
}

TEST(SpatialRobotFile, EveryCommandRefusesASpatialRobotInOneLine) {
    const std::string path = shipped("stewart.yaml");
    try {
        (void)io::loadRobotDescription(path);
        ADD_FAILURE() << "a spatial robot loaded as a planar one";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), path + ": " + io::kSpatialNotComputed);
    }
    // an error in the file comes first, with its line
    expectRefused(edited("{mass: 5.0,", "{mass: -5.0,"), {"cartesian.yaml:14:"});
    try {
        (void)io::parseRobotDescription(edited("{mass: 5.0,", "{mass: -5.0,"), "cartesian.yaml");
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cartesian.yaml:14: limbs[0] (gantry).bodies[0].mass"), std::string::npos)
            << e.what();
    }
    const test::CliResult result = test::runCli("workspace --robot " + shipped("delta.yaml"));
    EXPECT_NE(result.exit_code, 0);
    EXPECT_EQ(result.out, "");
    EXPECT_EQ(result.err, "nocdyn: error: " + shipped("delta.yaml") +
                              ": a spatial robot (space: spatial): this command is planar for now (nocdyn pose and "
                              "Robot.load take it)\n");
}

TEST(SpatialRobotFile, PoseReportsASpatialRobotsJointsActuationAndForcesAtRest) {
    // the hexapod at home: its six legs alike (the design's symmetry), each at 0 of its stroke
    const test::CliResult home =
        test::runCli("pose 0 0 1.0579369000754848 0 0 0 --json --robot " + shipped("stewart.yaml"));
    ASSERT_EQ(home.exit_code, 0) << home.err;
    const nlohmann::json j = nlohmann::json::parse(home.out);
    ASSERT_EQ(j["tau"].size(), 6u);
    for (const auto& tau : j["tau"]) EXPECT_NEAR(tau.get<double>(), j["tau"][0].get<double>(), 1e-9);
    EXPECT_GT(j["tau"][0].get<double>(), 0.0);
    for (const auto& a : j["actuators"]) EXPECT_NEAR(a["u"].get<double>(), 0.0, 1e-12);
    EXPECT_EQ(j["A"].size(), 6u);
    EXPECT_EQ(j["limbs"][0]["type"], "UPS");
    EXPECT_EQ(j["limbs"][0]["q"].size(), 6u);
    // the Delta over x, y, z, as text
    const test::CliResult delta = test::runCli("pose 0 0 -0.85 --robot " + shipped("delta.yaml"));
    ASSERT_EQ(delta.exit_code, 0) << delta.err;
    EXPECT_NE(delta.out.find("robot delta (spatial), pose x = 0 m, y = 0 m, z = -0.85 m\n"), std::string::npos)
        << delta.out;
    EXPECT_NE(delta.out.find("columns: v_x v_y v_z):"), std::string::npos) << delta.out;
    // a pose of the wrong length, and angles for a planar robot, in one line each
    const test::CliResult short_pose = test::runCli("pose 0 0 1.05 --robot " + shipped("stewart.yaml"));
    EXPECT_NE(short_pose.exit_code, 0);
    EXPECT_EQ(short_pose.err,
              "nocdyn: error: pose: the robot stewart takes 6 pose coordinates (X Y Z ROLL PITCH YAW), got 3\n");
    const test::CliResult planar = test::runCli("pose 0 0 0 0.1 --robot " + shipped("3-rrr.yaml"));
    EXPECT_NE(planar.exit_code, 0);
    EXPECT_EQ(planar.err, "nocdyn: error: pose: ROLL PITCH YAW are for a spatial robot\n");
    const test::CliResult far = test::runCli("pose 0 0 -1.6 --robot " + shipped("delta.yaml"));
    EXPECT_NE(far.exit_code, 0);
    EXPECT_EQ(far.err.rfind("nocdyn: error: " + shipped("delta.yaml") + ": pose out of reach: limb 1 (arm1)", 0), 0u)
        << far.err;
}

TEST(SpatialRobotFile, ValidateReadsChecksAndSummarisesASpatialRobot) {
    if (test::runCli("validate --help > /dev/null").exit_code != 0) {
        NOCDYN_SKIP_OR_FAIL_IN_CI("nocdyn validate is built with Simbody and MuJoCo only");
    }
    const test::CliResult stewart = test::runCli("validate --robot " + shipped("stewart.yaml"));
    EXPECT_EQ(stewart.exit_code, 0) << stewart.err;
    EXPECT_EQ(stewart.out,
              "stewart: a spatial robot (motion full, pose [x, y, z, roll, pitch, yaw]), read and checked\n"
              "  limbs: 6 (6 UPS)\n"
              "  joints: 18 (6 P, 6 U, 6 S), 36 joint freedoms\n"
              "  actuators: 6 (6 P)\n"
              "  mass: 498 kg (platform 300 kg)\n"
              "give --trajectory to compare its actuator forces with Simbody's and MuJoCo's spatial models along it\n");
    const test::CliResult delta = test::runCli("validate --robot " + shipped("delta.yaml"));
    EXPECT_EQ(delta.exit_code, 0) << delta.err;
    EXPECT_NE(delta.out.find("  joints: 9 (3 R, 6 U), 15 joint freedoms\n  actuators: 3 (3 R)\n  mass: 3.15 kg"),
              std::string::npos)
        << delta.out;
    // an error in the file: one line naming it, its line and the joint; nothing on stdout
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_robot_file");
    const std::string bad = (dir / "bad.yaml").string();
    std::ofstream(bad) << edited("axis: [0.0, 0.0, 3.0]", "axis: [0.0, 0.0, 0.0]");
    const test::CliResult refused = test::runCli("validate --robot " + bad);
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_EQ(refused.out, "");
    EXPECT_EQ(refused.err, "nocdyn: error: " + bad +
                               ":18: limbs[1] (guide).joints[0].axis: must be a non-zero vector, got [0, 0, 0]\n");
    // a planar robot still needs its trajectory
    const test::CliResult planar = test::runCli("validate --robot " + shipped("3-rrr.yaml"));
    EXPECT_EQ(planar.exit_code, 2);
    EXPECT_EQ(planar.err, "nocdyn: error: --trajectory is required (see nocdyn validate --help)\n");
}

}  // namespace
}  // namespace nocdyn
