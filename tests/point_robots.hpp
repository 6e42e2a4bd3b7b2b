// Random two-DOF planar robots (motion: translation): five-bars, biglides and three-armed
// (redundant) point robots, assembled at home by construction. Shared by the model and engine
// tests.
#pragma once

#include <array>
#include <cmath>
#include <random>
#include <string>

#include "nocdyn/description.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn::test {

/// A random two-DOF robot: 2 or 3 limbs of kind RRR or PRR (last joint R at the tool point).
inline RobotDescription randomPointRobot(std::mt19937& rng, int limbs, bool prismatic) {
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    const auto between = [&](double lo, double hi) { return lo + (hi - lo) * 0.5 * (U(rng) + 1.0); };
    RobotDescription d;
    d.name = prismatic ? "random biglide" : "random five-bar";
    d.motion = PlatformMotion::translation;
    const Vector2 C(0.03 * U(rng), 0.3 + 0.03 * U(rng));
    d.home = Vector3(0.0, C.x(), C.y());
    d.gravity = Vector2(5.0 * U(rng), 10.0 * U(rng));
    d.platform.mass = between(0.05, 0.6);
    for (int j = 0; j < limbs; ++j) {
        LimbDescription limb;
        limb.name = "limb" + std::to_string(j + 1);
        // the base joints spread along x below the tool, the elbows out
        const double base_x = limbs == 2 ? (j == 0 ? -0.1 : 0.1) : -0.12 + 0.12 * j;
        const Vector2 A(base_x + 0.02 * U(rng), 0.02 * U(rng));
        Vector2 B;
        if (prismatic) {
            const double angle = 0.3 * U(rng);  // the rail about x
            limb.joints[0].type = JointType::prismatic;
            limb.joints[0].direction = Vector2(std::cos(angle), std::sin(angle));
            B = A;
        } else {
            limb.joints[0].type = JointType::revolute;
            limb.joints[0].point = A;
            const double out =
                base_x < 0.0 ? between(1.9, 2.6) : (base_x > 0.0 ? between(0.5, 1.2) : between(1.3, 1.8));
            B = A + between(0.15, 0.25) * Vector2(std::cos(out), std::sin(out));
        }
        limb.joints[0].actuated = true;
        limb.joints[1].type = JointType::revolute;
        limb.joints[1].point = B;
        limb.joints[2].type = JointType::revolute;
        limb.joints[2].point = C;
        const Vector2 first_end = prismatic ? A + Vector2(0.03, 0.0) : B;
        const std::array<Vector2, 2> ends0{A, B};
        const std::array<Vector2, 2> ends1{first_end, C};
        for (std::size_t b = 0; b < 2; ++b) {
            limb.bodies[b].mass = between(0.05, 1.0);
            limb.bodies[b].inertia = between(1e-5, 3e-3);
            limb.bodies[b].com = 0.5 * (ends0[b] + ends1[b]) + Vector2(0.02 * U(rng), 0.02 * U(rng));
        }
        d.limbs.push_back(limb);
    }
    return d;
}

}  // namespace nocdyn::test
