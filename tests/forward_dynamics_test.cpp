// Forward dynamics of the paper's 3-PRR, on the general model its short form expands to:
// integrated with the inverse-dynamics forces (linear between 10 kHz samples, as `reproduce`
// drives it) it returns to the paper's trajectories, with an error second order in the force
// sampling interval; pushed past the workspace it stops naming the limb; impossible tolerances
// end with an error instead of crawling. (Inversion of the inverse dynamics, energy
// conservation, friction's dissipation and allocation: forward_dynamics_robots_test.)
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nocdyn/io/short_form.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

/// Simulates `trajectory` for `duration` with its inverse-dynamics forces sampled at `rate`
/// and interpolated linearly; max_k |u(t_k) - u_d(t_k)| [m] and |p(t_k) - p_d(t_k)|.
struct RoundTrip {
    double u_error = 0.0;
    double pose_error = 0.0;
};
RoundTrip roundTrip(const Model& model, const PoseTrajectory& trajectory, double duration, double rate) {
    const int n = static_cast<int>(std::lround(duration * rate));
    Data data(model);
    std::vector<double> times;
    std::vector<ActuatorVector> tau, u;
    std::vector<Pose> poses;
    Pose p, dp, ddp;
    for (int k = 0; k <= n; ++k) {
        times.push_back(k / rate);
        trajectory.evaluate(times.back(), p, dp, ddp);
        EXPECT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
        tau.push_back(data.tau);
        u.push_back(data.u);
        poses.push_back(p);
    }
    trajectory.evaluate(0.0, p, dp, ddp);
    Simulator simulator(model);
    EXPECT_TRUE(simulator.reset(p, dp).ok());
    simulator.setForces(ForceSignal(times, tau, Interpolation::linear));
    RoundTrip result;
    for (int k = 1; k <= n; ++k) {
        const Status status = simulator.advance(times[static_cast<std::size_t>(k)] - simulator.time());
        EXPECT_TRUE(status.ok()) << "t = " << simulator.time() << ": " << describe(status, model);
        if (!status) return {1.0, 1.0};
        const auto kk = static_cast<std::size_t>(k);
        result.u_error = std::max(result.u_error, (simulator.u() - u[kk]).cwiseAbs().maxCoeff());
        result.pose_error = std::max(result.pose_error, (simulator.pose() - poses[kk]).cwiseAbs().maxCoeff());
    }
    return result;
}

TEST(ForwardDynamics, RoundTripReturnsToPaperTrajectories) {
    // Forces from the inverse dynamics at 10 kHz, linear in between, over the paper's 0.2 s.
    // Measured: 3.1e-7 m (paper1), 1.7e-7 m (paper2), the error of the linear force
    // interpolation; bound 1e-6 m.
    const Model model{io::expand(io::RobotParameters{})};
    for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
        const RoundTrip result = roundTrip(model, trajectory, 0.2, 10000.0);
        EXPECT_LE(result.u_error, 1e-6) << trajectory.name;
        EXPECT_LE(result.pose_error, 1e-5) << trajectory.name;
    }
}

TEST(ForwardDynamics, RoundTripErrorIsSecondOrderInForceSampling) {
    // The only approximation is the linear interpolation of the forces (O(h^2)): sampling
    // four times finer must shrink the error about sixteen-fold.
    const Model model{io::expand(io::RobotParameters{})};
    const RoundTrip coarse = roundTrip(model, paperTrajectory1(), 0.1, 5000.0);
    const RoundTrip fine = roundTrip(model, paperTrajectory1(), 0.1, 20000.0);
    EXPECT_GT(coarse.u_error / fine.u_error, 10.0) << coarse.u_error << " vs " << fine.u_error;
    EXPECT_LE(fine.u_error, 5e-8);
}

TEST(Simulator, PushedPastTheWorkspaceNamesTheLimb) {
    // 2000 N on slider 1 alone drives u_1 until link 1 stands normal to its rail: the
    // simulation stops there naming limb 1, not with a lost mode or a non-finite state.
    const Model model{io::expand(io::RobotParameters{})};
    Simulator simulator(model);
    ASSERT_TRUE(simulator.reset(Pose::Zero()).ok());
    const ActuatorVector push = Vector3(2000.0, 0.0, 0.0);
    Status status;
    for (int k = 0; k < 1000 && status.ok(); ++k) status = simulator.advance(1e-3, push);
    ASSERT_FALSE(status.ok());
    EXPECT_TRUE(status.code == StatusCode::singular_limb || status.code == StatusCode::unreachable)
        << describe(status, model);
    EXPECT_EQ(status.limb, 0) << describe(status, model);
    EXPECT_NE(describe(status, model).find("limb 1"), std::string::npos) << describe(status, model);
    EXPECT_TRUE(simulator.pose().allFinite());
}

TEST(Simulator, ImpossibleTolerancesEndWithAnErrorInsteadOfCrawling) {
    // Tolerances at the limit of double precision shrink the step without end (until t + h
    // equals t): the minimum step and the step budget stop it with an error naming the cause.
    const Model model{io::expand(io::RobotParameters{})};
    const ActuatorVector tau = Vector3(10.0, -5.0, 3.0);
    auto advanceWith = [&](const SimulatorOptions& options) {
        Simulator simulator(model, options);
        EXPECT_TRUE(simulator.reset(Pose::Zero(), Twist(0.1, 0.01, 0.0)).ok());
        return simulator.advance(1e-3, tau);
    };
    SimulatorOptions tight;
    tight.atol = 1e-22;
    tight.rtol = 1e-22;
    tight.floor_step = 0.0;  // no untested steps: the error test alone decides
    ASSERT_TRUE(advanceWith(SimulatorOptions{}).ok());

    SimulatorOptions budget = tight;
    budget.max_steps = 1000;
    const Status steps = advanceWith(budget);
    EXPECT_EQ(steps.code, StatusCode::integration_too_many_steps) << describe(steps, model);
    EXPECT_NE(describe(steps, model).find("integrator took 1000 steps"), std::string::npos) << describe(steps, model);

    SimulatorOptions floor = tight;
    floor.min_step = 1e-6;
    const Status small = advanceWith(floor);
    EXPECT_EQ(small.code, StatusCode::integration_step_too_small) << describe(small, model);
    EXPECT_LT(small.value, 1e-6);
    EXPECT_NE(describe(small, model).find("below its minimum"), std::string::npos) << describe(small, model);
}

}  // namespace
}  // namespace nocdyn::test
