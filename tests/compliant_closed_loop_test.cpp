// The shake-table loop on the lumped compliant plant (sim/closed_loop.hpp, LoopPlant::lumped)
// against the same loop on the rigid plant: equal at low frequency (static gain 1), apart at the
// first resonance (41.04 Hz on the compliant 3-PRR), the rigid loop as the compliance stiffens;
// its usable band within the amplification limit; and the command's summary of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "app/frequency_response.hpp"
#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/closed_loop.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::test {
namespace {

const std::string kCompliantFile = std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr-compliant.yaml";

/// The axes x, y, theta as indices of the core's pose [theta, x, y].
constexpr int kAxes[3] = {1, 2, 0};
constexpr double kFirstResonance = 41.0384;  // [Hz], the lumped model at home (stiffness.md)

RobotDescription compliantRobot() { return io::loadRobotDescription(kCompliantFile); }

/// Every drive stiffness and link rigidity times `factor`.
RobotDescription stiffened(RobotDescription robot, double factor) {
    for (LimbDescription& limb : robot.limbs) {
        for (JointDescription& joint : limb.joints) {
            if (joint.stiffness) *joint.stiffness *= factor;
        }
        for (BodyDescription& body : limb.bodies) {
            if (body.elastic) {
                body.elastic->EA *= factor;
                body.elastic->EI *= factor;
            }
        }
    }
    return robot;
}

/// The pose feedback's f_n [Hz] the compliant robot's loop is stable with: the default 6 Hz
/// (and down to about 0.9 Hz) drives the lightly damped (2 %) resonance unstable.
constexpr double kStableNaturalFrequency = 0.5;

ShakeLoopLinearization loopOf(const Model& model, LoopPlant plant, double natural_frequency = kStableNaturalFrequency) {
    ShakeLoopOptions options;
    options.natural_frequency = natural_frequency;
    return linearizeShakeLoop(model, model, model.home, options, LoopDerivatives::exact, 1e-6, plant);
}

/// The largest |H_ii(lumped) - H_ii(rigid)| over the axes and the frequencies.
double largestDifference(const ShakeLoopLinearization& lumped, const ShakeLoopLinearization& rigid,
                         const std::vector<double>& frequencies) {
    double worst = 0.0;
    for (const double f : frequencies) {
        const Eigen::Matrix3cd a = shakeLoopResponse(lumped, f).closed_loop;
        const Eigen::Matrix3cd b = shakeLoopResponse(rigid, f).closed_loop;
        for (const int i : kAxes) worst = std::max(worst, std::abs(a(i, i) - b(i, i)));
    }
    return worst;
}

TEST(CompliantClosedLoop, DefaultFeedbackDrivesTheResonanceUnstableASlowOneIsStable) {
    const Model model(compliantRobot());
    // f_n = 6 Hz: the velocity feedback through the 2 %-damped mode between the drives' set
    // points and the platform (non-collocated: -180 deg at the mode) returns more than it gets
    const double fast = shakeLoopSpectralRadius(loopOf(model, LoopPlant::lumped, 6.0));
    EXPECT_GT(fast, 1.001);
    EXPECT_LT(fast, 1.01);
    EXPECT_LT(shakeLoopSpectralRadius(loopOf(model, LoopPlant::rigid, 6.0)), 1.0);
    const ShakeLoopLinearization lumped = loopOf(model, LoopPlant::lumped);
    const ShakeLoopLinearization rigid = loopOf(model, LoopPlant::rigid);
    EXPECT_EQ(lumped.plant_states, 12);
    EXPECT_EQ(lumped.F.rows(), 30);
    EXPECT_EQ(rigid.F.rows(), 24);
    const double radius = shakeLoopSpectralRadius(lumped);
    EXPECT_LT(radius, 1.0);
    // the modes stay lightly damped: their eigenvalues closer to the circle than the rigid
    // loop's slowest
    EXPECT_GT(radius, shakeLoopSpectralRadius(rigid));
}

TEST(CompliantClosedLoop, MatchesTheRigidLoopAtLowFrequencyWithStaticGainOne) {
    const Model model(compliantRobot());
    const ShakeLoopLinearization lumped = loopOf(model, LoopPlant::lumped);
    const ShakeLoopLinearization rigid = loopOf(model, LoopPlant::rigid);
    for (const double f : {0.01, 0.1, 1.0}) {
        const Eigen::Matrix3cd h = shakeLoopResponse(lumped, f).closed_loop;
        for (const int i : kAxes) {
            EXPECT_NEAR(std::abs(h(i, i)), 1.0, 1e-3) << "axis " << i << " at " << f << " Hz";
            EXPECT_NEAR(std::arg(h(i, i)), 0.0, 1e-3) << "axis " << i << " at " << f << " Hz";
        }
    }
    // below the resonance the two differ by about the amplification 1/(1 - (f/f_1)^2) - 1
    EXPECT_LT(largestDifference(lumped, rigid, {0.01, 0.1}), 1e-5);
    EXPECT_LT(largestDifference(lumped, rigid, {1.0}), 2e-3);
}

TEST(CompliantClosedLoop, ShowsTheResonanceNearFortyOneHertz) {
    const Model model(compliantRobot());
    const ShakeLoopLinearization lumped = loopOf(model, LoopPlant::lumped);
    const ShakeLoopLinearization rigid = loopOf(model, LoopPlant::rigid);
    const ShakeLoopFrequencyResponse r = shakeLoopFrequencyResponse(lumped, logGrid(1.0, 1000.0, 600));
    const ShakeLoopFrequencyResponse flat = shakeLoopFrequencyResponse(rigid, logGrid(1.0, 1000.0, 600));
    const ShakeLoopBand band = shakeLoopBand(lumped, r, 1.1);
    const ShakeLoopBand rigid_band = shakeLoopBand(rigid, flat, 1.1);
    for (const int i : {1, 2}) {  // x, y: the translation modes at 41.04 Hz
        // the closed loop peaks within 5 % of the first resonance, by more than 20 dB
        EXPECT_NEAR(band.peak_frequency(i), kFirstResonance, 0.05 * kFirstResonance) << "axis " << i;
        EXPECT_GT(band.peak_db(i), 20.0) << "axis " << i;
        // the rigid loop stays within 0.1 dB of the reference there
        EXPECT_LT(std::abs(rigid_band.peak_db(i)), 0.1) << "axis " << i;
        const std::complex<double> h = shakeLoopResponse(lumped, kFirstResonance).closed_loop(i, i);
        const std::complex<double> g = shakeLoopResponse(rigid, kFirstResonance).closed_loop(i, i);
        EXPECT_GT(std::abs(h - g), 5.0) << "axis " << i;
    }
    // theta: the rotation's mode, 45.23 Hz
    EXPECT_NEAR(band.peak_frequency(0), 45.2333, 0.05 * 45.2333);
    EXPECT_GT(band.peak_db(0), 20.0);
}

TEST(CompliantClosedLoop, UsableBandHasNoFrequencyAmplifiedBeyondTheLimit) {
    const Model model(compliantRobot());
    const ShakeLoopLinearization lumped = loopOf(model, LoopPlant::lumped);
    for (const double limit : {1.1, 1.5}) {
        const ShakeLoopFrequencyResponse r = shakeLoopFrequencyResponse(lumped, logGrid(0.1, 1000.0, 400));
        const ShakeLoopBand band = shakeLoopBand(lumped, r, limit);
        for (const int i : kAxes) {
            const double end = band.end(i);
            ASSERT_TRUE(std::isfinite(end) && end > 0.1 && end < kFirstResonance * 1.2) << "axis " << i;
            // densely from the grid's start to the band's end: within [1/A, A]
            // (the end is found to the response's rounding, 1e-9 relative at most)
            for (const double f : logGrid(0.1, end, 2000)) {
                const double gain = std::abs(shakeLoopResponse(lumped, f).closed_loop(i, i));
                ASSERT_LE(gain, limit * (1.0 + 1e-9)) << "axis " << i << " at " << f << " Hz";
                ASSERT_GE(gain, 1.0 / limit / (1.0 + 1e-9)) << "axis " << i << " at " << f << " Hz";
            }
            // and just past the end, outside
            const double past = std::abs(shakeLoopResponse(lumped, end * (1.0 + 1e-6)).closed_loop(i, i));
            EXPECT_TRUE(past > limit || past < 1.0 / limit) << "axis " << i << ": " << past;
        }
    }
}

TEST(CompliantClosedLoop, TendsToTheRigidLoopAsTheCompliancesStiffen) {
    // H(w) = 1 / (1 - r^2 + 2 j zeta r), r = f / f_1: the lumped loop differs from the rigid one
    // by about 2 zeta r + r^2 below the first mode, and f_1 grows as the square root of the
    // stiffness (measured, below 200 Hz: 0.318, 2.19e-3, 6.1e-4 at 1e2, 1e4, 1e6 times the
    // file's stiffness; at 1e6, f_1 = 41 kHz lies beyond the tick's Nyquist frequency)
    const std::vector<double> grid = logGrid(0.5, 200.0, 40);
    std::vector<double> differences;
    for (const double factor : {1e2, 1e4, 1e6}) {
        // the default f_n = 6 Hz: stable once the first mode is 10 times higher
        const Model model(stiffened(compliantRobot(), factor));
        differences.push_back(
            largestDifference(loopOf(model, LoopPlant::lumped, 6.0), loopOf(model, LoopPlant::rigid, 6.0), grid));
        const double r = 200.0 / (kFirstResonance * std::sqrt(factor));
        // within twice the single mode's 2 zeta r + r^2 while f_1 is below the Nyquist frequency
        if (factor < 1e5) {
            EXPECT_LT(differences.back(), 2.0 * (2.0 * 0.02 * r + r * r)) << "stiffness x " << factor;
        }
    }
    EXPECT_GT(differences[0], 0.1);  // f_1 = 410 Hz: still felt at 200 Hz
    EXPECT_LT(differences[1], differences[0] / 100.0);
    EXPECT_LT(differences[2], differences[1] / 3.0);
    EXPECT_LT(differences[2], 1e-3);
}

TEST(CompliantClosedLoop, ForceDrivesLeaveTheLumpedLoopRigid) {
    // with every drive a force actuator (stiffness 0) and rigid links the lumped model is the
    // rigid one (K = 0, B = the rigid B): the loops agree to rounding
    RobotDescription robot = compliantRobot();
    for (LimbDescription& limb : robot.limbs) {
        limb.joints[0].stiffness = 0.0;
        for (BodyDescription& body : limb.bodies) body.elastic.reset();
    }
    robot.limbs[0].joints[1].stiffness = 1e-9;  // keeps compliance declared, carries next to no load
    const Model model(robot);
    const ShakeLoopLinearization lumped = loopOf(model, LoopPlant::lumped);
    EXPECT_EQ(lumped.plant_states, 6);
    EXPECT_LT(largestDifference(lumped, loopOf(model, LoopPlant::rigid), {1.0, 41.0, 1000.0}), 1e-6);
}

TEST(CompliantClosedLoop, LumpedPlantNeedsCompliance) {
    const Model model(io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr.yaml"));
    EXPECT_THROW((void)loopOf(model, LoopPlant::lumped), Error);
    EXPECT_THROW((void)linearizeShakeLoop(model, model, model.home, ShakeLoopOptions{},
                                          LoopDerivatives::central_difference, 1e-6, LoopPlant::lumped),
                 Error);
}

TEST(CompliantClosedLoop, TheCommandsSummaryGivesTheBandPerAxis) {
    app::FrequencyResponseOptions options;
    options.robot.path = kCompliantFile;
    options.closed_loop = true;
    options.min_frequency = 0.1;
    options.max_frequency = 1000.0;
    options.points = 400;
    app::Observer& observer = app::silent();
    // the default f_n: refused, naming the radius and the plant
    try {
        (void)app::runFrequencyResponse(options, observer);
        ADD_FAILURE() << "an unstable loop was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("unstable closed loop"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("lumped compliant plant"), std::string::npos) << e.what();
    }
    options.natural_frequency = kStableNaturalFrequency;
    const app::FrequencyResponseResult r = app::runFrequencyResponse(options, observer);
    EXPECT_TRUE(r.lumped);
    EXPECT_NE(r.summary.find("# plant: the lumped compliant model"), std::string::npos) << r.summary;
    EXPECT_NE(r.summary.find("# H: the closed loop"), std::string::npos) << r.summary;
    ASSERT_EQ(r.band_end.size(), 3U);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_GT(r.band_end[k], 5.0);
        EXPECT_LT(r.band_end[k], kFirstResonance);
        EXPECT_NE(r.summary.find(text::format("%.4f", r.band_end[k])), std::string::npos) << r.summary;
    }
    // --compliance rigid: the rigid loop, said so, flat within the limit over the grid
    options.compliance = app::PlantCompliance::rigid;
    const app::FrequencyResponseResult rigid = app::runFrequencyResponse(options, observer);
    EXPECT_FALSE(rigid.lumped);
    EXPECT_NE(rigid.summary.find("# rigid plant"), std::string::npos);
    for (const double end : rigid.band_end) EXPECT_TRUE(std::isnan(end));
    EXPECT_NE(rigid.summary.find("band  x  beyond the grid"), std::string::npos) << rigid.summary;
}

}  // namespace
}  // namespace nocdyn::test
