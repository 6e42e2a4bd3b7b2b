// Inverse dynamics of the paper's trajectory 1 at t = 0.01 s through the installed package;
// exits non-zero unless tau_2 matches the golden value (-45.341191494377961 N).
#include <nocdyn/prr3/dynamics.hpp>
#include <nocdyn/trajectory.hpp>

#include <cmath>
#include <cstdio>

int main() {
    const nocdyn::prr3::Model model;
    nocdyn::prr3::Data data;
    nocdyn::Pose p, dp, ddp;
    nocdyn::paperTrajectory1().evaluate(0.01, p, dp, ddp);
    if (!nocdyn::prr3::inverseDynamics(model, data, p, dp, ddp)) return 2;
    std::printf("tau = %.12g %.12g %.12g N\n", data.tau(0), data.tau(1), data.tau(2));
    return std::abs(data.tau(1) - -45.341191494377961) < 1e-8 ? 0 : 1;
}
