// Shared by the spatial engine tests (Simbody, MuJoCo): the shipped spatial robots, a smooth
// two-harmonic path about home, random 6-UPS, 6-RUS, 6-SPU hexapods and Delta robots, and
// the agreement of nocdyn's spatial inverse dynamics with an engine's along the path.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"

namespace nocdyn_spatial_test {

// Agreement asked of the actuator forces, relative to their peak over the samples.
inline constexpr double kRelativeTolerance = 1e-9;
inline constexpr int kSamples = 50;

inline nocdyn::SpatialRobotDescription shipped(const std::string& name) {
    return nocdyn::io::loadSpatialRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml");
}

struct Path {
    std::vector<Eigen::VectorXd> p, dp, ddp;
};

/// p_i(t) = home_i + A_i (sin(w1 t + a_i) + 0.5 sin(w2 t + b_i)) over one second, A_i = `length`
/// for x, y, z and `angle` for roll, pitch, yaw; w1 = 2 pi 1.5 / s, w2 = 2 pi 2.5 / s, so that
/// the accelerations are a few m/s^2 for a few cm.
inline Path twoHarmonics(const nocdyn::SpatialRobotDescription& robot, double length, double angle) {
    const int n = robot.taskDimension();
    const double w1 = 2.0 * std::numbers::pi * 1.5, w2 = 2.0 * std::numbers::pi * 2.5;
    Path path;
    for (int s = 0; s < kSamples; ++s) {
        const double t = static_cast<double>(s) / kSamples;
        Eigen::VectorXd p(n), dp(n), ddp(n);
        for (int i = 0; i < n; ++i) {
            const double A = i < 3 ? length : angle;
            const double a = 0.7 * i + 0.3, b = 1.9 * i + 1.1;
            p[i] = robot.home[i] + A * (std::sin(w1 * t + a) + 0.5 * std::sin(w2 * t + b));
            dp[i] = A * (w1 * std::cos(w1 * t + a) + 0.5 * w2 * std::cos(w2 * t + b));
            ddp[i] = -A * (w1 * w1 * std::sin(w1 * t + a) + 0.5 * w2 * w2 * std::sin(w2 * t + b));
        }
        path.p.push_back(p);
        path.dp.push_back(dp);
        path.ddp.push_back(ddp);
    }
    return path;
}

/// The largest difference of nocdyn's tau for `robot` from the engine's for `engine_robot` over
/// the path, relative to the peak |tau|; also checks that the forces are not trivially small.
template <typename Engine>
double relativeDifference(const nocdyn::SpatialRobotDescription& robot,
                          const nocdyn::SpatialRobotDescription& engine_robot, double length, double angle,
                          double min_peak) {
    const Path path = twoHarmonics(robot, length, angle);
    Engine engine(engine_robot);
    const Eigen::MatrixXd reference = engine.actuatorForces(path.p, path.dp, path.ddp);

    const nocdyn::spatial::Model model(robot);
    nocdyn::spatial::Data data(model);
    EXPECT_EQ(reference.cols(), model.actuators);
    double peak = 0.0, diff = 0.0;
    for (int s = 0; s < kSamples; ++s) {
        const auto status = nocdyn::spatial::inverseDynamics(model, data, path.p[static_cast<std::size_t>(s)],
                                                             path.dp[static_cast<std::size_t>(s)],
                                                             path.ddp[static_cast<std::size_t>(s)]);
        EXPECT_TRUE(status.ok()) << nocdyn::spatial::describe(status, model);
        peak = std::max(peak, reference.row(s).cwiseAbs().maxCoeff());
        diff = std::max(diff, (data.tau.transpose() - reference.row(s)).cwiseAbs().maxCoeff());
    }
    EXPECT_GT(peak, min_peak);
    std::printf("%s: peak |tau| %.6g, max |tau_nocdyn - tau_engine| / peak %.3e\n", robot.name.c_str(), peak,
                diff / peak);
    return diff / peak;
}

/// A random physically possible inertia tensor: principal moments obeying the triangle
/// inequalities, turned by a random rotation.
inline Eigen::Matrix3d randomInertia(std::mt19937& rng, double scale) {
    std::uniform_real_distribution<double> u(0.2, 1.0);
    std::normal_distribution<double> n(0.0, 1.0);
    const double a = u(rng), b = u(rng);
    const Eigen::Vector3d moments = scale * Eigen::Vector3d(a, b, 0.5 * (a + b) + 0.4 * std::abs(a - b));
    const Eigen::Matrix3d R = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
    return R * moments.asDiagonal() * R.transpose();
}

/// A random hexapod: base points near a circle of radius 1, platform points on one of 0.6 about
/// a home pose with non-zero angles, each leg a UPS (its U's second axis 20 degrees off the
/// normal of the first, the actuated P along the leg) or an RUS (an actuated crank of 0.3 m
/// about a horizontal axis); random masses, c.o.m. and inertias, gravity tilted, damping and
/// friction on every actuated joint.
inline nocdyn::SpatialRobotDescription randomHexapod(std::mt19937& rng, bool rus) {
    using namespace nocdyn;
    constexpr double deg = std::numbers::pi / 180.0;
    std::uniform_real_distribution<double> jitter(-0.08, 0.08);
    std::uniform_real_distribution<double> mass(0.5, 5.0);
    SpatialRobotDescription d;
    d.name = rus ? "random-6rus" : "random-6ups";
    d.motion = PlatformMotion::full;
    d.gravity = {0.3, -0.2, -9.81};
    d.home << jitter(rng), jitter(rng), 1.0 + jitter(rng), jitter(rng), jitter(rng), jitter(rng);
    d.platform.mass = 20.0 + 10.0 * mass(rng);
    d.platform.com = {jitter(rng), jitter(rng), 0.05 + jitter(rng)};
    d.platform.inertia = randomInertia(rng, 5.0);
    const Eigen::Matrix3d R_home = spatial::rotation(d.home(3), d.home(4), d.home(5));
    for (int i = 0; i < 6; ++i) {
        const double base_angle = (120.0 * (i / 2) + (i % 2 == 0 ? -15.0 : 15.0)) * deg + jitter(rng);
        const double top_angle = (60.0 + 120.0 * ((i + 1) / 2 % 3) + (i % 2 == 0 ? 15.0 : -15.0)) * deg + jitter(rng);
        const Eigen::Vector3d b(std::cos(base_angle) * (1.0 + jitter(rng)), std::sin(base_angle) * (1.0 + jitter(rng)),
                                jitter(rng));
        const Eigen::Vector3d top =
            d.home.head<3>() + R_home * Eigen::Vector3d(0.6 * std::cos(top_angle), 0.6 * std::sin(top_angle), 0.0);
        SpatialLimbDescription limb;
        limb.name = "leg" + std::to_string(i + 1);
        SpatialJointDescription s;
        s.type = SpatialJointType::spherical;
        s.point = top;
        SpatialBodyDescription body1, body2;
        body1.mass = mass(rng);
        body2.mass = mass(rng);
        body1.inertia = randomInertia(rng, 0.05);
        body2.inertia = randomInertia(rng, 0.05);
        SpatialJointDescription actuator;
        actuator.actuated = true;
        actuator.damping = 10.0 * (1.0 + jitter(rng));
        actuator.friction = 5.0 * (1.0 + jitter(rng));
        if (!rus) {
            const Eigen::Vector3d e = (top - b).normalized();
            SpatialJointDescription u;
            u.type = SpatialJointType::universal;
            u.point = b;
            u.axis1 = e.cross(Eigen::Vector3d::UnitZ()).normalized();
            u.axis2 =
                (std::cos(20.0 * deg) * e.cross(u.axis1).normalized() + std::sin(20.0 * deg) * u.axis1).normalized();
            actuator.type = SpatialJointType::prismatic;
            actuator.direction = e;
            limb.joints = {u, actuator, s};
            body1.com = b + 0.3 * (top - b) + 0.02 * Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
            body2.com = b + 0.7 * (top - b) + 0.02 * Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
        } else {
            const Eigen::Vector3d radial(std::cos(base_angle), std::sin(base_angle), 0.0);
            const Eigen::Vector3d axis = Eigen::Vector3d::UnitZ().cross(radial).normalized();
            const Eigen::Vector3d elbow = b + 0.3 * (0.6 * radial + 0.8 * Eigen::Vector3d::UnitZ()).normalized();
            actuator.type = SpatialJointType::revolute;
            actuator.point = b;
            actuator.axis = axis;
            actuator.damping *= 0.1;
            actuator.friction *= 0.1;
            SpatialJointDescription u;
            u.type = SpatialJointType::universal;
            u.point = elbow;
            u.axis1 = axis;
            u.axis2 = (top - elbow).normalized().cross(axis).normalized();
            limb.joints = {actuator, u, s};
            body1.com = 0.5 * (b + elbow);
            body2.com = 0.5 * (elbow + top) + 0.01 * Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
        }
        limb.bodies = {body1, body2};
        d.limbs.push_back(limb);
    }
    return d;
}

/// A random 6-SPU: the random 6-UPS's legs with an S at the base (three R freedoms, a body
/// after them) and a U at the platform whose axes, a1 in the rod and a2 in the platform, both
/// across the leg, are 70 degrees apart.
inline nocdyn::SpatialRobotDescription randomSpu(std::mt19937& rng) {
    using namespace nocdyn;
    constexpr double deg = std::numbers::pi / 180.0;
    SpatialRobotDescription d = randomHexapod(rng, false);
    d.name = "random-6spu";
    for (SpatialLimbDescription& limb : d.limbs) {
        const Eigen::Vector3d b = limb.joints[0].point, top = limb.joints[2].point;
        const Eigen::Vector3d e = (top - b).normalized();
        limb.joints[0].type = SpatialJointType::spherical;
        SpatialJointDescription& u = limb.joints[2];
        u.type = SpatialJointType::universal;
        u.axis1 = e.cross(Eigen::Vector3d::UnitZ()).normalized();
        u.axis2 = std::cos(70.0 * deg) * u.axis1 + std::sin(70.0 * deg) * e.cross(u.axis1).normalized();
    }
    return d;
}

/// A random Delta: the shipped one's geometry (its parallelograms keep the platform's
/// orientation) with random masses, c.o.m. (within 2 cm of the file's) and inertias of every
/// body, the platform's mass scaled, gravity tilted, damping and friction on the actuated cranks.
inline nocdyn::SpatialRobotDescription randomDelta(std::mt19937& rng) {
    std::uniform_real_distribution<double> jitter(-0.02, 0.02), scale(0.5, 2.0);
    nocdyn::SpatialRobotDescription d = shipped("delta");
    d.name = "random-delta";
    d.gravity = {0.5, 0.3, -9.81};
    d.platform.mass *= scale(rng);
    d.platform.inertia = randomInertia(rng, 0.0005);
    for (nocdyn::SpatialLimbDescription& limb : d.limbs) {
        for (nocdyn::SpatialBodyDescription& body : limb.bodies) {
            body.mass *= scale(rng);
            body.com += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
            body.inertia = randomInertia(rng, 0.005);
        }
        limb.joints[0].damping = 0.05 * scale(rng);
        limb.joints[0].friction = 0.02 * scale(rng);
    }
    return d;
}

}  // namespace nocdyn_spatial_test
