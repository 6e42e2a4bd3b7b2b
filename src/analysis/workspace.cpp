// Workspace map at a fixed orientation: every grid point through the position and velocity
// stages (kinematics.hpp), each limb's reach by its closed form (limb_ik.hpp), the singularity
// curves refined by bisection along the grid edges that cross them.
#include "nocdyn/analysis/workspace.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/limb_ik.hpp"

namespace nocdyn {

namespace {

/// Bisection passes on a grid edge (2^-40 of a step: far below the figure's resolution).
constexpr int kRefinements = 40;
constexpr int kCoarse = 101;

/// One point of the plane at the map's orientation.
class Probe {
public:
    Probe(const Model& model, double theta) : model_(model), data_(model), theta_(theta) {
        G_.dtheta = theta - model.home(0);
        G_.cos_dtheta = std::cos(G_.dtheta);
        G_.sin_dtheta = std::sin(G_.dtheta);
    }

    /// Whether limb j alone reaches C = (x, y) on its home branch.
    bool reaches(int j, double x, double y) {
        G_.C = Vector2(x, y);
        LimbData& ld = data_.limb[static_cast<std::size_t>(j)];
        return solveLimb(model_.limb[static_cast<std::size_t>(j)], j, G_, false, ld).ok();
    }

    /// The cell of (x, y); `actuation`: det A with three actuators, else +1 / -1 for a
    /// condition number of A within / beyond the limit; NaN where A is not defined (a limb out
    /// of reach or singular).
    WorkspaceCell classify(double x, double y, double& actuation) {
        actuation = std::nan("");
        condition_ = std::nan("");
        const Pose p(theta_, x, y);
        if (const Status s = inverseDisplacement(model_, data_, p); !s) {
            return s.code == StatusCode::singular_limb ? WorkspaceCell::singular : WorkspaceCell::unreachable;
        }
        const Status v = velocityFromPlatformTwist(model_, data_, Twist::Zero());
        if (v.ok() || v.code == StatusCode::singular_actuation) {
            if (model_.coordinates == Coordinates::actuators) {
                actuation = Matrix3(data_.A.topRows<3>()).determinant();
            } else if (model_.task_dimension == 2 && model_.actuators == 2) {
                // det A_t, A_t = A S(c) E: the x, y columns of A
                actuation = data_.A(0, 1) * data_.A(1, 2) - data_.A(0, 2) * data_.A(1, 1);
            } else {
                actuation = v.ok() ? 1.0 : -1.0;
            }
        }
        if (!v) return WorkspaceCell::singular;
        if (!checkJointLimits(model_, data_)) return WorkspaceCell::range;
        condition_ = data_.cond_A;
        return WorkspaceCell::feasible;
    }

    /// The scaled condition number of A at the last point classified feasible, else NaN.
    [[nodiscard]] double condition() const { return condition_; }

    double actuation(double x, double y) {
        double value = 0.0;
        (void)classify(x, y, value);
        return value;
    }

private:
    const Model& model_;
    Data data_;
    double theta_;
    double condition_ = 0.0;
    PlatformDisplacement G_;
};

/// A point where `inside(t)` changes along a -> b (inside(0) != inside(1)), by bisection.
template <class Inside>
Vector2 crossing(const Vector2& a, const Vector2& b, Inside inside) {
    double lo = 0.0, hi = 1.0;
    const bool at_lo = inside(a);
    for (int pass = 0; pass < kRefinements; ++pass) {
        const double mid = 0.5 * (lo + hi);
        (inside(a + mid * (b - a)) == at_lo ? lo : hi) = mid;
    }
    return a + 0.5 * (lo + hi) * (b - a);
}

/// Half the side of a box about C_home that holds every limb's reach [m].
double coarseHalfWidth(const Model& model) {
    double reach = model.length_scale;
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        double extent = limb.length1 + limb.length2;
        for (std::size_t k = 0; k < 3; ++k) {
            if (limb.type[k] != JointType::prismatic) continue;
            const JointLimits& lim = limb.limits[k];
            const double range = std::max(std::abs(lim.lower), std::abs(lim.upper));
            extent += std::isfinite(range) ? range : model.length_scale;
        }
        reach = std::max(reach, extent);
    }
    return 1.5 * reach;
}

}  // namespace

Dexterity dexterity(const WorkspaceMap& map) {
    std::vector<double> values;
    values.reserve(map.condition.size());
    for (const double c : map.condition) {
        if (!std::isnan(c)) values.push_back(c);
    }
    if (values.empty()) return {std::nan(""), std::nan("")};
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return {*middle, *std::max_element(values.begin(), values.end())};
}

WorkspaceMap workspaceMap(const Model& model, const WorkspaceOptions& options) {
    if (!std::isfinite(options.theta) || std::abs(options.theta) > 1e3) {
        throw Error("workspace: theta must be a finite angle in [-1000, 1000] rad");
    }
    if (options.resolution < 11 || options.resolution > 2001) {
        throw Error("workspace: the resolution must be in [11, 2001] points per side, got " +
                    std::to_string(options.resolution));
    }
    Probe probe(model, options.theta);
    double actuation = 0.0;

    // coarse pass: the feasible region's bounding box
    const Vector2 centre = model.home.tail<2>();
    const double half = coarseHalfWidth(model);
    const double coarse_step = 2.0 * half / (kCoarse - 1);
    Vector2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (int i = 0; i < kCoarse; ++i) {
        for (int k = 0; k < kCoarse; ++k) {
            const Vector2 c = centre + Vector2(-half + i * coarse_step, -half + k * coarse_step);
            if (probe.classify(c.x(), c.y(), actuation) != WorkspaceCell::feasible) continue;
            lo = lo.cwiseMin(c);
            hi = hi.cwiseMax(c);
        }
    }
    if (!(lo.x() <= hi.x())) {
        throw Error("workspace: no position of C is feasible at theta = " + std::to_string(options.theta) +
                    " rad within " + std::to_string(half) + " m of the home position");
    }
    // fine pass: a square about the box, a tenth (and at least two coarse steps) wider
    const double side = std::max((hi - lo).maxCoeff() * 1.2, (hi - lo).maxCoeff() + 4.0 * coarse_step);
    const Vector2 middle = 0.5 * (lo + hi);
    WorkspaceMap map;
    map.theta = options.theta;
    map.task_dimension = model.task_dimension;
    map.n = options.resolution;
    map.step = side / (map.n - 1);
    map.x0 = middle.x() - 0.5 * side;
    map.y0 = middle.y() - 0.5 * side;
    const auto at = [&](int i, int k) { return Vector2(map.x0 + i * map.step, map.y0 + k * map.step); };
    const auto count = static_cast<std::size_t>(map.n) * static_cast<std::size_t>(map.n);
    map.cells.resize(count);
    map.condition.assign(count, std::nan(""));
    std::vector<double> act(count);
    std::vector<std::uint8_t> reach(count);  // bit j: limb j reaches
    for (int i = 0; i < map.n; ++i) {
        for (int k = 0; k < map.n; ++k) {
            const auto index =
                static_cast<std::size_t>(i) * static_cast<std::size_t>(map.n) + static_cast<std::size_t>(k);
            const Vector2 c = at(i, k);
            map.cells[index] = probe.classify(c.x(), c.y(), act[index]);
            if (map.cells[index] == WorkspaceCell::feasible) {
                map.area += map.step * map.step;
                map.condition[index] = probe.condition();
            }
            if (!options.curves) continue;
            for (int j = 0; j < model.limbs; ++j) {
                if (probe.reaches(j, c.x(), c.y())) reach[index] |= static_cast<std::uint8_t>(1u << j);
            }
        }
        if (options.progress) options.progress(i + 1, 2 * map.n);
    }

    // the curves, on every grid edge that crosses one
    for (int i = 0; i < (options.curves ? map.n : 0); ++i) {
        for (int k = 0; k < map.n; ++k) {
            const auto a_index =
                static_cast<std::size_t>(i) * static_cast<std::size_t>(map.n) + static_cast<std::size_t>(k);
            for (const auto& [di, dk] : {std::pair{1, 0}, std::pair{0, 1}}) {
                if (i + di >= map.n || k + dk >= map.n) continue;
                const auto b_index = a_index + static_cast<std::size_t>(di * map.n + dk);
                const Vector2 a = at(i, k), b = at(i + di, k + dk);
                const std::uint8_t changed = reach[a_index] ^ reach[b_index];
                for (int j = 0; j < model.limbs; ++j) {
                    if ((changed >> j) & 1u) {
                        map.limb_singular.push_back(
                            crossing(a, b, [&](const Vector2& c) { return probe.reaches(j, c.x(), c.y()); }));
                    }
                }
                const double fa = act[a_index], fb = act[b_index];
                if (std::isfinite(fa) && std::isfinite(fb) && (fa > 0.0) != (fb > 0.0)) {
                    map.actuation_singular.push_back(
                        crossing(a, b, [&](const Vector2& c) { return probe.actuation(c.x(), c.y()) > 0.0; }));
                }
            }
        }
        if (options.progress) options.progress(map.n + i + 1, 2 * map.n);
    }
    return map;
}

}  // namespace nocdyn
