// Helpers of the tests of the frozen 3-PRR kernel (nocdyn::prr3, the speed baseline): random
// poses across its workspace, the whole per-sample path, and the forward singularity where the
// link lines meet at C. The robot-independent helpers (tolerances, describePose) are
// tests/support.hpp's.
#pragma once

#include <gtest/gtest.h>

#include <random>

#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"
#include "support.hpp"

namespace nocdyn::test {

/// Random poses spread across the reachable workspace of a 3-PRR `model` (rotation up to
/// +-0.35 rad, centre within +-60 mm), with H and D conditioned better than 1e3; deterministic
/// per seed.
class BaselineSampler {
public:
    explicit BaselineSampler(const prr3::Model& model, unsigned seed = 2024) : model_(model), rng_(seed) {}

    /// Next pose accepted by the position and velocity stages.
    Pose next() {
        std::uniform_real_distribution<double> angle(-0.35, 0.35), position(-0.06, 0.06);
        prr3::Data data;
        for (;;) {
            const Pose p(angle(rng_), position(rng_), position(rng_));
            if (!prr3::inverseDisplacement(model_, data, p)) continue;
            if (!prr3::velocityFromPlatformTwist(model_, data, Twist::Zero())) continue;
            if (data.cond_H > 1e3 || data.cond_D > 1e3) continue;
            return p;
        }
    }

    /// A random platform twist: up to +-5 rad/s and +-1 m/s.
    Twist twist() {
        std::uniform_real_distribution<double> w(-5.0, 5.0), v(-1.0, 1.0);
        return {w(rng_), v(rng_), v(rng_)};
    }

    std::mt19937& rng() { return rng_; }

private:
    const prr3::Model& model_;
    std::mt19937 rng_;
};

/// Runs the baseline's whole per-sample path; fails the test (with the pose) when it does not
/// succeed.
inline void solve(const prr3::Model& model, prr3::Data& data, const Pose& p, const Twist& dp, const Twist& ddp) {
    const prr3::Status status = prr3::inverseDynamics(model, data, p, dp, ddp);
    ASSERT_TRUE(status.ok()) << describePose(p) << ": " << describe(status, model.parameters);
}

/// The platform rotation about O (C = O) at which the three link lines meet at C, so that
/// h_j1 = 0 (eq. 7) and H is singular: near theta = -2.08 rad for the paper's robot, where
/// phi_Mj = pi/6. Found by bisection on h_11 with a model that accepts any conditioning.
inline double baselineConcurrentLinkLinesRotation() {
    io::RobotParameters permissive;
    permissive.max_condition = 1e300;
    const prr3::Model probe(permissive);
    prr3::Data data;
    auto h11 = [&](double theta) {
        EXPECT_TRUE(prr3::inverseDisplacement(probe, data, Pose(theta, 0.0, 0.0)).ok());
        (void)prr3::velocityFromPlatformTwist(probe, data, Twist::Zero());
        return data.H(0, 0);
    };
    double lo = -2.6, hi = -1.5;
    EXPECT_LT(h11(lo) * h11(hi), 0.0);
    for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
        const double mid = 0.5 * (lo + hi);
        (h11(lo) * h11(mid) <= 0.0 ? hi : lo) = mid;
    }
    return lo;
}

}  // namespace nocdyn::test
