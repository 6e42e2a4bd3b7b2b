// nocdyn's spatial inverse dynamics (nocdyn/spatial.hpp) against the independent MuJoCo model
// (MujocoSpatialMechanism) on the shipped Delta (3-RUU), 6-UPS and 6-RUS, gravity on and the
// joints' damping and friction as in the files, along a smooth two-harmonic motion about home;
// on random 6-UPS, 6-RUS and 6-SPU hexapods (an S in a tree, a U closure at 70 degrees) and
// random Deltas; and MuJoCo's model against Simbody's, the two engines alone.
#include <cstdio>
#include <functional>
#include <tuple>
#include <string>

#include <gtest/gtest.h>

#include "nocdyn/error.hpp"
#include "nocdyn/validation/mujoco_spatial.hpp"
#include "nocdyn/validation/simbody_spatial.hpp"
#include "spatial_test_robots.hpp"

namespace {

using namespace nocdyn_spatial_test;
using nocdyn::validation::MujocoSpatialMechanism;

// Agreement asked of nocdyn's forces with MuJoCo's, relative to their peak: reached to 3e-14 on
// the hexapods and Deltas, 1.5e-12 on the shipped 6-RUS; 1e-10 leaves room for a faster core.
constexpr double kMujocoTolerance = 1e-10;
// The two engines alone, relative to Simbody's peak.
constexpr double kEnginesTolerance = 1e-12;

double mujocoDifference(const nocdyn::SpatialRobotDescription& robot,
                        const nocdyn::SpatialRobotDescription& engine_robot, double length, double angle,
                        double min_peak) {
    return relativeDifference<MujocoSpatialMechanism>(robot, engine_robot, length, angle, min_peak);
}

double mujocoDifference(const std::string& name, double length, double angle, double min_peak) {
    const nocdyn::SpatialRobotDescription robot = shipped(name);
    return mujocoDifference(robot, robot, length, angle, min_peak);
}

TEST(SpatialMujoco, StewartPlatformAgrees) {
    EXPECT_LT(mujocoDifference("stewart", 0.02, 0.04, 1000.0), kMujocoTolerance);
}

TEST(SpatialMujoco, SixRusAgrees) { EXPECT_LT(mujocoDifference("hexa-6rus", 0.01, 0.04, 0.1), kMujocoTolerance); }

TEST(SpatialMujoco, DeltaAgrees) { EXPECT_LT(mujocoDifference("delta", 0.03, 0.0, 1.0), kMujocoTolerance); }

// The comparison sees small changes of the MuJoCo model's data: 2 % of the platform's mass of
// each shipped robot, the cylinders' friction and damping left out, a product of inertia of a
// 6-RUS rod of the other sign.
TEST(SpatialMujoco, TheComparisonSeesSmallChangesOfTheEnginesData) {
    for (const auto& [name, length, angle, min_peak] :
         {std::tuple{"stewart", 0.02, 0.04, 1000.0}, std::tuple{"hexa-6rus", 0.01, 0.04, 0.1},
          std::tuple{"delta", 0.03, 0.0, 1.0}}) {
        const nocdyn::SpatialRobotDescription robot = shipped(name);
        nocdyn::SpatialRobotDescription changed = robot;
        changed.platform.mass *= 1.02;
        EXPECT_GT(mujocoDifference(robot, changed, length, angle, min_peak), 1e-4) << name;
    }
    const nocdyn::SpatialRobotDescription stewart = shipped("stewart");
    nocdyn::SpatialRobotDescription changed = stewart;
    for (nocdyn::SpatialLimbDescription& limb : changed.limbs) {
        for (nocdyn::SpatialJointDescription& joint : limb.joints) joint.damping = joint.friction = 0.0;
    }
    EXPECT_GT(mujocoDifference(stewart, changed, 0.02, 0.04, 1000.0), 1e-3);
    const nocdyn::SpatialRobotDescription rus = shipped("hexa-6rus");
    changed = rus;
    Eigen::Matrix3d& I = changed.limbs[2].bodies[1].inertia;
    I(0, 2) = I(2, 0) = -I(0, 2);
    EXPECT_GT(mujocoDifference(rus, changed, 0.01, 0.04, 0.1), 1e-6);
}

TEST(SpatialMujoco, RandomRobotsAgree) {
    std::mt19937 rng(2026);
    for (const bool rus : {false, true}) {
        for (int robot = 0; robot < 3; ++robot) {
            const nocdyn::SpatialRobotDescription d = randomHexapod(rng, rus);
            EXPECT_LT(mujocoDifference(d, d, 0.02, 0.03, 1.0), kMujocoTolerance) << d.name << " " << robot;
        }
    }
    for (int robot = 0; robot < 3; ++robot) {
        const nocdyn::SpatialRobotDescription d = randomSpu(rng);
        EXPECT_LT(mujocoDifference(d, d, 0.02, 0.03, 1.0), kMujocoTolerance) << d.name << " " << robot;
    }
    for (int robot = 0; robot < 3; ++robot) {
        const nocdyn::SpatialRobotDescription d = randomDelta(rng);
        EXPECT_LT(mujocoDifference(d, d, 0.03, 0.0, 0.1), kMujocoTolerance) << d.name << " " << robot;
    }
}

// The two engines alone, without nocdyn: MuJoCo's forces against Simbody's on the shipped robots.
TEST(SpatialMujoco, AgreesWithSimbody) {
    for (const auto& [name, length, angle] :
         {std::tuple{"stewart", 0.02, 0.04}, std::tuple{"hexa-6rus", 0.01, 0.04}, std::tuple{"delta", 0.03, 0.0}}) {
        const nocdyn::SpatialRobotDescription robot = shipped(name);
        const Path path = twoHarmonics(robot, length, angle);
        MujocoSpatialMechanism mujoco_engine(robot);
        nocdyn::validation::SimbodySpatialMechanism simbody_engine(robot);
        const Eigen::MatrixXd mujoco = mujoco_engine.actuatorForces(path.p, path.dp, path.ddp);
        const Eigen::MatrixXd simbody = simbody_engine.actuatorForces(path.p, path.dp, path.ddp);
        // a second call starts from home again, not from where the first ended
        EXPECT_EQ(mujoco_engine.actuatorForces(path.p, path.dp, path.ddp), mujoco) << name;
        EXPECT_EQ(simbody_engine.actuatorForces(path.p, path.dp, path.ddp), simbody) << name;
        const double peak = simbody.cwiseAbs().maxCoeff();
        const double relative = (mujoco - simbody).cwiseAbs().maxCoeff() / peak;
        std::printf("%s: max |tau_mujoco - tau_simbody| / peak %.3e\n", name, relative);
        EXPECT_LT(relative, kEnginesTolerance) << name;
    }
}

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const nocdyn::Error& e) {
        return e.what();
    }
    return "no error";
}

TEST(SpatialMujoco, WhatTheModelCannotTakeIsNamed) {
    nocdyn::SpatialRobotDescription delta = shipped("delta");
    const std::vector<Eigen::VectorXd> out_of_reach{Eigen::Vector3d(0.0, 0.0, -2.0)}, zero{Eigen::Vector3d::Zero()};
    MujocoSpatialMechanism engine(delta);
    EXPECT_NE(
        messageOf([&] { (void)engine.actuatorForces(out_of_reach, zero, zero); }).find("cannot assemble sample 0"),
        std::string::npos);
    EXPECT_NE(engine.mjcf().find("<connect name=\"loop3\""), std::string::npos);
    delta.limbs[1].joints[2].type = nocdyn::SpatialJointType::revolute;
    const std::string message = messageOf([&] { MujocoSpatialMechanism closed_at_r(delta); });
    EXPECT_NE(message.find("delta.yaml: limb arm2: the MuJoCo spatial model closes a limb at an S or U joint only"),
              std::string::npos)
        << message;
}

}  // namespace
