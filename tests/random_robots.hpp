// Random planar parallel robots of every limb type and actuation choice, assembled at home by
// construction (product-of-exponentials description), and smooth trajectories around home.
// Shared by the model and engine tests.
#pragma once

#include <algorithm>

#include "nocdyn/detail/sanitizer.hpp"
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "nocdyn/description.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {

#if NOCDYN_ASAN()
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

/// How many random robots a sweep runs: all `n` in the release build, a third (at least one,
/// the same first robots of the same seeds) under AddressSanitizer, where each costs 10-20x
/// more. The release build checks every robot; the sanitizer build checks the same code paths
/// for memory and undefined-behaviour errors on a sample of them.
inline int sweepSize(int n) { return kSanitized ? std::max(1, n / 3) : n; }

inline const std::vector<std::string>& limbTypes() {
    static const std::vector<std::string> types{"RRR", "PRR", "RPR", "RRP", "PRP", "RPP", "PPR"};
    return types;
}

/// Options of a random robot.
struct RandomRobotSpec {
    std::vector<std::string> limb_types;  ///< one per limb
    int actuators = 3;                    ///< actuated joints, chosen at random among all
    bool gravity = false;
    bool friction = false;
    int actuated_joint = -1;  ///< when 0..2: that joint of every limb instead (actuators ignored)
};

/// A random robot of the given limb types: limbs spread around the base (anchors ~0.25 m from
/// O), platform anchors ~0.06 m from C, bodies of 0.1-2 kg. Returns nothing when the random
/// actuation choice is singular at home (the Model rejects it).
inline std::optional<RobotDescription> randomRobot(const RandomRobotSpec& spec, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0), mass(0.1, 2.0), inertia(1e-4, 1e-2);
    const auto rot = [](double a, const Eigen::Vector2d& v) {
        return Eigen::Vector2d(std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y());
    };
    // One draw a statement: the arguments of a call are evaluated in an unspecified order (GCC
    // takes the last first, clang the first), and the robots must not depend on the compiler.
    // The order is the one GCC 12 gave the former one-line forms (Vector2d(s u, s u): y before
    // x; home: y, x, theta), so that these are the robots the tests' tolerances were set on.
    const auto draw2 = [&](double scale) {
        const double y = scale * unit(rng);
        const double x = scale * unit(rng);
        return Eigen::Vector2d(x, y);
    };
    RobotDescription robot;
    robot.name = "random";
    const Eigen::Vector2d C0 = draw2(0.01);
    const double theta0 = 0.2 * unit(rng);
    robot.home = Eigen::Vector3d(theta0, C0.x(), C0.y());
    robot.platform = {mass(rng), inertia(rng), draw2(0.01), 0};  // a braced list: drawn in order
    if (spec.gravity) robot.gravity = Eigen::Vector2d(3.0 * unit(rng), -9.81);
    const int n = static_cast<int>(spec.limb_types.size());
    for (int j = 0; j < n; ++j) {
        const double phi = 2.0 * std::numbers::pi * j / n + 0.2 * unit(rng);
        const Eigen::Vector2d radial(std::cos(phi), std::sin(phi));
        const Eigen::Vector2d base = (0.25 + 0.03 * unit(rng)) * radial;
        const double turn = 0.3 * unit(rng);  // before the reach, as GCC 12 drew them
        const double reach = 0.06 + 0.01 * unit(rng);
        const Eigen::Vector2d anchor = C0 + rot(robot.home(0), reach * rot(turn, radial));
        // elbow off the base-anchor line so that no limb starts at the edge of its reach
        const double offset = 0.04 + 0.02 * unit(rng);
        const double side = unit(rng) > 0 ? 1.0 : -1.0;
        const Eigen::Vector2d mid = 0.5 * (base + anchor) + offset * side * Eigen::Vector2d(-radial.y(), radial.x());
        const std::array<Eigen::Vector2d, 3> points{base, mid, anchor};
        LimbDescription limb;
        limb.name = "limb" + std::to_string(j + 1);
        for (std::size_t k = 0; k < 3; ++k) {
            JointDescription& joint = limb.joints[k];
            joint.type =
                spec.limb_types[static_cast<std::size_t>(j)][k] == 'R' ? JointType::revolute : JointType::prismatic;
            joint.point = points[k];
            // a prismatic joint runs roughly along its segment of the chain, turned at random
            const Eigen::Vector2d along = k < 2 ? points[k + 1] - points[k] : points[k] - points[k - 1];
            joint.direction = rot(0.8 * unit(rng), along.normalized());
            if (spec.friction) {
                joint.damping = 2.0 * (unit(rng) + 1.0);
                joint.friction = 0.5 * (unit(rng) + 1.0);
            }
        }
        limb.bodies[0] = {mass(rng), inertia(rng), 0.5 * (base + mid) + draw2(0.01), 0, {}};
        limb.bodies[1] = {mass(rng), inertia(rng), 0.5 * (mid + anchor) + draw2(0.01), 0, {}};
        robot.limbs.push_back(limb);
    }
    // actuators: a random choice among all joints
    std::vector<int> all(static_cast<std::size_t>(3 * n));
    for (int i = 0; i < 3 * n; ++i) all[static_cast<std::size_t>(i)] = i;
    std::shuffle(all.begin(), all.end(), rng);
    for (int a = 0; a < spec.actuators && a < 3 * n && spec.actuated_joint < 0; ++a) {
        const int i = all[static_cast<std::size_t>(a)];
        robot.limbs[static_cast<std::size_t>(i / 3)].joints[static_cast<std::size_t>(i % 3)].actuated = true;
    }
    if (spec.actuated_joint >= 0) {
        for (LimbDescription& limb : robot.limbs)
            limb.joints[static_cast<std::size_t>(spec.actuated_joint)].actuated = true;
    }
    try {
        RobotDescription copy = robot;
        copy.max_condition = 1e3;  // reject robots that are nearly singular at home
        const Model model(copy);
    } catch (const Error&) {
        return std::nullopt;
    }
    return robot;
}

/// A smooth trajectory around `home`: two harmonics per axis, a few degrees and millimetres,
/// 2-12 Hz.
inline PoseTrajectory trajectoryAround(const Eigen::Vector3d& home, std::mt19937& rng, double scale = 1.0) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0), frequency(2.0, 12.0);
    PoseTrajectory trajectory;
    trajectory.name = "random";
    AxisMotion* axes[3] = {&trajectory.theta, &trajectory.x, &trajectory.y};
    const double amplitude[3] = {0.05 * scale, 0.004 * scale, 0.004 * scale};
    for (int i = 0; i < 3; ++i) {
        axes[i]->offset = home(i);
        for (int h = 0; h < 2; ++h) {
            axes[i]->harmonics.push_back({amplitude[i] * unit(rng), frequency(rng), std::numbers::pi * unit(rng)});
        }
    }
    return trajectory;
}

}  // namespace nocdyn::test
