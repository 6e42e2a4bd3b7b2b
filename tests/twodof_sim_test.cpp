// Two-DOF planar robots (motion: translation, pose [x, y] of a point tool): forward dynamics in
// the task coordinates, M_t d2p_t/dt2 = A_t^T tau - h_t (sim/forward_dynamics.hpp), and
// `nocdyn simulate` on the shipped five-bar (horizontal) and biglide (vertical, under gravity).
//   - The energy balance along a simulated run: the work of the actuators, the integral of
//     tau . du dt (Simpson's rule on the output samples), equals the change of kinetic plus
//     potential energy (the shipped robots have no joint friction).
//   - The inverse dynamics of the simulated motion gives back the applied forces: with the
//     acceleration the forward dynamics computed (an identity of the two stages), and with the
//     acceleration from central differences of the simulated rates (independent of it).
//   - theta is no coordinate: it stays exactly at home(0) and its rate exactly 0.
//   - The command line: the columns t,x,y,u1,u2,du1,du2,tau1,tau2,kinetic, the initial state
//     from x,y or u1,u2, and a theta column refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/sim/simulator.hpp"

namespace nocdyn::test {
namespace {

constexpr double kPi = std::numbers::pi;
// Output step of the simulated runs [s] and their length.
constexpr double kStep = 1e-4;
constexpr int kSamples = 2500;  // even: Simpson's rule over 0.25 s
// Measured: |work - (dT + dV)| <= 3e-12 of the largest energy term on both robots.
constexpr double kEnergyTolerance = 1e-9;
// Measured: inverse dynamics at the forward dynamics' own acceleration gives tau back to 1e-13
// of the peak force.
constexpr double kIdentityTolerance = 1e-10;
// Measured: with central differences of the simulated rates (h = 1e-4 s), to 2e-7 of the peak.
constexpr double kDifferenceTolerance = 1e-5;

RobotDescription shipped(const std::string& name) {
    return io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml");
}

/// Smooth forces about `hold` (the forces holding the robot at home at rest): sinusoids of
/// amplitude `swing` at 3 and 5 Hz, sampled every 1 ms over 0.3 s (cubic spline).
ForceSignal forcesAbout(const Vector2& hold, double swing) {
    std::vector<double> times;
    std::vector<ActuatorVector> tau;
    for (int k = 0; k <= 300; ++k) {
        const double t = 1e-3 * k;
        times.push_back(t);
        ActuatorVector f(2);
        f(0) = hold(0) + swing * std::sin(2.0 * kPi * 3.0 * t);
        f(1) = hold(1) - 0.7 * swing * std::sin(2.0 * kPi * 5.0 * t + 0.4);
        tau.push_back(f);
    }
    return {times, tau, Interpolation::cubic, "test forces"};
}

/// The forces holding the robot at rest at home (inverse dynamics at rest).
Vector2 holding(const Model& model) {
    Data data(model);
    EXPECT_TRUE(inverseDynamics(model, data, model.home, Twist::Zero(), Twist::Zero()).ok());
    return {data.tau(0), data.tau(1)};
}

struct SimulatedRun {
    std::string name;
    double swing;  ///< [N m or N]
};

const std::vector<SimulatedRun>& runs() {
    static const std::vector<SimulatedRun> all{{"five-bar", 0.1}, {"biglide", 1.0}};
    return all;
}

TEST(TwoDofSimulation, WorkOfTheActuatorsIsTheChangeOfEnergy) {
    for (const SimulatedRun& run : runs()) {
        SCOPED_TRACE(run.name);
        const Model model(shipped(run.name));
        ASSERT_EQ(model.task_dimension, 2);
        Simulator simulator(model);
        ASSERT_TRUE(simulator.reset(model.home).ok());
        simulator.setForces(forcesAbout(holding(model), run.swing));
        const double T0 = simulator.kineticEnergy(), V0 = simulator.potentialEnergy();
        std::vector<double> power;  // tau . du at every output sample
        power.push_back(simulator.tau().dot(simulator.du()));
        double largest = std::abs(V0);
        double travel = 0.0;
        for (int k = 1; k <= kSamples; ++k) {
            const Status status = simulator.advance(kStep);
            ASSERT_TRUE(status.ok()) << describe(status, model) << " at t = " << simulator.time();
            power.push_back(simulator.tau().dot(simulator.du()));
            // theta is no coordinate: exactly at home, exactly at rest
            ASSERT_EQ(simulator.pose()(0), model.home(0));
            ASSERT_EQ(simulator.poseRate()(0), 0.0);
            ASSERT_EQ(simulator.poseAcceleration()(0), 0.0);
            largest = std::max({largest, simulator.kineticEnergy(), std::abs(simulator.potentialEnergy())});
            travel = std::max(travel, (simulator.pose() - model.home).tail<2>().norm());
        }
        // the run moves the tool by centimetres, not micrometres
        EXPECT_GT(travel, 5e-3);
        double work = power.front() + power.back();
        for (int k = 1; k < kSamples; ++k) work += (k % 2 == 1 ? 4.0 : 2.0) * power[static_cast<std::size_t>(k)];
        work *= kStep / 3.0;
        const double change = simulator.kineticEnergy() - T0 + simulator.potentialEnergy() - V0;
        EXPECT_GT(simulator.kineticEnergy(), 1e-4);
        EXPECT_NEAR(work, change, kEnergyTolerance * largest) << "work " << work << " J, dT + dV " << change << " J";
        std::printf("%s: work %.12g J, dT + dV %.12g J, |difference| / largest %.3g, travel %.4g m\n", run.name.c_str(),
                    work, change, std::abs(work - change) / largest, travel);
    }
}

TEST(TwoDofSimulation, InverseDynamicsOfTheSimulatedMotionGivesTheForcesBack) {
    for (const SimulatedRun& run : runs()) {
        SCOPED_TRACE(run.name);
        const Model model(shipped(run.name));
        Simulator simulator(model);
        ASSERT_TRUE(simulator.reset(model.home).ok());
        simulator.setForces(forcesAbout(holding(model), run.swing));
        Data data(model);
        double identity = 0.0, difference = 0.0, peak = 0.0;
        for (int k = 1; k <= 20; ++k) {
            const double t = 0.0125 * k - kStep;
            ASSERT_TRUE(simulator.advance(t - simulator.time()).ok());
            const Twist before = simulator.poseRate();
            ASSERT_TRUE(simulator.advance(kStep).ok());
            const Pose p = simulator.pose();
            const Twist dp = simulator.poseRate(), ddp = simulator.poseAcceleration();
            const ActuatorVector applied = simulator.tau();
            ASSERT_TRUE(simulator.advance(kStep).ok());
            const Twist after = simulator.poseRate();
            peak = std::max(peak, applied.cwiseAbs().maxCoeff());
            ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
            identity = std::max(identity, (data.tau - applied).cwiseAbs().maxCoeff());
            const Twist ddp_difference = (after - before) / (2.0 * kStep);
            ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp_difference).ok());
            difference = std::max(difference, (data.tau - applied).cwiseAbs().maxCoeff());
        }
        EXPECT_LE(identity, kIdentityTolerance * peak);
        EXPECT_LE(difference, kDifferenceTolerance * peak);
        std::printf("%s: |tau_ID - tau| / peak %.3g (own acceleration), %.3g (differences)\n", run.name.c_str(),
                    identity / peak, difference / peak);
    }
}

TEST(TwoDofSimulation, ActuatorRatesGiveTaskRatesWithoutTheta) {
    // du = A_t dp_t/dt: the least-squares pose rate of a two-DOF robot has theta's rate 0 and
    // gives du back (a rotation about C moves no actuator, so it is no part of the answer)
    for (const SimulatedRun& run : runs()) {
        SCOPED_TRACE(run.name);
        const Model model(shipped(run.name));
        Data data(model);
        const Pose p(model.home(0), model.home(1) + 0.02, model.home(2) - 0.03);
        const Twist dp(0.0, 0.3, -0.2);
        ASSERT_TRUE(inverseDisplacement(model, data, p).ok());
        ASSERT_TRUE(velocityFromPlatformTwist(model, data, dp).ok());
        const ActuatorVector du = data.du;
        Twist found;
        ASSERT_TRUE(velocityFromActuatorRatesLeastSquares(model, data, du, found).ok());
        EXPECT_EQ(found(0), 0.0);
        EXPECT_NEAR(found(1), dp(1), 1e-12);
        EXPECT_NEAR(found(2), dp(2), 1e-12);
    }
}

void write(const std::filesystem::path& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
}

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

TEST(TwoDofSimulation, SimulateWritesXYAndTakesItsStartFromXYOrU) {
    const std::filesystem::path dir = freshScratchDirectory("twodof_sim");
    const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/biglide.yaml";
    // the biglide's holding forces at home: it stays there, at rest
    write(dir / "hold.csv", "t,tau1,tau2\n0,2.575125,-2.575125\n0.01,2.575125,-2.575125\n");
    CliResult r = runCli("simulate --robot " + robot + " --forces " + (dir / "hold.csv").string() + " --rate 1000");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> out = lines(r.out);
    ASSERT_EQ(out.size(), 12U) << r.out;
    EXPECT_EQ(out[0], "t,x,y,u1,u2,du1,du2,tau1,tau2,kinetic");
    double x = 1.0, y = 1.0;
    ASSERT_EQ(std::sscanf(out.back().c_str(), "%*g,%lg,%lg", &x, &y), 2) << out.back();
    EXPECT_NEAR(x, 0.0, 1e-9);
    EXPECT_NEAR(y, 0.2, 1e-9);
    EXPECT_NE(r.err.find("from the home, at rest"), std::string::npos) << r.err;

    // the start from the first row's x,y,dx,dy
    write(dir / "posed.csv", "t,x,y,dx,dy,tau1,tau2\n0,0.01,0.19,0.1,0,2.5,-2.5\n0.01,0.01,0.19,0.1,0,2.5,-2.5\n");
    r = runCli("simulate --robot " + robot + " --forces " + (dir / "posed.csv").string() + " --rate 1000");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    out = lines(r.out);
    ASSERT_GE(out.size(), 2U);
    double t0 = 1.0;
    ASSERT_EQ(std::sscanf(out[1].c_str(), "%lg,%lg,%lg", &t0, &x, &y), 3) << out[1];
    EXPECT_EQ(t0, 0.0);
    EXPECT_NEAR(x, 0.01, 1e-15);
    EXPECT_NEAR(y, 0.19, 1e-15);
    EXPECT_NE(r.err.find("first row's x,y,dx,dy"), std::string::npos) << r.err;

    // the start from u1,u2: the assembly mode nearest home, named without theta
    write(dir / "u.csv", "t,u1,u2,tau1,tau2\n0,0,0,2.575125,-2.575125\n0.01,0,0,2.575125,-2.575125\n");
    r = runCli("simulate --robot " + robot + " --forces " + (dir / "u.csv").string() + " --rate 1000");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("first row's u1..u2, at rest (assembly mode"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("theta"), std::string::npos) << r.err;
    out = lines(r.out);
    ASSERT_EQ(std::sscanf(out.back().c_str(), "%*g,%lg,%lg", &x, &y), 2) << out.back();
    EXPECT_NEAR(x, 0.0, 1e-9);
    EXPECT_NEAR(y, 0.2, 1e-9);

    // a theta of a two-DOF robot: refused in one line naming the file, line and column
    write(dir / "theta.csv", "t,x,y,theta,tau1,tau2\n0,0,0.2,0.1,0,0\n0.01,0,0.2,0.1,0,0\n");
    r = runCli("simulate --robot " + robot + " --forces " + (dir / "theta.csv").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("theta.csv:2: column 'theta'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("has no theta"), std::string::npos) << r.err;
    EXPECT_EQ(lines(r.err).size(), 1U) << r.err;
}

}  // namespace
}  // namespace nocdyn::test
