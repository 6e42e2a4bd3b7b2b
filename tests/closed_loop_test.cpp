// The shake-table loop linearised (sim/closed_loop.hpp) against the loop itself run in time on
// nocdyn's own plant.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/closed_loop.hpp"
#include "nocdyn/sim/shake.hpp"

namespace nocdyn::test {
namespace {

RobotDescription paperRobot() {
    return io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr.yaml");
}

/// A plant that records its pose rate at every tick (the loop's achieved acceleration is its
/// difference over a tick).
class RecordingPlant final : public RobotPlant {
public:
    explicit RecordingPlant(RobotPlant& plant) : plant_(plant) {}
    void reset(const Pose& p, const Twist& dp) override {
        plant_.reset(p, dp);
        rates.assign(1, dp);
    }
    void setForces(const ActuatorVector& tau) override { plant_.setForces(tau); }
    void advance(double dt) override {
        plant_.advance(dt);
        rates.push_back(plant_.poseRate());
    }
    [[nodiscard]] Pose pose() const override { return plant_.pose(); }
    [[nodiscard]] Twist poseRate() const override { return plant_.poseRate(); }
    [[nodiscard]] ActuatorVector u() const override { return plant_.u(); }
    [[nodiscard]] std::string name() const override { return plant_.name(); }
    std::vector<Twist> rates;

private:
    RobotPlant& plant_;
};

/// The measured H_ii at f: the shake loop on the RK4 plant of `plant_model`, the reference a
/// sine of acceleration amplitude `amplitude` on axis i about home, the fundamental of the
/// achieved mean acceleration per tick over that of the reference's, over whole periods after
/// `settle` seconds.
std::complex<double> measuredResponse(const Model& model, const Model& plant_model, const ShakeLoopOptions& base,
                                      int axis, double f, double amplitude, double settle) {
    const double w = 2.0 * std::numbers::pi * f;
    PoseTrajectory trajectory;
    AxisMotion* axes[3] = {&trajectory.theta, &trajectory.x, &trajectory.y};
    for (int i = 0; i < 3; ++i) axes[i]->offset = model.home(i);
    axes[axis]->harmonics.push_back({amplitude / (w * w), f, 0.0});
    const double periods = std::max(4.0, std::ceil(0.5 * f));
    ShakeLoopOptions options = base;
    options.duration = settle + periods / f;
    RungeKuttaRobotPlant rk4(plant_model);
    RecordingPlant plant(rk4);
    const PoseLoopResult result = runShakeLoop(model, plant, trajectory, options);
    const double T = 1.0 / options.rate;
    std::complex<double> achieved = 0.0, reference = 0.0;
    Pose p, dp0, dp1, ddp;
    for (std::size_t k = 0; k + 1 < plant.rates.size() && k < result.t.size(); ++k) {
        const double t = result.t[k];
        if (t < settle - 0.5 * T) continue;
        const std::complex<double> e = std::exp(std::complex<double>(0.0, -w * t));
        achieved += (plant.rates[k + 1](axis) - plant.rates[k](axis)) / T * e;
        trajectory.evaluate(t, p, dp0, ddp);
        trajectory.evaluate(t + T, p, dp1, ddp);
        reference += (dp1(axis) - dp0(axis)) / T * e;
    }
    return achieved / reference;
}

/// The loop at home with the default controller and sensors (their noise included in the run),
/// the plant carrying `payload` kg at C unknown to the controller.
void expectAgreementAtFiveFrequencies(double payload) {
    const Model model(paperRobot());
    const Model plant_model(withPayload(paperRobot(), Payload{payload, 0.0, Vector2::Zero()}));
    const ShakeLoopOptions options;
    const ShakeLoopLinearization loop = linearizeShakeLoop(model, plant_model, model.home, options);
    const double amplitude[3] = {2.0, 0.2, 0.2};  // [rad/s^2, m/s^2, m/s^2]
    for (int axis = 0; axis < 3; ++axis) {
        for (const double f : {2.0, 10.0, 50.0, 250.0, 1000.0}) {
            const std::complex<double> h = shakeLoopResponse(loop, f).closed_loop(axis, axis);
            const std::complex<double> m = measuredResponse(model, plant_model, options, axis, f, amplitude[axis], 0.3);
            // the complex error bounds both: 1 % in amplitude, 0.57 deg in phase
            EXPECT_LT(std::abs(m - h) / std::abs(h), 0.01)
                << "payload " << payload << " kg, axis " << axis << ", " << f << " Hz: linear " << std::abs(h) << " "
                << std::arg(h) << ", simulated " << std::abs(m) << " " << std::arg(m);
        }
    }
}

TEST(ShakeLoopResponse, AgreesWithTheSimulatedLoopToOnePercentAtFiveFrequencies) {
    expectAgreementAtFiveFrequencies(0.0);
}

TEST(ShakeLoopResponse, AgreesWithTheSimulatedLoopWithAnUnknownPayload) { expectAgreementAtFiveFrequencies(5.0); }

// docs/frequency-response.md: the paper's robot under the default shake controller
TEST(ShakeLoopResponse, PaperRobotBandwidthAndPhaseMarginAreTheGuides) {
    const Model model(paperRobot());
    const ShakeLoopOptions options;
    const std::vector<double> grid = logGrid(0.1, 4000.0, 400);
    const ShakeLoopFrequencyResponse nominal =
        shakeLoopFrequencyResponse(linearizeShakeLoop(model, model, model.home, options), grid);
    for (int i = 0; i < 3; ++i) {
        EXPECT_TRUE(std::isnan(nominal.bandwidth(i)));  // no -3 dB point below 4 kHz
        EXPECT_NEAR(nominal.crossover(i), 12.45, 0.01);
        EXPECT_NEAR(nominal.phase_margin(i), 76.0, 0.05);
        // within 0.1 dB of the reference over the whole grid, peaking near 50 Hz
        EXPECT_LT(nominal.magnitude_db.col(i).cwiseAbs().maxCoeff(), 0.1);
    }
    const Model plant_model(withPayload(paperRobot(), Payload{5.0, 0.0, Vector2::Zero()}));
    const ShakeLoopFrequencyResponse loaded =
        shakeLoopFrequencyResponse(linearizeShakeLoop(model, plant_model, model.home, options), grid);
    EXPECT_TRUE(std::isnan(loaded.bandwidth(0)));  // a point mass at C leaves the rotation alone
    for (int i = 1; i < 3; ++i) {
        EXPECT_NEAR(loaded.bandwidth(i), 10.56, 0.01);
        EXPECT_NEAR(loaded.crossover(i), 7.22, 0.01);
        EXPECT_NEAR(loaded.phase_margin(i), 67.3, 0.05);
        EXPECT_NEAR(loaded.magnitude_db(loaded.magnitude_db.rows() - 1, i), -5.15, 0.01);
    }
}

TEST(ShakeLoopResponse, RejectsFrequenciesOutsideTheNyquistBand) {
    const Model model(paperRobot());
    const ShakeLoopLinearization loop = linearizeShakeLoop(model, model, model.home, ShakeLoopOptions{});
    EXPECT_THROW((void)shakeLoopResponse(loop, 5000.0), Error);
    EXPECT_THROW((void)shakeLoopResponse(loop, 0.0), Error);
}

}  // namespace
}  // namespace nocdyn::test
