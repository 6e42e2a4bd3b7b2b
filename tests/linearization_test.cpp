// The linearised model and its frequency response (analysis/linearization.hpp) against
// time-domain simulation with nocdyn's own integrator (sim/forward_dynamics.hpp): a small sine
// force on one actuator, simulated to steady state, the platform acceleration's fundamental
// compared with H(j w) at five frequencies; and the paper robot's plant response (the numbers
// of docs/frequency-response.md).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/sim/simulator.hpp"

namespace nocdyn::test {
namespace {

RobotDescription paperRobot() {
    return io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr.yaml");
}

/// The paper's robot with viscous damping `c` [N s/m] at every slider: the plant from force to
/// acceleration is then a high-pass (M s + D)^-1 s A_p^T instead of a constant.
RobotDescription dampedPaperRobot(double c) {
    RobotDescription robot = paperRobot();
    for (LimbDescription& limb : robot.limbs) {
        for (JointDescription& joint : limb.joints) {
            if (joint.actuated) joint.damping = c;
        }
    }
    return robot;
}

/// The fundamental of y over samples at times t (whole periods of w): sum y e^{-j w t} 2 / N.
std::complex<double> fundamental(const std::vector<double>& t, const std::vector<double>& y, double w) {
    std::complex<double> sum = 0.0;
    for (std::size_t k = 0; k < t.size(); ++k) sum += y[k] * std::exp(std::complex<double>(0.0, -w * t[k]));
    return 2.0 * sum / static_cast<double>(t.size());
}

TEST(FrequencyResponse, AgreesWithTimeDomainSimulationToOnePercentAtFiveFrequencies) {
    const Model model(dampedPaperRobot(150.0));
    Data data(model);
    const Pose p0 = model.home;
    const ActuatorVector tau0 = ActuatorVector::Zero(model.actuators);
    StateSpace system;
    ASSERT_TRUE(linearize(model, data, p0, Twist::Zero(), tau0, LinearOutput::platform_acceleration, system).ok());
    // the slowest decaying mode sets the settling time (the pose integrators, eigenvalue 0, are
    // not seen by the acceleration)
    const Eigen::VectorXcd poles = system.A.eigenvalues();
    double slowest = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < poles.size(); ++i) {
        if (std::abs(poles(i)) > 1e-6) slowest = std::min(slowest, -poles(i).real());
    }
    ASSERT_GT(slowest, 10.0);  // decays faster than 0.1 s
    const double settle = 12.0 / slowest;
    const double amplitude = 0.05;  // [N]: the platform moves less than 0.1 mm at 3 Hz
    int checked = 0;
    for (const double f : {3.0, 10.0, 30.0, 100.0, 300.0}) {
        const double w = 2.0 * std::numbers::pi * f;
        const int periods = 4;
        const double start = std::ceil(settle * f) / f;  // whole periods
        const double end = start + periods / f;
        // the force as a cubic spline through 400 samples a period
        const int per_period = 400;
        const auto count = static_cast<std::size_t>(std::ceil(end * f * per_period)) + 8;
        std::vector<double> times(count), forces(count * static_cast<std::size_t>(model.actuators), 0.0);
        for (std::size_t k = 0; k < count; ++k) {
            times[k] = static_cast<double>(k) / (f * per_period);
            forces[k * static_cast<std::size_t>(model.actuators)] = amplitude * std::sin(w * times[k]);
        }
        Simulator sim(model);
        ASSERT_TRUE(sim.reset(p0).ok());
        sim.setForces(ForceSignal(times, forces, model.actuators, Interpolation::cubic));
        ASSERT_TRUE(sim.advance(start).ok());
        const int samples = periods * 200;
        std::vector<double> t(static_cast<std::size_t>(samples)), u(t.size());
        std::array<std::vector<double>, 3> y;
        for (auto& axis : y) axis.resize(t.size());
        for (int k = 0; k < samples; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            t[kk] = sim.time();
            u[kk] = sim.tau()(0);
            for (std::size_t o = 0; o < 3; ++o) y[o][kk] = sim.poseAcceleration()(static_cast<Eigen::Index>(o));
            ASSERT_TRUE(sim.advance((end - start) / samples).ok());
        }
        const std::complex<double> U = fundamental(t, u, w);
        const Eigen::MatrixXcd H = frequencyResponse(system, f);
        const double scale = H.col(0).cwiseAbs().maxCoeff();
        for (int o = 0; o < 3; ++o) {
            const std::complex<double> measured = fundamental(t, y[static_cast<std::size_t>(o)], w) / U;
            const double error = std::abs(measured - H(o, 0)) / scale;
            EXPECT_LT(error, 0.01) << "f = " << f << " Hz, output " << o << ": simulated " << std::abs(measured)
                                   << " at " << std::arg(measured) * 180 / std::numbers::pi << " deg, linear "
                                   << std::abs(H(o, 0)) << " at " << std::arg(H(o, 0)) * 180 / std::numbers::pi
                                   << " deg";
            // and each of amplitude and phase to 1 % on the channel that carries the force
            if (std::abs(H(o, 0)) > 0.3 * scale) {
                EXPECT_NEAR(std::abs(measured) / std::abs(H(o, 0)), 1.0, 0.01) << "f = " << f << ", output " << o;
                EXPECT_NEAR(std::arg(measured / H(o, 0)), 0.0, 0.01) << "f = " << f << ", output " << o;
            }
        }
        ++checked;
    }
    EXPECT_EQ(checked, 5);
}

TEST(FrequencyResponse, DampedPlantIsAHighPassWithTheMassLineAboveIt) {
    // M ddp + D dp = A_p^T tau: H(s) = s (M s + D)^-1 A_p^T, 0 at low frequency, M^-1 A_p^T above
    const Model model(dampedPaperRobot(150.0));
    Data data(model);
    StateSpace system;
    ASSERT_TRUE(linearize(model, data, model.home, Twist::Zero(), ActuatorVector::Zero(3),
                          LinearOutput::platform_acceleration, system)
                    .ok());
    const Eigen::MatrixXcd low = frequencyResponse(system, 1e-3), high = frequencyResponse(system, 1e5);
    EXPECT_LT(low.cwiseAbs().maxCoeff(), 1e-3 * high.cwiseAbs().maxCoeff());
    EXPECT_LT((high - system.D.cast<std::complex<double>>()).cwiseAbs().maxCoeff(),
              1e-3 * system.D.cwiseAbs().maxCoeff());
}

TEST(FrequencyResponse, PaperRobotPlantAtRestIsTheConstantMassLine) {
    // the rigid, frictionless, horizontal robot at rest: A = [0 I; 0 0], C = [0 0]: H = D =
    // M_p^-1 A_p^T at every frequency (docs/frequency-response.md), no -3 dB point
    const Model model(paperRobot());
    Data data(model);
    StateSpace system;
    ASSERT_TRUE(linearize(model, data, model.home, Twist::Zero(), ActuatorVector::Zero(3),
                          LinearOutput::platform_acceleration, system)
                    .ok());
    const FrequencyResponse r = frequencyResponse(system, logGrid(1.0, 1000.0, 31));
    for (int c = 0; c < 9; ++c) {
        EXPECT_LT(r.magnitude_db.col(c).maxCoeff() - r.magnitude_db.col(c).minCoeff(), 1e-9);
        EXPECT_TRUE(std::isnan(bandwidth3dB(r, c / 3, c % 3)));
    }
    // D = M_p^-1 A_p^T with M_p of the platform-coordinate dynamics (forward_dynamics.hpp)
    Data platform(model);
    ASSERT_TRUE(inverseDisplacement(model, platform, model.home).ok());
    ASSERT_TRUE(velocityFromPlatformTwist(model, platform, Twist::Zero()).ok());
    platformDynamics(model, platform);
    const Eigen::MatrixXd A_p = Eigen::MatrixXd(platform.A) * platformTwistMap(model.home.tail<2>());
    EXPECT_LT((system.D - platform.M_p.inverse() * A_p.transpose()).cwiseAbs().maxCoeff(),
              1e-12 * system.D.cwiseAbs().maxCoeff());
    // the numbers of the guide: |d2theta/dt2 / tau1| and |d2x/dt2 / tau1| at home
    EXPECT_NEAR(r.magnitude_db(0, 3 * 0 + 0), 6.2490, 5e-4);
    EXPECT_NEAR(r.magnitude_db(0, 3 * 1 + 0), -15.8739, 5e-4);
}

TEST(FrequencyResponse, ActuatorOutputIsTheActuationMatrix) {
    const Model model(paperRobot());
    Data data(model);
    StateSpace system;
    ASSERT_TRUE(linearize(model, data, model.home, Twist::Zero(), ActuatorVector::Zero(3),
                          LinearOutput::actuator_variables, system)
                    .ok());
    // u = u(p): a small pose step moves u by A_p dp
    Data probe(model);
    const Pose step(1e-6, -2e-6, 3e-6);
    ASSERT_TRUE(inverseDisplacement(model, probe, model.home + step).ok());
    const ActuatorVector u1 = probe.u;
    ASSERT_TRUE(inverseDisplacement(model, probe, model.home - step).ok());
    const Eigen::VectorXd du = (Eigen::VectorXd(u1) - Eigen::VectorXd(probe.u)) / 2.0;
    EXPECT_LT((system.C.leftCols<3>() * step - du).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_TRUE(system.D.isZero());
}

TEST(FrequencyResponse, GridAndBandwidthRejectBadInput) {
    EXPECT_THROW((void)logGrid(0.0, 10.0, 5), Error);
    EXPECT_THROW((void)logGrid(10.0, 1.0, 5), Error);
    EXPECT_THROW((void)logGrid(1.0, 10.0, 1), Error);
    const std::vector<double> grid = logGrid(1.0, 100.0, 3);
    EXPECT_NEAR(grid[1], 10.0, 1e-12);
    // a first-order low-pass 1 / (1 + s / w_c), w_c = 2 pi 10 Hz: -3.01 dB at 10 Hz
    StateSpace lowpass;
    const double wc = 2.0 * std::numbers::pi * 10.0;
    lowpass.A = Eigen::MatrixXd::Constant(1, 1, -wc);
    lowpass.B = Eigen::MatrixXd::Constant(1, 1, wc);
    lowpass.C = Eigen::MatrixXd::Constant(1, 1, 1.0);
    lowpass.D = Eigen::MatrixXd::Zero(1, 1);
    const FrequencyResponse r = frequencyResponse(lowpass, logGrid(0.01, 1000.0, 2001));
    // -3 dB (not -3.0103 dB) lies just below the corner: 1 + (f/10)^2 = 10^0.3
    EXPECT_NEAR(bandwidth3dB(r, 0, 0), 10.0 * std::sqrt(std::pow(10.0, 0.3) - 1.0), 1e-3);
    EXPECT_NEAR(r.phase_deg(2000, 0), -std::atan(100.0) * 180.0 / std::numbers::pi, 1e-9);
}

TEST(FrequencyResponse, BandwidthIsMeasuredFromTheLowFrequencyAsymptote) {
    // a double integrator behind a low-pass, y = w_c / (s^2 (s + w_c)): it falls at 40 dB/decade
    // from the start (a position per force); below w_c it is its asymptote, so its -3 dB point
    // is the low-pass's, not the grid's first step
    const double wc = 2.0 * std::numbers::pi * 10.0;
    StateSpace system;
    system.A = Eigen::MatrixXd::Zero(3, 3);
    system.A(0, 1) = 1.0;
    system.A(1, 2) = 1.0;
    system.A(2, 2) = -wc;
    system.B = Eigen::MatrixXd::Zero(3, 1);
    system.B(2, 0) = wc;
    system.C = Eigen::MatrixXd::Zero(1, 3);
    system.C(0, 0) = 1.0;
    system.D = Eigen::MatrixXd::Zero(1, 1);
    const FrequencyResponse r = frequencyResponse(system, logGrid(0.01, 1000.0, 2001));
    EXPECT_NEAR(lowFrequencySlope(r, 0, 0), -2.0, 1e-3);
    EXPECT_NEAR(bandwidth3dB(r, 0, 0), 10.0 * std::sqrt(std::pow(10.0, 0.3) - 1.0), 1e-3);
    // a phase of exactly 180 deg reads 180 whichever sign the rounding gives: -1 + (-0) j
    EXPECT_EQ(anchoredPhase(std::arg(std::complex<double>(-1.0, -0.0)) * 180.0 / std::numbers::pi), 180.0);
    EXPECT_EQ(anchoredPhase(-90.0), -90.0);
    // the double integrator's -180 deg at the first frequency reads 180, continuous after
    EXPECT_NEAR(r.phase_deg(0, 0), 180.0 - std::atan(0.001) * 180.0 / std::numbers::pi, 1e-6);
    EXPECT_NEAR(r.phase_deg(2000, 0), 180.0 - std::atan(100.0) * 180.0 / std::numbers::pi, 1e-6);
}

}  // namespace
}  // namespace nocdyn::test
