// Forward dynamics: it inverts the inverse dynamics; integrated with the inverse-dynamics
// forces it returns to the trajectory; without forces it conserves the kinetic energy; the
// optional loads do what they say; one evaluation and one integration step allocate nothing.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"

#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/forward_dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"
#include "nocdyn/trajectory.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

using prr3::JointVector;

/// Simulates `trajectory` for `duration` with its inverse-dynamics forces sampled at `rate`
/// and interpolated linearly; returns max_k |u(t_k) - u_d(t_k)| [m] and the final pose error.
struct RoundTrip {
    double u_error = 0.0;
    double pose_error = 0.0;
};
RoundTrip roundTrip(const prr3::Model& model, const PoseTrajectory& trajectory, double duration, double rate) {
    prr3::Data data;
    Pose p, dp, ddp;
    trajectory.evaluate(0.0, p, dp, ddp);
    prr3::Simulator simulator(model);
    EXPECT_TRUE(simulator.reset(p, dp).ok());
    EXPECT_TRUE(prr3::inverseDynamics(model, data, p, dp, ddp).ok());
    JointVector tau_begin = data.tau;
    RoundTrip result;
    const int n = static_cast<int>(std::lround(duration * rate));
    for (int k = 1; k <= n; ++k) {
        trajectory.evaluate(k / rate, p, dp, ddp);
        EXPECT_TRUE(prr3::inverseDynamics(model, data, p, dp, ddp).ok());
        const Status status = simulator.advance(1.0 / rate, tau_begin, data.tau);
        EXPECT_TRUE(status.ok()) << "t = " << k / rate << ": " << describe(status, model.parameters);
        if (!status) break;
        tau_begin = data.tau;
        result.u_error = std::max(result.u_error, (simulator.u() - data.u).cwiseAbs().maxCoeff());
        result.pose_error = std::max(result.pose_error, (simulator.pose() - p).cwiseAbs().maxCoeff());
    }
    return result;
}

TEST(ForwardDynamics, InvertsInverseDynamicsAtRandomStates) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data, forward;
    std::uniform_real_distribution<double> acceleration(-50.0, 50.0);
    for (int k = 0; k < 1000; ++k) {
        const Pose p = sampler.next();
        const Twist dp = sampler.twist();
        const Twist ddp(acceleration(sampler.rng()), acceleration(sampler.rng()), acceleration(sampler.rng()));
        solve(model, data, p, dp, ddp);
        Pose guess = p + Pose(1e-4, 1e-4, -1e-4);
        const Status status = prr3::forwardDynamicsFromState(model, forward, data.u, data.du, data.tau, guess);
        ASSERT_TRUE(status.ok()) << describePose(p) << ": " << describe(status, model.parameters);
        const Tolerance tolerance{1e-9, 1e-9};
        for (int j = 0; j < 3; ++j) {
            EXPECT_TRUE(tolerance.accepts(forward.ddu(j), data.ddu(j)))
                << describePose(p) << " limb " << j + 1 << ": " << forward.ddu(j) << " vs " << data.ddu(j);
            EXPECT_TRUE(tolerance.accepts(forward.t_M_dot(j), ddp(j))) << describePose(p);
        }
    }
}

TEST(ForwardDynamics, RoundTripReturnsToPaperTrajectories) {
    // Forces from the inverse dynamics at 10 kHz, linear in between, over the paper's 0.2 s.
    // Measured: ~3e-7 m (paper1), the error of the linear force interpolation; bound 1e-6 m.
    const prr3::Model model;
    for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
        const RoundTrip result = roundTrip(model, trajectory, 0.2, 10000.0);
        EXPECT_LE(result.u_error, 1e-6) << trajectory.name;
        EXPECT_LE(result.pose_error, 1e-5) << trajectory.name;
    }
}

TEST(ForwardDynamics, RoundTripErrorIsSecondOrderInForceSampling) {
    // The only approximation is the linear interpolation of the forces (O(h^2)): sampling
    // four times finer must shrink the error about sixteen-fold.
    const prr3::Model model;
    const RoundTrip coarse = roundTrip(model, paperTrajectory1(), 0.1, 5000.0);
    const RoundTrip fine = roundTrip(model, paperTrajectory1(), 0.1, 20000.0);
    EXPECT_GT(coarse.u_error / fine.u_error, 10.0) << coarse.u_error << " vs " << fine.u_error;
    EXPECT_LE(fine.u_error, 5e-8);
}

TEST(ForwardDynamics, ZeroForceConservesKineticEnergy) {
    const prr3::Model model;
    prr3::Simulator simulator(model);
    ASSERT_TRUE(simulator.reset(Pose(0.01, 0.002, -0.001), Twist(0.5, 0.05, -0.03)).ok());
    const double initial = simulator.kineticEnergy();
    ASSERT_GT(initial, 1e-3);
    double drift = 0.0;
    for (int k = 0; k < 500; ++k) {  // 0.5 s, the platform drifts several centimetres
        const Status status = simulator.advance(1e-3, JointVector::Zero());
        ASSERT_TRUE(status.ok()) << "t = " << simulator.time() << ": " << describe(status, model.parameters);
        drift = std::max(drift, std::abs(simulator.kineticEnergy() - initial));
    }
    // Integrator tolerances 1e-12 absolute, 1e-10 relative per component.
    EXPECT_LE(drift / initial, 1e-9);
    EXPECT_GT((simulator.pose() - Pose(0.01, 0.002, -0.001)).norm(), 0.01);
}

TEST(ForwardDynamics, ForcesBalancingAPlatformWrenchHoldTheRobotAtRest) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data;
    for (int k = 0; k < 100; ++k) {
        Pose p = sampler.next();
        ASSERT_TRUE(prr3::inverseDisplacement(model, data, p).ok());
        prr3::ExternalLoads loads;
        loads.platform_wrench = Wrench(0.3, 5.0, -2.0);
        ASSERT_TRUE(prr3::velocityFromActuatorRates(model, data, JointVector::Zero()).ok());
        prr3::twistShaping(model, data);
        // tau = -T_7^T w: the actuators react the wrench exactly (statics of eq. 20).
        const JointVector tau = -data.T[prr3::kPlatformBody].transpose() * loads.platform_wrench;
        ASSERT_TRUE(prr3::forwardDynamics(model, data, tau, loads).ok());
        EXPECT_LE(data.ddu.cwiseAbs().maxCoeff(), 1e-10) << describePose(p);
        // Without the actuators the same wrench accelerates the platform along itself:
        // power w . dt_M > 0 (I is positive definite).
        ASSERT_TRUE(prr3::forwardDynamics(model, data, JointVector::Zero(), loads).ok());
        EXPECT_GT(loads.platform_wrench.dot(data.t_M_dot), 0.0) << describePose(p);
    }
}

TEST(ForwardDynamics, ViscousFrictionDissipatesWhatItsPowerSays) {
    const prr3::Model model;
    prr3::SimulatorOptions options;
    options.loads.viscous_friction = JointVector(20.0, 30.0, 40.0);
    prr3::Simulator simulator(model, options);
    ASSERT_TRUE(simulator.reset(Pose::Zero(), Twist(0.5, 0.05, -0.03)).ok());
    double energy = simulator.kineticEnergy();
    const double initial = energy;
    double dissipated = 0.0;
    const double dt = 1e-5;
    for (int k = 0; k < 2000; ++k) {
        const JointVector du = simulator.du();
        ASSERT_TRUE(simulator.advance(dt, JointVector::Zero()).ok());
        const JointVector du_end = simulator.du();
        // trapezoidal rule on the dissipated power sum_j b_j du_j^2
        dissipated += 0.5 * dt *
                      (options.loads.viscous_friction.dot(du.cwiseAbs2()) +
                       options.loads.viscous_friction.dot(du_end.cwiseAbs2()));
        const double now = simulator.kineticEnergy();
        EXPECT_LT(now, energy);
        energy = now;
    }
    EXPECT_LT(energy, 0.9 * initial);
    EXPECT_NEAR(initial - energy, dissipated, 1e-6 * initial);
}

TEST(ForwardDynamics, EvaluationAndIntegrationAllocateNothing) {
    const prr3::Model model;
    prr3::Data data;
    prr3::Simulator simulator(model);
    ASSERT_TRUE(simulator.reset(Pose(0.01, 0.002, -0.001), Twist(0.5, 0.05, -0.03)).ok());
    Pose pose(0.0, 0.0, 0.0);
    const long before = allocationCount();
    double checksum = 0.0;
    for (int k = 0; k < 100; ++k) {
        const Status status = prr3::forwardDynamicsFromState(
            model, data, JointVector(1e-3, -2e-3, 5e-4), JointVector(0.1, 0.2, -0.1), JointVector(10, 20, 30), pose);
        checksum += status.ok() ? data.ddu.sum() : 1e9;
        checksum += simulator.advance(1e-4, JointVector(1.0, -1.0, 0.5)).ok();
    }
    EXPECT_EQ(allocationCount() - before, 0);
    EXPECT_TRUE(std::isfinite(checksum));
}

TEST(Simulator, PushedPastTheWorkspaceEdgeNamesTheEdgeAndTheLimb) {
    // 2000 N on slider 1 alone drives u_1 until link 1 stands normal to its rail, where u_1
    // turns back: the simulation stops there naming limb 1 and the edge, not a lost mode.
    const prr3::Model model;
    prr3::Simulator simulator(model);
    ASSERT_TRUE(simulator.reset(Pose::Zero()).ok());
    Status status;
    for (int k = 0; k < 1000 && status.ok(); ++k) status = simulator.advance(1e-3, prr3::JointVector(2000.0, 0.0, 0.0));
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.code, StatusCode::workspace_edge) << describe(status, model.parameters);
    EXPECT_EQ(status.limb, 0);
    EXPECT_NE(describe(status, model.parameters).find("edge of the workspace: limb 1"), std::string::npos);
}

TEST(Simulator, ImpossibleTolerancesEndWithAnErrorInsteadOfCrawling) {
    // Tolerances at the limit of double precision shrink the step without end (until t + h
    // equals t): the minimum step and the step budget stop it with an error naming the cause.
    const prr3::Model model;
    auto advanceWith = [&](const prr3::SimulatorOptions& options) {
        prr3::Simulator simulator(model, options);
        EXPECT_TRUE(simulator.reset(Pose::Zero(), Twist(0.1, 0.01, 0.0)).ok());
        return simulator.advance(1e-3, prr3::JointVector(10.0, -5.0, 3.0));
    };
    prr3::SimulatorOptions tight;
    tight.absolute_tolerance = 1e-22;
    tight.relative_tolerance = 1e-22;
    ASSERT_TRUE(advanceWith(prr3::SimulatorOptions{}).ok());

    prr3::SimulatorOptions budget = tight;
    budget.max_steps = 1000;
    const Status steps = advanceWith(budget);
    EXPECT_EQ(steps.code, StatusCode::integration_too_many_steps) << describe(steps, model.parameters);
    EXPECT_NE(describe(steps, model.parameters).find("integrator took 1000 steps"), std::string::npos);

    prr3::SimulatorOptions floor = tight;
    floor.min_step = 1e-6;
    const Status small = advanceWith(floor);
    EXPECT_EQ(small.code, StatusCode::integration_step_too_small) << describe(small, model.parameters);
    EXPECT_LT(small.value, 1e-6);
    EXPECT_NE(describe(small, model.parameters).find("below its minimum"), std::string::npos);
}

}  // namespace
}  // namespace nocdyn::test
