// The shake-table loop linearised (sim/closed_loop.hpp) against the loop itself run in time on
// nocdyn's own plant.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "nocdyn/analysis/linearization.hpp"
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

struct Case {
    const char* name;
    double payload;  // [kg] on the plant, unknown to the controller
};

TEST(ShakeLoopResponse, Explore) {
    const Model model(paperRobot());
    for (const double payload : {0.0, 2.0, 5.0}) {
        const Model plant_model(withPayload(paperRobot(), Payload{payload, 0.0, Vector2::Zero()}));
        const ShakeLoopOptions options;
        const ShakeLoopLinearization loop = linearizeShakeLoop(model, plant_model, model.home, options);
        const ShakeLoopFrequencyResponse r = shakeLoopFrequencyResponse(loop, logGrid(0.1, 4000.0, 400));
        std::printf("payload %g: bw %g %g %g  fc %g %g %g  pm %g %g %g\n", payload, r.bandwidth(0), r.bandwidth(1),
                    r.bandwidth(2), r.crossover(0), r.crossover(1), r.crossover(2), r.phase_margin(0),
                    r.phase_margin(1), r.phase_margin(2));
        for (const double f : {2.0, 10.0, 50.0, 250.0, 1000.0}) {
            const std::complex<double> h = shakeLoopResponse(loop, f).closed_loop(1, 1);
            const std::complex<double> m = measuredResponse(model, plant_model, options, 1, f, 0.2, 0.3);
            std::printf("  f %g  lin %.5f %.3f  sim %.5f %.3f\n", f, std::abs(h), std::arg(h) * 180 / M_PI, std::abs(m),
                        std::arg(m) * 180 / M_PI);
        }
    }
}

}  // namespace
}  // namespace nocdyn::test
