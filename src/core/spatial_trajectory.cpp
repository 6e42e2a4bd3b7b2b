// A spatial robot's pose trajectory (spatial_trajectory.hpp): the planar axes' motions, one per
// coordinate.
#include "nocdyn/spatial_trajectory.hpp"

#include <algorithm>
#include <cmath>

namespace nocdyn::spatial {

void Trajectory::evaluate(double t, TaskVector& p, TaskVector& dp, TaskVector& ddp) const {
    p.resize(dimension);
    dp.resize(dimension);
    ddp.resize(dimension);
    for (int i = 0; i < dimension; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (sampled[k]) {
            sampled[k]->evaluate(t, p(i), dp(i), ddp(i));
        } else {
            axis[k].evaluate(t, p(i), dp(i), ddp(i));
        }
    }
}

double Trajectory::highestFrequency() const {
    double highest = 0.0;
    for (int i = 0; i < dimension; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (sampled[k]) continue;
        for (const Harmonic& h : axis[k].harmonics) {
            if (h.amplitude != 0.0) highest = std::max(highest, std::abs(h.frequency));
        }
    }
    return highest;
}

std::size_t Trajectory::harmonics() const {
    std::size_t count = 0;
    for (int i = 0; i < dimension; ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (!sampled[k]) count += axis[k].harmonics.size();
    }
    return count;
}

}  // namespace nocdyn::spatial
