// The standard deviations identification reports hold: over independent noise draws of the same
// experiment, the spread of each estimate matches the mean reported standard deviation. The
// experiment is the one docs/identification.md runs (the paper's robot along trajectory 1 by
// computed torque at 10 kHz, f_n = 50 Hz, a payload the controller does not know, encoder noise
// 1e-6 m and force noise 0.5 N, u and tau low-pass filtered at 50 Hz), and the same on the 3-RRR
// for its base parameters. The filtered residuals are correlated over about 120 samples: counted
// as independent samples they gave standard deviations about ten times too small.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/excitation.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/sim/plant.hpp"
#include "nocdyn/sim/shake.hpp"
#include "random_robots.hpp"

namespace nocdyn {
namespace {

/// Noise draws per experiment, and the factor within which the spread (sample standard
/// deviation over the draws) and the mean reported standard deviation must agree. With 20 draws
/// the sample standard deviation itself scatters by 1 / sqrt(2 * 19) = 16 %: 1.5 is 2.5 of that.
constexpr int kSeeds = 20;
constexpr double kFactor = 1.5;
/// Seconds of the experiment: docs/identification.md runs 5 s; 2 s keeps the test short and
/// changes nothing in what is checked (both the spread and the reported value scale alike).
constexpr double kDuration = 2.0;

struct Spread {
    std::vector<double> values, reported;
    void add(double value, double sd) {
        values.push_back(value);
        reported.push_back(sd);
    }
    [[nodiscard]] double mean() const {
        double s = 0.0;
        for (const double v : values) s += v;
        return s / static_cast<double>(values.size());
    }
    [[nodiscard]] double spread() const {
        const double m = mean();
        double s = 0.0;
        for (const double v : values) s += (v - m) * (v - m);
        return std::sqrt(s / static_cast<double>(values.size() - 1));
    }
    [[nodiscard]] double meanReported() const {
        double s = 0.0;
        for (const double v : reported) s += v;
        return s / static_cast<double>(reported.size());
    }
};

void expectSpreadMatchesReported(const Spread& s, const std::string& what) {
    const double ratio = s.spread() / s.meanReported();
    EXPECT_GT(ratio, 1.0 / kFactor) << what << ": spread " << s.spread() << ", reported " << s.meanReported();
    EXPECT_LT(ratio, kFactor) << what << ": spread " << s.spread() << ", reported " << s.meanReported();
    std::printf("%-44s mean %.6g  spread %.3g  reported %.3g  ratio %.2f\n", what.c_str(), s.mean(), s.spread(),
                s.meanReported(), ratio);
}

PoseLoopResult experiment(const RobotDescription& robot, const RobotDescription& plant_robot,
                          const PoseTrajectory& trajectory) {
    const Model model(robot);
    SimulatorRobotPlant plant{Model(plant_robot)};
    PoseController controller(model, ControlLaw::computed_torque, taskCriticallyDamped(50.0));
    PoseLoopOptions loop;
    loop.duration = kDuration;
    loop.rate = 10000.0;
    return runPoseLoop(controller, plant, trajectory, loop);
}

TEST(IdentificationUncertainty, PayloadSpreadOverNoiseDrawsMatchesTheReportedStandardDeviation) {
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    const Model model(robot);
    const Payload payload{0.5, 8e-4, Vector2(0.012, -0.007)};
    const PoseLoopResult run = experiment(robot, withPayload(robot, payload), io::trajectoryByNameOrFile("paper1"));
    Spread mass, com_x, com_y, inertia;
    IdentificationOptions options;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const Measurements log = sensorLog(run, 1e-6, 0.5, static_cast<unsigned>(seed));
        const PayloadResult r = identifyPayload(model, reconstructMotion(model, log, options), options);
        mass.add(r.mass, r.mass_sd);
        com_x.add(r.com.x(), r.com_sd.x());
        com_y.add(r.com.y(), r.com_sd.y());
        inertia.add(r.inertia, r.inertia_sd);
        // the covariance's diagonal is the standard deviations reported
        ASSERT_EQ(r.covariance.rows(), 4);
        EXPECT_DOUBLE_EQ(std::sqrt(r.covariance(0, 0)), r.mass_sd);
        EXPECT_DOUBLE_EQ(std::sqrt(r.covariance(3, 3)), r.inertia_sd);
        // the residuals of a log filtered at 50 Hz and sampled at 10 kHz: the force noise's part
        // correlated over f_s / (2 * 0.83 f_c) = 120 samples, the encoder noise's part
        // (differentiated twice: no power at low frequency) over a few; measured 55 to 60
        EXPECT_GT(r.fit.correlation_samples, 20.0);
        EXPECT_LT(r.fit.correlation_samples, 240.0);
    }
    expectSpreadMatchesReported(mass, "payload mass [kg]");
    expectSpreadMatchesReported(com_x, "payload c.o.m. x [m]");
    expectSpreadMatchesReported(com_y, "payload c.o.m. y [m]");
    expectSpreadMatchesReported(inertia, "payload inertia [kg m^2]");
    // and the mean is within three standard errors of the truth (no bias beyond the noise's)
    const double n = std::sqrt(static_cast<double>(kSeeds));
    EXPECT_NEAR(mass.mean(), payload.mass, 3.0 * mass.spread() / n + 1e-4 * payload.mass);
    EXPECT_NEAR(inertia.mean(), payload.inertia, 3.0 * inertia.spread() / n + 1e-3 * payload.inertia);
}

TEST(IdentificationUncertainty, BaseParameterSpreadOnThe3RrrMatchesTheReportedStandardDeviation) {
    const RobotDescription robot = io::exampleRobot("3-rrr");
    const Model model(robot);
    std::mt19937 rng(5);
    const PoseLoopResult run = experiment(robot, robot, test::trajectoryAround(model.home, rng));
    std::vector<Spread> beta;
    std::vector<std::string> names;
    IdentificationOptions options;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        const Measurements log = sensorLog(run, 1e-6, 0.05, static_cast<unsigned>(seed));
        const BaseResult r = identifyBase(model, reconstructMotion(model, log, options), options);
        beta.resize(r.beta.size());
        for (std::size_t i = 0; i < r.beta.size(); ++i) {
            beta[i].add(r.beta[i].value, r.beta[i].stddev);
            if (names.size() < r.beta.size()) names.push_back(r.beta[i].name);
        }
        ASSERT_EQ(r.covariance.rows(), static_cast<Eigen::Index>(r.beta.size()));
    }
    ASSERT_FALSE(beta.empty());
    for (std::size_t i = 0; i < beta.size(); ++i) expectSpreadMatchesReported(beta[i], names[i]);
}

}  // namespace
}  // namespace nocdyn
