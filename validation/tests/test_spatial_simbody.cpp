// nocdyn's spatial inverse dynamics (nocdyn/spatial.hpp) against the independent Simbody model
// (SimbodySpatialMechanism) on the shipped Delta (3-RUU), 6-UPS and 6-RUS, gravity on and the
// joints' damping and friction as in the files, along a smooth two-harmonic motion about home;
// and on random 6-UPS, 6-RUS and 6-SPU hexapods (an S in a tree, a U closure at 70 degrees).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/validation/simbody_spatial.hpp"
#include "spatial_test_robots.hpp"

namespace {

using namespace nocdyn_spatial_test;

double relativeDifference(const nocdyn::SpatialRobotDescription& robot,
                          const nocdyn::SpatialRobotDescription& engine_robot, double length, double angle,
                          double min_peak) {
    return nocdyn_spatial_test::relativeDifference<nocdyn::validation::SimbodySpatialMechanism>(
        robot, engine_robot, length, angle, min_peak);
}

double relativeDifference(const std::string& name, double length, double angle, double min_peak) {
    const nocdyn::SpatialRobotDescription robot = shipped(name);
    return relativeDifference(robot, robot, length, angle, min_peak);
}

TEST(SpatialSimbody, StewartPlatformAgrees) {
    EXPECT_LT(relativeDifference("stewart", 0.02, 0.04, 1000.0), kRelativeTolerance);
}

TEST(SpatialSimbody, SixRusAgrees) { EXPECT_LT(relativeDifference("hexa-6rus", 0.01, 0.04, 0.1), kRelativeTolerance); }

TEST(SpatialSimbody, DeltaAgrees) { EXPECT_LT(relativeDifference("delta", 0.03, 0.0, 1.0), kRelativeTolerance); }

}  // namespace

namespace {

// The comparison sees small changes of the Simbody model's data: the cylinders' friction and
// damping left out, a product of inertia of the table, 2 % of the Delta's platform mass, the
// sign of a product of inertia of a 6-RUS rod.
TEST(SpatialSimbody, TheComparisonSeesSmallChangesOfTheEnginesData) {
    const nocdyn::SpatialRobotDescription stewart = shipped("stewart");
    nocdyn::SpatialRobotDescription changed = stewart;
    for (nocdyn::SpatialLimbDescription& limb : changed.limbs) {
        for (nocdyn::SpatialJointDescription& joint : limb.joints) joint.damping = joint.friction = 0.0;
    }
    EXPECT_GT(relativeDifference(stewart, changed, 0.02, 0.04, 1000.0), 1e-3);
    changed = stewart;
    changed.platform.inertia(0, 1) = changed.platform.inertia(1, 0) = 1.0;
    EXPECT_GT(relativeDifference(stewart, changed, 0.02, 0.04, 1000.0), 1e-5);

    const nocdyn::SpatialRobotDescription delta = shipped("delta");
    changed = delta;
    changed.platform.mass *= 1.02;
    EXPECT_GT(relativeDifference(delta, changed, 0.03, 0.0, 1.0), 1e-4);

    const nocdyn::SpatialRobotDescription rus = shipped("hexa-6rus");
    changed = rus;
    Eigen::Matrix3d& I = changed.limbs[2].bodies[1].inertia;
    I(0, 2) = I(2, 0) = -I(0, 2);
    EXPECT_GT(relativeDifference(rus, changed, 0.01, 0.04, 0.1), 1e-6);
}

}  // namespace

namespace {

TEST(SpatialSimbody, RandomHexapodsAgree) {
    std::mt19937 rng(2026);
    for (const bool rus : {false, true}) {
        for (int robot = 0; robot < 3; ++robot) {
            const nocdyn::SpatialRobotDescription d = randomHexapod(rng, rus);
            EXPECT_LT(relativeDifference(d, d, 0.02, 0.03, 1.0), kRelativeTolerance) << d.name << " " << robot;
        }
    }
    for (int robot = 0; robot < 3; ++robot) {
        const nocdyn::SpatialRobotDescription d = randomSpu(rng);
        EXPECT_LT(relativeDifference(d, d, 0.02, 0.03, 1.0), kRelativeTolerance) << d.name << " " << robot;
    }
}

}  // namespace

namespace {

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const nocdyn::Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(SpatialSimbody, WhatTheModelCannotTakeIsNamed) {
    nocdyn::SpatialRobotDescription delta = shipped("delta");
    const std::vector<Eigen::VectorXd> out_of_reach{Eigen::Vector3d(0.0, 0.0, -2.0)}, zero{Eigen::Vector3d::Zero()};
    nocdyn::validation::SimbodySpatialMechanism engine(delta);
    EXPECT_NE(
        messageOf([&] { (void)engine.actuatorForces(out_of_reach, zero, zero); }).find("cannot assemble sample 0"),
        std::string::npos);
    delta.limbs[1].joints[2].type = nocdyn::SpatialJointType::revolute;
    const std::string message = messageOf([&] { nocdyn::validation::SimbodySpatialMechanism closed_at_r(delta); });
    EXPECT_NE(message.find("delta.yaml: limb arm2: the Simbody model closes a limb at an S or U joint only"),
              std::string::npos)
        << message;
}

}  // namespace
