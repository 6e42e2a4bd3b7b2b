// Inverse dynamics of the paper's trajectory 1 at t = 0.01 s through the installed package, by
// the general model of a robot described in code: the paper's 3-PRR prototype (eqs. 8, 32,
// 35-41, Table I). Exits non-zero unless tau_2 matches the golden value (-45.341191494377961 N).
#include <nocdyn/description.hpp>
#include <nocdyn/dynamics.hpp>
#include <nocdyn/model.hpp>
#include <nocdyn/trajectory.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

int main() {
    constexpr double pi = std::numbers::pi;
    const double R = 0.400 / std::sqrt(3.0), r = 0.110 / std::sqrt(3.0);  // circumradii of b and a (eq. 32)
    const double l = 0.15915, l_c = 0.079575;                             // link length and c.o.m. [m]
    // reference posture (theta = 0, C = O): M_j is (R - r) / 2 inside rail L_j (eqs. 37-39)
    const double sin_A = 0.5 * (R - r) / l, cos_A = std::sqrt(1.0 - sin_A * sin_A);
    nocdyn::RobotDescription robot;
    robot.name = "paper-3prr";
    robot.platform = {1.75257, 6.17311382e-3, Eigen::Vector2d::Zero(), 0};
    for (int j = 0; j < 3; ++j) {
        const double phi = (j == 0 ? 0.0 : (j == 1 ? 2.0 : -2.0)) * pi / 3.0;  // eq. 8
        const Eigen::Vector2d e(std::cos(phi), std::sin(phi)), n(-e.y(), e.x());
        const Eigen::Vector2d M = r * Eigen::Vector2d(std::cos(phi - pi / 6), std::sin(phi - pi / 6));  // eq. 41
        const Eigen::Vector2d m = l * (cos_A * e + sin_A * n);                                          // eq. 40
        const Eigen::Vector2d A = M - m;
        nocdyn::LimbDescription limb;
        limb.name = "limb" + std::to_string(j + 1);
        limb.joints[0].type = nocdyn::JointType::prismatic;  // the actuated slider on rail L_j
        limb.joints[0].direction = e;
        limb.joints[0].point = A;
        limb.joints[0].actuated = true;
        limb.joints[1].type = nocdyn::JointType::revolute;  // at A_j
        limb.joints[1].point = A;
        limb.joints[2].type = nocdyn::JointType::revolute;  // at M_j
        limb.joints[2].point = M;
        limb.bodies[0] = {1.46966, 0.0, A, 0, {}};                           // slider (Table I)
        limb.bodies[1] = {0.63863, 1.5786066e-3, A + (l_c / l) * m, 0, {}};  // link
        robot.limbs.push_back(limb);
    }
    const nocdyn::Model model(robot);
    nocdyn::Data data(model);
    nocdyn::Pose p, dp, ddp;
    nocdyn::paperTrajectory1().evaluate(0.01, p, dp, ddp);
    if (!nocdyn::inverseDynamics(model, data, p, dp, ddp)) return 2;
    std::printf("tau = %.12g %.12g %.12g N\n", data.tau(0), data.tau(1), data.tau(2));
    return std::abs(data.tau(1) - -45.341191494377961) < 1e-8 ? 0 : 1;
}
