// Pose trajectories with exact derivatives: harmonic (the paper's eqs. 33-34 and users' own)
// or sampled (recorded motion).
//
// Harmonic: each axis q in {theta, x, y} follows q(t) = offset + sum_k a_k sin(2 pi f_k t + phase_k).
// Sampled: each axis is a piecewise quintic in t (SampledAxis) built from samples either of the
// position (a not-a-knot cubic spline, C2, exact on cubics) or of the acceleration (a
// not-a-knot cubic spline of the acceleration integrated exactly twice from zero velocity and
// displacement, so that q, dq/dt and d2q/dt2 are consistent to rounding).
#pragma once

#include <array>
#include <memory>
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

/// One axis given by samples: on [t_i, t_{i+1}] q(t) = sum_k c_ik s^k, s = t - t_i, k = 0..5.
/// Before t_0 and after t_last the axis holds its end value with zero rate and acceleration.
struct SampledAxis {
    std::vector<double> times;                  ///< knots t_0 < t_1 < ... [s]
    std::vector<std::array<double, 6>> pieces;  ///< one polynomial per interval

    /// Value, first and second time derivative at t. Allocation-free (binary search).
    void evaluate(double t, double& q, double& dq, double& ddq) const;
};

/// Positions q_i at strictly increasing t_i (at least 2 samples) interpolated by the
/// not-a-knot cubic spline (C2; reproduces any cubic exactly; 2 samples: a line, 3: a parabola).
/// Throws nocdyn::Error for non-increasing times, fewer than 2 samples or non-finite values.
[[nodiscard]] SampledAxis splineOfPositions(const std::vector<double>& t, const std::vector<double>& q);

/// Accelerations a_i at strictly increasing t_i: the not-a-knot cubic spline of a(t), integrated
/// exactly to the velocity and the displacement from v(t_0) = v0 and q(t_0) = q0.
[[nodiscard]] SampledAxis splineOfAccelerations(const std::vector<double>& t, const std::vector<double>& a,
                                                double v0 = 0.0, double q0 = 0.0);

/// The three axes of a sampled pose trajectory; an axis without samples is harmonic (the
/// PoseTrajectory's AxisMotion, usually zero).
struct SampledPose {
    std::optional<SampledAxis> theta, x, y;
};

/// A platform pose trajectory p(t) = [theta(t), x(t), y(t)].
struct PoseTrajectory {
    std::string name;
    AxisMotion theta;                ///< [rad]
    AxisMotion x;                    ///< [m]
    AxisMotion y;                    ///< [m]
    std::optional<double> duration;  ///< [s], when the description gives one
    /// When set, its sampled axes replace the harmonic ones (shared: copies stay cheap).
    std::shared_ptr<const SampledPose> sampled = nullptr;

    /// p, dp/dt and d2p/dt2 at time t (pose order [theta, x, y], eq. 1). Allocation-free.
    void evaluate(double t, Pose& p, Pose& dp, Pose& ddp) const;
};

/// Trajectory 1 of the paper (eq. 33) in SI units.
[[nodiscard]] PoseTrajectory paperTrajectory1();
/// Trajectory 2 of the paper (eq. 34) in SI units.
[[nodiscard]] PoseTrajectory paperTrajectory2();

}  // namespace nocdyn
