// A spatial robot's pose trajectory with exact derivatives (spatial.hpp's pose order): each
// coordinate of p = [x, y, z, roll, pitch, yaw] (or [x, y, z] for motion translation) is an
// AxisMotion, offset + sum_k a_k sin(2 pi f_k t + phase_k), or a SampledAxis, a piecewise
// quintic through samples (trajectory.hpp); dp and ddp are the axes' exact time derivatives
// (Euler-angle rates, as spatial::inverseDynamics takes them).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "nocdyn/spatial.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::spatial {

/// The pose coordinates' names in pose order; a translation robot's are the first three.
inline constexpr std::array<const char*, 6> kCoordinateNames = {"x", "y", "z", "roll", "pitch", "yaw"};

/// p(t) for a spatial robot: dimension axes, each harmonic or sampled.
struct Trajectory {
    std::string name;
    int dimension = 6;               ///< 6 (motion full) or 3 (motion translation)
    std::array<AxisMotion, 6> axis;  ///< [m or rad], pose order; those past dimension unused
    std::optional<double> duration;  ///< [s], when the description gives one
    /// Per axis, when set, the samples' spline that replaces axis[i] (shared: copies stay cheap).
    std::array<std::shared_ptr<const SampledAxis>, 6> sampled{};

    /// p, dp/dt and d2p/dt2 at t, each resized to `dimension` (within TaskVector's fixed
    /// capacity: allocation-free).
    void evaluate(double t, TaskVector& p, TaskVector& dp, TaskVector& ddp) const;
    /// The highest frequency of any harmonic axis with a non-zero amplitude [Hz]; 0 when none.
    [[nodiscard]] double highestFrequency() const;
    /// Harmonic terms in all the harmonic axes.
    [[nodiscard]] std::size_t harmonics() const;
};

}  // namespace nocdyn::spatial
