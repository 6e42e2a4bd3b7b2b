// Forces for the forward-dynamics benchmarks (BM_Simulate/<robot>/...): the inverse-dynamics
// forces of one period of the benchmark trajectory (fixture.hpp), held over each 1 ms control
// period as a DAC would, and the state the motion starts from; built outside the timed loops.
#pragma once

#include <string>
#include <vector>

#include "fixture.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/examples.hpp"

namespace nocdyn::bench {

/// Control period over which each force is held [s], and the number of periods simulated.
inline constexpr double kHoldPeriod = 1e-3;
inline constexpr int kHoldPeriods = 100;  // kPeriod / kHoldPeriod

struct SimulateFixture {
    RobotDescription robot;
    Pose p0, dp0;
    std::vector<ActuatorVector> tau;  ///< held over [k, k + 1) kHoldPeriod

    explicit SimulateFixture(const std::string& name) : robot(io::exampleRobot(name)) {
        const Model model(robot);
        Data data(model);
        const PoseTrajectory trajectory = benchmarkTrajectory();
        Pose ddp;
        trajectory.evaluate(0.0, p0, dp0, ddp);
        for (int k = 0; k < kHoldPeriods; ++k) {
            Pose p, dp;
            trajectory.evaluate(k * kHoldPeriod, p, dp, ddp);
            if (!inverseDynamics(model, data, p, dp, ddp)) throw std::runtime_error("benchmark trajectory: singular");
            tau.push_back(data.tau);
        }
    }
};

}  // namespace nocdyn::bench
