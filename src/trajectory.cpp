// Harmonic pose trajectories (see trajectory.hpp); eqs. 33-34 of the paper.
#include "nocdyn/trajectory.hpp"

#include <cmath>
#include <numbers>

namespace nocdyn {

void AxisMotion::evaluate(double t, double& q, double& dq, double& ddq) const {
    q = offset;
    dq = 0.0;
    ddq = 0.0;
    for (const Harmonic& h : harmonics) {
        const double w = 2.0 * std::numbers::pi * h.frequency;
        const double s = std::sin(w * t + h.phase);
        const double c = std::cos(w * t + h.phase);
        q += h.amplitude * s;
        dq += h.amplitude * w * c;
        ddq -= h.amplitude * w * w * s;
    }
}

void PoseTrajectory::evaluate(double t, Pose& p, Pose& dp, Pose& ddp) const {
    theta.evaluate(t, p(0), dp(0), ddp(0));
    x.evaluate(t, p(1), dp(1), ddp(1));
    y.evaluate(t, p(2), dp(2), ddp(2));
}

namespace {

PoseTrajectory paperTranslation(const char* name) {
    constexpr double pi = std::numbers::pi;
    PoseTrajectory traj;
    traj.name = name;
    traj.duration = 0.2;
    // eqs. 33-34: x = -2 sin(20 pi t + pi/6) + 1 mm, y = 4 sin(20 pi t - pi/6) + 2 mm
    traj.x = {0.001, {{-0.002, 10.0, pi / 6.0}}};
    traj.y = {0.002, {{0.004, 10.0, -pi / 6.0}}};
    return traj;
}

}  // namespace

PoseTrajectory paperTrajectory1() {
    PoseTrajectory traj = paperTranslation("paper1");
    // eq. 33: theta_1 = (3/180) pi sin(20 pi t)
    traj.theta = {0.0, {{3.0 * std::numbers::pi / 180.0, 10.0, 0.0}}};
    return traj;
}

PoseTrajectory paperTrajectory2() {
    PoseTrajectory traj = paperTranslation("paper2");
    // eq. 34: theta_2 = (3/180) pi sin(10 pi t)
    traj.theta = {0.0, {{3.0 * std::numbers::pi / 180.0, 5.0, 0.0}}};
    return traj;
}

}  // namespace nocdyn
