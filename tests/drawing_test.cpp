// The drawable points of drawing.hpp: rigid bodies stay rigid along a motion, the platform
// polygon is the pose's transform of its home points, P joints stay on their rails at the
// joint variable, R joints sit on the axes of the kinematics' joint screws.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "nocdyn/drawing.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"

namespace nocdyn {
namespace {

const std::vector<std::string> kRobots = {"paper-3prr-general", "3-rrr", "3-rpr", "4-rrr"};

Model robotModel(const std::string& name) {
    return Model(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml"));
}

/// A small motion about home: 20 poses over one period of a few-millimetre circle and a
/// 0.05 rad swing.
std::vector<Pose> motion(const Model& model) {
    std::vector<Pose> poses;
    for (int k = 0; k < 20; ++k) {
        const double phase = 2.0 * M_PI * k / 20.0;
        poses.push_back(model.home +
                        Pose(0.05 * std::sin(phase), 0.004 * std::cos(phase), 0.003 * std::sin(2 * phase)));
    }
    return poses;
}

/// The points carried by body b (1 or 2) of a limb: the outboard point of joint b - 1 and the
/// inboard points (axis or rail ends) of joint b.
std::vector<Vector2> bodyPoints(const LimbDrawing& limb, int b) {
    const JointDrawing& in = limb.joint[static_cast<std::size_t>(b - 1)];
    const JointDrawing& out = limb.joint[static_cast<std::size_t>(b)];
    return {in.position, out.rail_start, out.rail_end};
}

TEST(Drawing, EveryBodyKeepsItsShapeAlongAMotionOfEveryExampleRobot) {
    for (const std::string& name : kRobots) {
        const Model model = robotModel(name);
        Data data(model);
        RobotDrawing home, now;
        ASSERT_TRUE(drawRobot(model, data, model.home, home)) << name;
        for (const Pose& p : motion(model)) {
            ASSERT_TRUE(drawRobot(model, data, p, now)) << name;
            for (int j = 0; j < model.limbs; ++j) {
                const auto& h = home.limb[static_cast<std::size_t>(j)];
                const auto& n = now.limb[static_cast<std::size_t>(j)];
                // the base anchors do not move
                EXPECT_LT((n.joint[0].rail_start - h.joint[0].rail_start).norm(), 1e-12) << name;
                EXPECT_LT((n.joint[0].rail_end - h.joint[0].rail_end).norm(), 1e-12) << name;
                for (int b = 1; b <= 2; ++b) {
                    const auto ph = bodyPoints(h, b), pn = bodyPoints(n, b);
                    for (std::size_t a = 0; a < ph.size(); ++a) {
                        for (std::size_t c = a + 1; c < ph.size(); ++c) {
                            EXPECT_NEAR((pn[a] - pn[c]).norm(), (ph[a] - ph[c]).norm(), 1e-12)
                                << name << " limb " << j + 1 << " body " << b;
                        }
                    }
                }
            }
        }
    }
}

TEST(Drawing, PlatformPolygonIsThePoseTransformOfItsHomePoints) {
    for (const std::string& name : kRobots) {
        const Model model = robotModel(name);
        Data data(model);
        RobotDrawing d;
        for (const Pose& p : motion(model)) {
            ASSERT_TRUE(drawRobot(model, data, p, d)) << name;
            const double dtheta = p(0) - model.home(0);
            Matrix2 rot;
            rot << std::cos(dtheta), -std::sin(dtheta), std::sin(dtheta), std::cos(dtheta);
            EXPECT_EQ(d.C, Vector2(p(1), p(2)));
            for (int j = 0; j < model.limbs; ++j) {
                const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
                const Vector2 expected =
                    rot * (jointReferencePoint(limb, 2) - model.home.tail<2>()) + Vector2(p(1), p(2));
                EXPECT_LT((d.platform[static_cast<std::size_t>(j)] - expected).norm(), 1e-12) << name << " limb " << j;
            }
        }
    }
}

TEST(Drawing, PrismaticJointsSitOnTheirRailsAtTheJointVariable) {
    for (const std::string& name : {std::string("paper-3prr-general"), std::string("3-rpr")}) {
        const Model model = robotModel(name);
        Data data(model);
        RobotDrawing d;
        int checked = 0;
        for (const Pose& p : motion(model)) {
            ASSERT_TRUE(drawRobot(model, data, p, d));
            for (int j = 0; j < model.limbs; ++j) {
                for (int k = 0; k < 3; ++k) {
                    const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
                    const JointDrawing& joint = d.limb[static_cast<std::size_t>(j)].joint[static_cast<std::size_t>(k)];
                    if (joint.type != JointType::prismatic) continue;
                    const double lower = limb.limits[static_cast<std::size_t>(k)].lower;
                    const double upper = limb.limits[static_cast<std::size_t>(k)].upper;
                    // the rail spans exactly the stroke, along the current direction
                    EXPECT_NEAR((joint.rail_end - joint.rail_start).norm(), upper - lower, 1e-12);
                    EXPECT_NEAR(cross(joint.direction, joint.rail_end - joint.rail_start), 0.0, 1e-12);
                    // the slider is at q along the rail
                    const Vector2 expected = joint.rail_start + (joint.q - lower) * joint.direction;
                    EXPECT_LT((joint.position - expected).norm(), 1e-12) << name << " limb " << j;
                    EXPECT_EQ(joint.q, data.u(joint.actuator));
                    ++checked;
                }
            }
        }
        EXPECT_EQ(checked, 20 * 3) << name;
    }
}

TEST(Drawing, RevoluteJointsSitOnTheAxesOfTheKinematicsJointScrews) {
    // an R screw referred to O is [1; r_y; -r_x]: its axis r is an independent computation
    for (const std::string& name : kRobots) {
        const Model model = robotModel(name);
        Data data(model);
        RobotDrawing d;
        for (const Pose& p : motion(model)) {
            ASSERT_TRUE(drawRobot(model, data, p, d));
            for (int j = 0; j < model.limbs; ++j) {
                for (int k = 0; k < 3; ++k) {
                    const JointDrawing& joint = d.limb[static_cast<std::size_t>(j)].joint[static_cast<std::size_t>(k)];
                    if (joint.type != JointType::revolute) continue;
                    const Twist& s = data.limb[static_cast<std::size_t>(j)].s[static_cast<std::size_t>(k)];
                    EXPECT_LT((joint.position - Vector2(-s(2), s(1))).norm(), 1e-12) << name << " limb " << j;
                }
            }
        }
    }
}

TEST(Drawing, APoseOutOfReachIsRefusedNamingTheLimb) {
    const Model model = robotModel("3-rrr");
    Data data(model);
    RobotDrawing d;
    const Status status = drawRobot(model, data, model.home + Pose(0.0, 5.0, 0.0), d);
    EXPECT_EQ(status.code, StatusCode::unreachable);
    EXPECT_GE(status.limb, 0);
}

}  // namespace
}  // namespace nocdyn
