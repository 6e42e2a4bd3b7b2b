// Exact identification data for the tests: samples of a robot's motion with the forces its
// inverse dynamics (eq. 20) gives, so that identification must recover the parameters exactly.
#pragma once

#include <gtest/gtest.h>

#include <random>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/identification.hpp"
#include "random_robots.hpp"

namespace nocdyn::test {

/// Samples of `robot` along `trajectory` at t = k dt, k < samples, tau by inverse dynamics;
/// samples the robot cannot reach are left out.
inline Motion exactMotion(const Model& robot, const PoseTrajectory& trajectory, int samples, double dt) {
    Motion motion;
    Data data(robot);
    motion.tau.resize(samples, robot.actuators);
    int k = 0;
    for (int s = 0; s < samples; ++s) {
        Pose p, dp, ddp;
        trajectory.evaluate(dt * s, p, dp, ddp);
        if (!inverseDynamics(robot, data, p, dp, ddp)) continue;
        motion.t.push_back(dt * s);
        motion.p.push_back(p);
        motion.dp.push_back(dp);
        motion.ddp.push_back(ddp);
        motion.tau.row(k++) = data.tau.transpose();
    }
    motion.tau.conservativeResize(k, robot.actuators);
    return motion;
}

/// The exact log (u, du, ddu, tau) of `robot` at 250 Hz along a random motion about its home
/// (trajectoryAround, seeded): what an ideal logger would record.
inline Measurements exactLog(const Model& robot, unsigned seed, int samples) {
    std::mt19937 rng(seed);
    const PoseTrajectory trajectory = trajectoryAround(robot.home, rng);
    Data data(robot);
    Measurements m;
    m.u.resize(samples, robot.actuators);
    m.du.resize(samples, robot.actuators);
    m.ddu.resize(samples, robot.actuators);
    m.tau.resize(samples, robot.actuators);
    for (int k = 0; k < samples; ++k) {
        Pose p, dp, ddp;
        trajectory.evaluate(0.004 * k, p, dp, ddp);
        EXPECT_TRUE(inverseDynamics(robot, data, p, dp, ddp).ok());
        m.t.push_back(0.004 * k);
        m.u.row(k) = data.u.transpose();
        m.du.row(k) = data.du.transpose();
        m.ddu.row(k) = data.ddu.transpose();
        m.tau.row(k) = data.tau.transpose();
    }
    return m;
}

}  // namespace nocdyn::test
