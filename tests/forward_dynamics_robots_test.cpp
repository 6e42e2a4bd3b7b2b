// Forward dynamics of any robot (forward_dynamics.hpp) on the example robots: the inverse
// dynamics' forces, replayed through the cubic interpolation, give back the motion; without
// forces, gravity and friction the kinetic energy is conserved; with them the energy balance
// holds; M_p is symmetric positive definite, agrees with the inverse dynamics and with the
// finite differences of the model; the interpolations do what they say; a singularity stops
// the integration naming the limb; one step allocates nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Dense>

#include "allocation_counter.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

const std::vector<std::string> kRobots{"paper-3prr", "3-rrr", "3-rpr", "4-rrr"};

/// The example robot with gravity along -y, damping at every joint and, when `coulomb`,
/// Coulomb friction too.
RobotDescription withGravityAndFriction(RobotDescription robot, bool coulomb = true) {
    robot.gravity = Vector2(0.0, -9.81);
    for (LimbDescription& limb : robot.limbs) {
        for (JointDescription& joint : limb.joints) {
            const bool revolute = joint.type == JointType::revolute;
            joint.damping = revolute ? 2e-3 : 0.5;                     // [N m s/rad], [N s/m]
            joint.friction = coulomb ? (revolute ? 1e-3 : 0.2) : 0.0;  // [N m], [N]
        }
    }
    return robot;
}

/// The example robot without gravity or friction.
RobotDescription conservative(RobotDescription robot) {
    robot.gravity = Vector2::Zero();
    for (LimbDescription& limb : robot.limbs) {
        for (JointDescription& joint : limb.joints) joint.damping = joint.friction = 0.0;
    }
    return robot;
}

/// Inverse dynamics of `trajectory` at t_k = k / rate, k = 0..count: the forces as a signal.
ForceSignal inverseDynamicsForces(const Model& model, const PoseTrajectory& trajectory, double rate, int count,
                                  Interpolation interpolation, std::vector<ActuatorVector>* u = nullptr) {
    Data data(model);
    std::vector<double> times;
    std::vector<ActuatorVector> tau;
    for (int k = 0; k <= count; ++k) {
        const double t = k / rate;
        Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        const Status status = inverseDynamics(model, data, p, dp, ddp);
        EXPECT_TRUE(status.ok()) << "t = " << t << ": " << describe(status, model);
        times.push_back(t);
        tau.push_back(data.tau);
        if (u) u->push_back(data.u);
    }
    return {times, tau, interpolation, "inverse dynamics"};
}

struct RoundTrip {
    double error = 0.0;  ///< max over actuators of max_k |u_a(t_k) - u_a,d(t_k)| / peak_k |u_a,d(t_k) - u_a,d(0)|
    double peak = 0.0;   ///< the smallest peak displacement [m or rad]
    std::size_t steps = 0;
};

/// The round trip at 10 kHz over `duration` with the given interpolation of the forces.
RoundTrip roundTrip(const Model& model, const PoseTrajectory& trajectory, double duration,
                    Interpolation interpolation) {
    constexpr double kRate = 10000.0;
    const int count = static_cast<int>(std::lround(duration * kRate));
    std::vector<ActuatorVector> u_d;
    Simulator simulator(model);
    Pose p, dp, ddp;
    trajectory.evaluate(0.0, p, dp, ddp);
    EXPECT_TRUE(simulator.reset(p, dp).ok());  // (clears the forces)
    simulator.setForces(inverseDynamicsForces(model, trajectory, kRate, count, interpolation, &u_d));
    std::vector<double> peak(static_cast<std::size_t>(model.actuators), 0.0), error(peak);
    for (int k = 1; k <= count; ++k) {
        const Status status = simulator.advance(1.0 / kRate);
        EXPECT_TRUE(status.ok()) << "t = " << simulator.time() << ": " << describe(status, model);
        if (!status) return {1.0, 0.0, 0};
        for (int a = 0; a < model.actuators; ++a) {
            const auto aa = static_cast<std::size_t>(a);
            const auto kk = static_cast<std::size_t>(k);
            peak[aa] = std::max(peak[aa], std::abs(u_d[kk](a) - u_d[0](a)));
            error[aa] = std::max(error[aa], std::abs(simulator.u()(a) - u_d[kk](a)));
        }
    }
    RoundTrip result;
    result.peak = *std::min_element(peak.begin(), peak.end());
    for (std::size_t a = 0; a < peak.size(); ++a) result.error = std::max(result.error, error[a] / peak[a]);
    result.steps = simulator.acceptedSteps();
    return result;
}

class ExampleRobot : public ::testing::TestWithParam<std::string> {};

TEST_P(ExampleRobot, InverseDynamicsForcesThroughTheCubicSplineGiveBackTheMotion) {
    // with gravity and damping (smooth forces); Coulomb friction makes the forces jump where a
    // joint rate changes sign, which no interpolation of samples reproduces (next test)
    for (const bool gravity : {false, true}) {
        const RobotDescription robot = io::exampleRobot(GetParam());
        const Model model(gravity ? withGravityAndFriction(robot, false) : robot);
        const RoundTrip r = roundTrip(model, paperTrajectory1(), 0.2, Interpolation::cubic);
        EXPECT_GT(r.peak, 1e-4);                 // the motion is not trivial
        EXPECT_LT(r.error, 2e-9) << GetParam();  // measured: 1.5e-10 at most (4-rrr)
        std::printf("%s%s: round trip (cubic, 10 kHz, 0.2 s): max |u - u_d| / peak |u_d - u_d(0)| = %.3g, %zu steps\n",
                    GetParam().c_str(), gravity ? " (gravity, damping)" : "", r.error, r.steps);
    }
}

TEST_P(ExampleRobot, WithCoulombFrictionTheRoundTripIsLimitedByTheForceJumps) {
    const Model model(withGravityAndFriction(io::exampleRobot(GetParam())));
    const RoundTrip r = roundTrip(model, paperTrajectory1(), 0.2, Interpolation::cubic);
    EXPECT_LT(r.error, 1e-2) << GetParam();  // measured: 2.0e-3 at most (3-rpr), 3e-5 to 2e-4 elsewhere
    std::printf("%s (gravity, damping, Coulomb friction): round trip (cubic, 10 kHz, 0.2 s): %.3g\n",
                GetParam().c_str(), r.error);
}

TEST_P(ExampleRobot, TheRoundTripIsLimitedByTheInterpolationOfTheForces) {
    // the same forces held or interpolated linearly: errors of order of the sample period
    const Model model(conservative(io::exampleRobot(GetParam())));
    const RoundTrip cubic = roundTrip(model, paperTrajectory1(), 0.05, Interpolation::cubic);
    const RoundTrip linear = roundTrip(model, paperTrajectory1(), 0.05, Interpolation::linear);
    const RoundTrip hold = roundTrip(model, paperTrajectory1(), 0.05, Interpolation::hold);
    // measured: cubic 8e-11 to 1.9e-10, linear 1.0e-5 to 1.7e-5, hold 6.9e-3 to 7.4e-3
    EXPECT_LT(cubic.error, 2e-9);
    EXPECT_GT(linear.error, 10.0 * cubic.error);
    EXPECT_LT(linear.error, 2e-4);
    EXPECT_GT(hold.error, 10.0 * linear.error);
    EXPECT_LT(hold.error, 0.075);
    std::printf("%s: round trip over 0.05 s: cubic %.3g, linear %.3g, hold %.3g\n", GetParam().c_str(), cubic.error,
                linear.error, hold.error);
}

TEST_P(ExampleRobot, WithoutForcesGravityOrFrictionKineticEnergyIsConserved) {
    const Model model(conservative(io::exampleRobot(GetParam())));
    SimulatorOptions options;
    options.rtol = 1e-12;
    options.atol = 1e-14;
    Simulator simulator(model, options);
    ASSERT_TRUE(simulator.reset(model.home, Twist(0.2, 0.006, -0.004)).ok());
    const double energy = simulator.kineticEnergy();
    ASSERT_GT(energy, 0.0);
    double drift = 0.0;
    for (int k = 0; k < 100; ++k) {
        const Status status = simulator.advance(0.01);
        ASSERT_TRUE(status.ok()) << "t = " << simulator.time() << ": " << describe(status, model);
        drift = std::max(drift, std::abs(simulator.kineticEnergy() - energy) / energy);
    }
    EXPECT_LT(drift, 2e-14) << GetParam();                    // measured: 2.2e-15 at most
    EXPECT_GT((simulator.pose() - model.home).norm(), 1e-3);  // it moved
    std::printf("%s: kinetic energy drift over 1 s: %.3g (relative), %zu steps\n", GetParam().c_str(), drift,
                simulator.acceptedSteps());
}

TEST_P(ExampleRobot, WithGravityAndFrictionEnergyChangesByTheWorkOfTheActuatorsLessFriction) {
    // d(KE + PE)/dt = tau . du - friction power, integrated over the run (Simpson's rule)
    const Model model(withGravityAndFriction(io::exampleRobot(GetParam())));
    constexpr double kRate = 10000.0;
    constexpr int kCount = 1000;
    Simulator simulator(model);
    Pose p, dp, ddp;
    paperTrajectory2().evaluate(0.0, p, dp, ddp);
    ASSERT_TRUE(simulator.reset(p, dp).ok());
    simulator.setForces(inverseDynamicsForces(model, paperTrajectory2(), kRate, kCount, Interpolation::cubic));
    ASSERT_TRUE(simulator.advance(0.0).ok());
    std::vector<double> power, energy;
    double flow = 0.0;
    for (int k = 0; k <= kCount; ++k) {
        if (k > 0) {
            ASSERT_TRUE(simulator.advance(1.0 / kRate).ok());
        }
        const Data& d = simulator.data();
        power.push_back(d.tau.dot(d.du) - frictionPower(model, d));
        energy.push_back(simulator.kineticEnergy() + simulator.potentialEnergy());
        flow += std::abs(power.back()) / kRate;
    }
    double work = 0.0;
    for (int k = 0; k + 2 <= kCount; k += 2) {
        const auto kk = static_cast<std::size_t>(k);
        work += (power[kk] + 4.0 * power[kk + 1] + power[kk + 2]) / (3.0 * kRate);
    }
    const double change = energy.back() - energy.front();
    EXPECT_GT(flow, 1e-4);
    // measured: 2.0e-8 at most (3-rpr)
    EXPECT_LT(std::abs(change - work), 2e-7 * flow) << GetParam() << ": dE = " << change << " J, work " << work;
    std::printf("%s: energy balance over 0.1 s: |dE - W| / int |P| dt = %.3g\n", GetParam().c_str(),
                std::abs(change - work) / flow);
}

TEST_P(ExampleRobot, PlatformInertiaIsSymmetricPositiveDefiniteAndInvertsTheInverseDynamics) {
    const Model model(withGravityAndFriction(io::exampleRobot(GetParam())));
    Data data(model), ref(model);
    const PoseTrajectory trajectory = paperTrajectory2();
    for (int k = 0; k < 20; ++k) {
        Pose p, dp, ddp;
        trajectory.evaluate(0.013 * k, p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(model, ref, p, dp, ddp).ok());
        ASSERT_TRUE(forwardDynamics(model, data, p, dp, ref.tau).ok());
        const Matrix3& M = data.M_p;
        EXPECT_LT((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-14 * M.cwiseAbs().maxCoeff());
        const Eigen::SelfAdjointEigenSolver<Matrix3> eig(M);
        EXPECT_GT(eig.eigenvalues().minCoeff(), 1e-6 * eig.eigenvalues().maxCoeff());
        // the accelerations that gave the forces
        EXPECT_LT((data.t_M_dot - ddp).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + ddp.cwiseAbs().maxCoeff()));
        EXPECT_LT((data.ddu - ref.ddu).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + ref.ddu.cwiseAbs().maxCoeff()));
        // in the actuator coordinates of a three-actuator robot: I = Xi_p^T M_p Xi_p, t_M = Xi_p du
        if (model.coordinates == Coordinates::actuators) {
            const Vector2 c = p.tail<2>();
            Matrix3 S_inv;
            S_inv << 1.0, 0.0, 0.0, -c.y(), 1.0, 0.0, c.x(), 0.0, 1.0;
            const Matrix3 Xi_p = S_inv * ref.Xi;
            EXPECT_LT((Xi_p.transpose() * M * Xi_p - ref.I).cwiseAbs().maxCoeff(), 1e-12 * ref.I.cwiseAbs().maxCoeff());
            // Xi keeps the model's coordinates (A^-1); T, I and C say they are the platform's
            EXPECT_LT((data.Xi - ref.Xi).cwiseAbs().maxCoeff(), 1e-12 * ref.Xi.cwiseAbs().maxCoeff());
            EXPECT_EQ(ref.coordinates, Coordinates::actuators);
        }
        EXPECT_EQ(data.coordinates, Coordinates::platform);
        EXPECT_LT((data.I - M).cwiseAbs().maxCoeff(), 1e-300) << "I holds M_p after forwardDynamics";
    }
}

TEST_P(ExampleRobot, PlatformInertiaRateMatchesFiniteDifferences) {
    // dM_p/dt = C_p + C_p^T (eq. 23), dM_p/dt by central differences along the motion
    const Model model(io::exampleRobot(GetParam()));
    Data data(model), ahead(model), behind(model);
    const ActuatorVector zero = ActuatorVector::Zero(model.actuators);
    constexpr double h = 1e-6;
    for (int k = 0; k < 10; ++k) {
        Pose p, dp, ddp;
        paperTrajectory1().evaluate(0.021 * k, p, dp, ddp);
        ASSERT_TRUE(forwardDynamics(model, data, p, dp, zero).ok());
        ASSERT_TRUE(forwardDynamics(model, ahead, p + h * dp, dp, zero).ok());
        ASSERT_TRUE(forwardDynamics(model, behind, p - h * dp, dp, zero).ok());
        const Matrix3 M_dot = (ahead.M_p - behind.M_p) / (2.0 * h);
        const Matrix3 C_sum = data.C + data.C.transpose();
        EXPECT_LT((M_dot - C_sum).cwiseAbs().maxCoeff(), 1e-6 * (1e-9 + C_sum.cwiseAbs().maxCoeff())) << GetParam();
    }
}

TEST_P(ExampleRobot, WithoutForcesTheAccelerationNeedsNoForceAndKeepsTheKineticEnergy) {
    // The acceleration forwardDynamics gives for tau = 0, checked by two independent means:
    // the inverse dynamics (the full path over T_i, I and C, eq. 23) of that acceleration needs
    // no force, and the kinetic energy of the bodies (their twists, no M_p) is constant along
    // p(t) = p + t dp + t^2 ddp / 2, by central differences.
    const Model model(conservative(io::exampleRobot(GetParam())));
    Data data(model), ref(model), ahead(model), behind(model);
    const ActuatorVector zero = ActuatorVector::Zero(model.actuators);
    // Measured on the example robots: |tau| <= 1.3e-14 of the bias forces, |dE/dt| <= 2.2e-9 of
    // 2 E |ddp| / |dp| (3-rpr; rounding below h = 1e-6, truncation above).
    constexpr double kForceTolerance = 1e-13, kEnergyRateTolerance = 2e-8, h = 1e-6;
    double force = 0.0, power = 0.0;
    for (int k = 0; k < 10; ++k) {
        Pose p, dp, ddp;
        paperTrajectory1().evaluate(0.021 * k, p, dp, ddp);
        ASSERT_TRUE(forwardDynamics(model, data, p, dp, zero).ok()) << GetParam() << ", p = [" << p.transpose() << "]";
        const Twist a = data.t_M_dot;
        ASSERT_TRUE(inverseDynamics(model, ref, p, dp, Twist::Zero()).ok());
        const double bias = ref.tau.cwiseAbs().maxCoeff();
        ASSERT_GT(bias, 0.0) << GetParam() << ": the motion has no velocity-dependent force to balance";
        ASSERT_TRUE(inverseDynamics(model, ref, p, dp, a).ok());
        EXPECT_LT(ref.tau.cwiseAbs().maxCoeff(), kForceTolerance * bias)
            << GetParam() << ", p = [" << p.transpose() << "]";
        ASSERT_TRUE(inverseDynamics(model, ahead, p + h * dp + 0.5 * h * h * a, dp + h * a, Twist::Zero()).ok());
        ASSERT_TRUE(inverseDynamics(model, behind, p - h * dp + 0.5 * h * h * a, dp - h * a, Twist::Zero()).ok());
        const double energy = kineticEnergy(model, ref);
        const double rate = (kineticEnergy(model, ahead) - kineticEnergy(model, behind)) / (2.0 * h);
        const double power_scale = 2.0 * energy * a.norm() / dp.norm();
        EXPECT_LT(std::abs(rate), kEnergyRateTolerance * power_scale)
            << GetParam() << ", p = [" << p.transpose() << "]";
        force = std::max(force, ref.tau.cwiseAbs().maxCoeff() / bias);
        power = std::max(power, std::abs(rate) / power_scale);
    }
    std::printf("%s: without forces: |tau(ddp)| / bias %.3g, |dE/dt| / scale %.3g\n", GetParam().c_str(), force, power);
}

INSTANTIATE_TEST_SUITE_P(Robots, ExampleRobot, ::testing::ValuesIn(kRobots), [](const auto& info) {
    std::string name = info.param;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
});

TEST(ForceSignal, HoldLinearAndCubicInterpolateAsTheyShould) {
    std::vector<double> t;
    std::vector<ActuatorVector> tau;
    for (int k = 0; k <= 100; ++k) {
        const double x = k / 100.0;
        t.push_back(x);
        ActuatorVector f(3);
        f << x, x * x * x, 1.0;  // a cubic is reproduced by the spline away from the ends
        tau.push_back(f);
    }
    const ForceSignal hold(t, tau, Interpolation::hold);
    const ForceSignal linear(t, tau, Interpolation::linear);
    const ForceSignal cubic(t, tau, Interpolation::cubic);
    EXPECT_DOUBLE_EQ(hold.at(0.255)(0), 0.25);
    EXPECT_DOUBLE_EQ(hold.at(0.26)(0), 0.26);  // right-continuous at a sample
    ActuatorVector f;
    hold.evaluate(0.26, hold.piece(0.255), f);  // the piece's own limit at its end
    EXPECT_DOUBLE_EQ(f(0), 0.25);
    EXPECT_NEAR(linear.at(0.255)(1), 0.5 * (0.25 * 0.25 * 0.25 + 0.26 * 0.26 * 0.26), 1e-15);
    for (const double x : {0.005, 0.255, 0.5, 0.995}) {
        EXPECT_NEAR(cubic.at(x)(1), x * x * x, 1e-8) << x;  // endpoint slopes O(h^4)
        EXPECT_NEAR(cubic.at(x)(0), x, 1e-12) << x;
        EXPECT_NEAR(cubic.at(x)(2), 1.0, 1e-12) << x;
    }
    EXPECT_DOUBLE_EQ(cubic.at(5.0)(1), 1.0);  // held after the last sample
    EXPECT_DOUBLE_EQ(cubic.at(-1.0)(1), 0.0);
    // pieces: every sample for hold and linear, only the ends for cubic
    EXPECT_DOUBLE_EQ(hold.pieceEnd(hold.piece(0.255)), 0.26);
    EXPECT_DOUBLE_EQ(cubic.pieceEnd(cubic.piece(0.255)), 1.0);
    EXPECT_TRUE(std::isinf(cubic.pieceEnd(cubic.piece(1.0))));
}

TEST(ForceSignal, CubicRefusesNonUniformTimesAndNamesTheSample) {
    std::vector<double> t{0.0, 0.1, 0.2, 0.35, 0.4, 0.5};
    std::vector<ActuatorVector> tau(t.size(), ActuatorVector::Zero(3));
    try {
        const ForceSignal s(t, tau, Interpolation::cubic, "f.csv");
        FAIL() << "accepted non-uniform times";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("f.csv: sample 4"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("uniform"), std::string::npos) << e.what();
    }
    EXPECT_NO_THROW(ForceSignal(t, tau, Interpolation::linear));
    std::vector<double> back{0.0, 0.2, 0.1};
    std::vector<ActuatorVector> three(3, ActuatorVector::Zero(3));
    EXPECT_THROW(ForceSignal(back, three, Interpolation::hold), Error);
}

TEST(Simulator, AConstantPushEndsAtASingularityOrOutOfReachNamingTheLimb) {
    const Model model(io::exampleRobot("3-rrr"));
    Simulator simulator(model);
    ActuatorVector tau = ActuatorVector::Zero(3);
    tau(0) = 1.0;  // [N m] on the first motor only
    Status status;
    for (int k = 0; k < 1000 && status.ok(); ++k) status = simulator.advance(0.01, tau);
    ASSERT_FALSE(status.ok());
    EXPECT_TRUE(status.code == StatusCode::singular_limb || status.code == StatusCode::unreachable ||
                status.code == StatusCode::singular_actuation)
        << describe(status, model);
    if (status.code != StatusCode::singular_actuation) {
        EXPECT_GE(status.limb, 0);
    }
    EXPECT_GT(simulator.time(), 0.0);
    EXPECT_TRUE(simulator.pose().allFinite());
}

TEST(Simulator, ASlidingPlatformThatSticksUnderCoulombFrictionIsSimulatedInBoundedTime) {
    // Coulomb friction only, at the paper robot's sliders, and no force: the platform coasts,
    // stops, and sticks; from then on q' chatters about 0 and every step straddles friction's
    // jump. The step floor keeps the work per tick bounded; without it the controller would
    // shrink the step without end (here: below min_step, or max_steps per tick reached).
    RobotDescription robot = conservative(io::exampleRobot("paper-3prr"));
    for (LimbDescription& limb : robot.limbs) limb.joints[0].friction = 20.0;  // [N]
    const Model model(robot);
    SimulatorOptions options;
    options.max_steps = 2000;  // per tick: far more than the floor ever needs (1e-4 / 1e-6)
    Simulator simulator(model, options);
    ASSERT_TRUE(simulator.reset(model.home, Twist(0.0, 0.005, 0.0)).ok());  // 5 mm/s along x
    const ActuatorVector none = ActuatorVector::Zero(3);
    Status status;
    for (int k = 0; k < 50 && status.ok(); ++k) status = simulator.advance(1e-4, none);  // 10 kHz, 5 ms
    ASSERT_TRUE(status.ok()) << describe(status, model);
    std::printf("sticking: %zu accepted steps (%zu at the floor), %zu rejected over 50 ticks\n",
                simulator.acceptedSteps(), simulator.flooredSteps(), simulator.rejectedSteps());
    EXPECT_GT(simulator.flooredSteps(), 0U);                // it did stick
    EXPECT_LT(simulator.du().cwiseAbs().maxCoeff(), 1e-4);  // and is at rest (5 mm/s before)
    EXPECT_LT(simulator.acceptedSteps() + simulator.rejectedSteps(), 50U * 250U);
    EXPECT_TRUE(simulator.pose().allFinite());
    // with the floor off, the same run fails: the step falls below min_step, or a tick takes max_steps
    options.floor_step = 0.0;
    Simulator crawling(model, options);
    ASSERT_TRUE(crawling.reset(model.home, Twist(0.0, 0.005, 0.0)).ok());
    status = {};
    for (int k = 0; k < 50 && status.ok(); ++k) status = crawling.advance(1e-4, none);
    EXPECT_TRUE(status.code == StatusCode::integration_step_too_small ||
                status.code == StatusCode::integration_too_many_steps)
        << describe(status, model);
}

TEST(Simulator, OneStepAllocatesNothing) {
    const Model model(withGravityAndFriction(io::exampleRobot("4-rrr")));
    Simulator simulator(model);
    simulator.setForces(inverseDynamicsForces(model, paperTrajectory1(), 10000.0, 100, Interpolation::cubic));
    ASSERT_TRUE(simulator.advance(1e-4).ok());
    const ActuatorVector tau = simulator.tau();
    const long before = allocationCount();
    const Status a = simulator.advance(1e-4);
    const Status b = simulator.advance(1e-4, tau);
    EXPECT_EQ(allocationCount(), before);
    EXPECT_TRUE(a.ok() && b.ok());
}

}  // namespace
}  // namespace nocdyn::test
