// The one benchmark fixture: model, data and a cycle of precomputed samples, all built
// outside the timed loops.
//
// The samples are one period (0.1 s at 10 kHz = 1000 samples) of a multi-harmonic
// trajectory: the paper's trajectory 1 (eq. 33) plus a second harmonic on every axis, so
// that consecutive samples differ in pose, rate and acceleration and the cycle wraps around
// continuously (the engines that continue from the previous sample see no jump).
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"
#include "nocdyn/prr3/model.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::bench {

/// Period of the benchmark trajectory [s] and sampling rate of the cycle [Hz].
inline constexpr double kPeriod = 0.1;
inline constexpr double kRate = 10000.0;
inline constexpr std::size_t kCycle = 1000;  // kPeriod * kRate

/// Paper trajectory 1 plus a second harmonic per axis (10, 20 and 30 Hz: period 0.1 s).
inline PoseTrajectory benchmarkTrajectory() {
    constexpr double pi = std::numbers::pi;
    PoseTrajectory traj = paperTrajectory1();
    traj.name = "bench";
    traj.duration = kPeriod;
    traj.theta.harmonics.push_back({1.0 * pi / 180.0, 30.0, 0.3});
    traj.x.harmonics.push_back({0.0005, 20.0, 1.0});
    traj.y.harmonics.push_back({0.0008, 30.0, -0.5});
    return traj;
}

/// One pose-space sample and the joint-space results of nocdyn's per-sample path.
struct Sample {
    double t = 0.0;
    Pose p, dp, ddp;
    prr3::JointVector u, du, ddu, tau;
};

struct Fixture {
    prr3::Model model;
    prr3::Data data;
    PoseTrajectory trajectory = benchmarkTrajectory();
    std::vector<double> times;
    std::vector<Sample> samples;

    Fixture() {
        times.resize(kCycle);
        samples.resize(kCycle);
        for (std::size_t k = 0; k < kCycle; ++k) {
            Sample& s = samples[k];
            s.t = static_cast<double>(k) / kRate;
            times[k] = s.t;
            trajectory.evaluate(s.t, s.p, s.dp, s.ddp);
            const prr3::Status status = prr3::inverseDynamics(model, data, s.p, s.dp, s.ddp);
            if (!status || !prr3::checkStroke(model, data) || !prr3::checkForce(model, data)) {
                throw std::runtime_error("benchmark trajectory leaves the workspace at t = " + std::to_string(s.t));
            }
            s.u = data.u;
            s.du = data.du;
            s.ddu = data.ddu;
            s.tau = data.tau;
        }
    }
};

/// The process-wide fixture (built once, on first use, never inside a timed loop).
inline const Fixture& fixture() {
    static const Fixture f;
    return f;
}

/// A two-DOF robot's cycle (the five-bar, the biglide): the tool point about the robot's home
/// (theta held there), two harmonics per axis of 10, 20 and 30 Hz (period 0.1 s, kCycle
/// samples at kRate), amplitudes of 10-15 mm and 3-4 mm: the same cycle for nocdyn and the
/// engines.
struct ToolCycle {
    PoseTrajectory trajectory;
    std::vector<double> times;
    std::vector<Pose> p, dp, ddp;

    explicit ToolCycle(const Pose& home) {
        trajectory.name = "bench tool point";
        trajectory.duration = kPeriod;
        trajectory.theta.offset = home(0);
        trajectory.x = {home(1), {{0.015, 10.0, 0.0}, {0.004, 20.0, 1.0}}};
        trajectory.y = {home(2), {{0.010, 10.0, 0.7}, {0.003, 30.0, -0.5}}};
        times.resize(kCycle);
        p.resize(kCycle);
        dp.resize(kCycle);
        ddp.resize(kCycle);
        for (std::size_t k = 0; k < kCycle; ++k) {
            times[k] = static_cast<double>(k) / kRate;
            trajectory.evaluate(times[k], p[k], dp[k], ddp[k]);
        }
    }
};

}  // namespace nocdyn::bench
