// Harmonic pose trajectories with exact derivatives (the paper's eqs. 33-34 and users' own).
//
// Each axis q in {theta, x, y} follows q(t) = offset + sum_k a_k sin(2 pi f_k t + phase_k).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "nocdyn/planar.hpp"

namespace nocdyn {

/// One term a sin(2 pi f t + phase).
struct Harmonic {
    double amplitude = 0.0;  ///< a [m or rad]
    double frequency = 0.0;  ///< f [Hz]
    double phase = 0.0;      ///< [rad]
};

/// Motion of one pose coordinate: offset plus any number of harmonics.
struct AxisMotion {
    double offset = 0.0;
    std::vector<Harmonic> harmonics;

    /// Value, first and second time derivative at time t. Allocation-free.
    void evaluate(double t, double& q, double& dq, double& ddq) const;
};

/// A platform pose trajectory p(t) = [theta(t), x(t), y(t)].
struct PoseTrajectory {
    std::string name;
    AxisMotion theta;                ///< [rad]
    AxisMotion x;                    ///< [m]
    AxisMotion y;                    ///< [m]
    std::optional<double> duration;  ///< [s], when the description gives one

    /// p, dp/dt and d2p/dt2 at time t (pose order [theta, x, y], eq. 1). Allocation-free.
    void evaluate(double t, Pose& p, Pose& dp, Pose& ddp) const;
};

/// Trajectory 1 of the paper (eq. 33) in SI units.
[[nodiscard]] PoseTrajectory paperTrajectory1();
/// Trajectory 2 of the paper (eq. 34) in SI units.
[[nodiscard]] PoseTrajectory paperTrajectory2();

}  // namespace nocdyn
