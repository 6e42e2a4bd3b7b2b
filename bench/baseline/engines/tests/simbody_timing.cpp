// Rough timing of SimbodyRobot::inverseDynamics per sample (for reports; not a test).
#include <chrono>
#include <ctime>
#include <cstdio>
#include <vector>

#include "nocdyn/prr3/simbody_robot.hpp"

int main() {
    nocdyn::prr3::SimbodyRobot robot{nocdyn::io::RobotParameters{}};
    const auto trajectory = nocdyn::paperTrajectory1();
    const int n = 2000;
    std::vector<double> times(n);
    for (int i = 0; i < n; ++i) times[static_cast<std::size_t>(i)] = 0.2 * i / n;  // 10 kHz
    (void)robot.inverseDynamics(trajectory, {0.0});                                // warm-up
    for (int rep = 0; rep < 3; ++rep) {
        const std::clock_t c0 = std::clock();
        const auto t0 = std::chrono::steady_clock::now();
        const auto s = robot.inverseDynamics(trajectory, times);
        const auto t1 = std::chrono::steady_clock::now();
        const std::clock_t c1 = std::clock();
        const double us = std::chrono::duration<double, std::micro>(t1 - t0).count() / n;
        const double cpu_us = 1e6 * static_cast<double>(c1 - c0) / CLOCKS_PER_SEC / n;
        std::printf("inverseDynamics: %d samples, %.1f us wall, %.1f us CPU per sample\n", n, us, cpu_us);
    }
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 200; ++i) (void)robot.jointSpaceInertia(Eigen::Vector3d(0.01 * (i % 5), 0.001, 0.0));
    const auto t1 = std::chrono::steady_clock::now();
    std::printf("jointSpaceInertia: %.1f us per call\n",
                std::chrono::duration<double, std::micro>(t1 - t0).count() / 200);
    return 0;
}
