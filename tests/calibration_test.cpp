// Calibration and the physically consistent payload (identification.hpp, io/calibration.hpp):
// exact data recover the base parameters; a payload identified against the calibrated robot is
// exact where the robot file's own parameters are wrong; a calibration file round-trips and a
// foreign one is refused; a negative inertia falls back to the best fit with none.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <utility>
#include <string>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/tables/calibration.hpp"
#include "nocdyn/io/examples.hpp"
#include "random_robots.hpp"
#include "identification_support.hpp"

namespace nocdyn::test {
namespace {

constexpr double kExact = 1e-9;

/// The robot as built: heavier links, a platform c.o.m. off its centre, friction and damping at
/// the sliders, none of which the file knows.
RobotDescription asBuilt(RobotDescription robot) {
    robot.platform.mass *= 1.04;
    robot.platform.com = Vector2(0.002, -0.001);
    for (LimbDescription& limb : robot.limbs) {
        limb.bodies[1].mass *= 1.1;
        limb.bodies[1].inertia *= 0.9;
        for (JointDescription& joint : limb.joints) {
            if (joint.actuated) {
                joint.damping = 6.0;
                joint.friction = 2.0;
            }
        }
    }
    return robot;
}

struct Calibrated {
    RobotDescription file = io::exampleRobot("paper-3prr-general");
    RobotDescription built = asBuilt(file);
    Model nominal{file};
    BaseResult base;
    Calibrated() {
        std::mt19937 rng(17);
        const Model robot(built);
        base = identifyBase(nominal, exactMotion(robot, trajectoryAround(nominal.home, rng), 300, 0.004));
    }
};

const Calibrated& calibrated() {
    static const Calibrated c;
    return c;
}

TEST(Calibration, ExactDataRecoverTheBaseParametersOfTheRobotAsBuilt) {
    const Calibrated& c = calibrated();
    const Model built(c.built);
    const BaseParameters base = baseParameters(c.nominal);
    ASSERT_EQ(c.base.calibration.independent, base.independent);
    const Eigen::VectorXd truth = base.K * standardParameters(built);
    const Eigen::VectorXd file = base.K * standardParameters(c.nominal);
    ASSERT_EQ(c.base.calibration.beta.size(), truth.size());
    for (Eigen::Index k = 0; k < truth.size(); ++k) {
        const double scale = std::max(std::abs(truth(k)), 1e-3 * truth.cwiseAbs().maxCoeff());
        EXPECT_NEAR(c.base.calibration.beta(k), truth(k), kExact * scale)
            << c.base.beta[static_cast<std::size_t>(k)].name;
        EXPECT_EQ(c.base.beta[static_cast<std::size_t>(k)].prior, file(k));
    }
    // the robot as built differs from its file by more than the recovery error
    EXPECT_GT((truth - file).cwiseAbs().maxCoeff(), 1.0);
    EXPECT_LE(c.base.fit.rms_holdout[0], 1e-9 * c.base.fit.rms_measured[0]);
}

TEST(Calibration, APayloadAgainstTheCalibratedRobotIsExactWhereTheFileIsWrong) {
    const Calibrated& c = calibrated();
    const Payload payload{0.5, 8e-4, Vector2(0.012, -0.007)};
    const Model loaded(withPayload(c.built, payload));
    std::mt19937 rng(23);
    const Motion motion = exactMotion(loaded, trajectoryAround(c.nominal.home, rng), 200, 0.005);
    IdentificationOptions options;
    options.calibration = c.base.calibration;
    const PayloadResult r = identifyPayload(c.nominal, motion, options);
    EXPECT_NEAR(r.mass, payload.mass, kExact * payload.mass);
    EXPECT_NEAR(r.com.x(), payload.com.x(), kExact * 0.012);
    EXPECT_NEAR(r.com.y(), payload.com.y(), kExact * 0.012);
    EXPECT_NEAR(r.inertia, payload.inertia, kExact * payload.inertia);
    // against the file's own parameters the same data give a wrong mass (the platform's 4 %)
    const PayloadResult uncalibrated = identifyPayload(c.nominal, motion);
    EXPECT_GT(std::abs(uncalibrated.mass - payload.mass), 0.05 * payload.mass);
}

TEST(Calibration, TheFileRoundTripsAndAForeignOneIsRefused) {
    const Calibrated& c = calibrated();
    const std::string text = tables::calibrationToYaml(c.nominal, c.base, "# test\n");
    const Calibration back = tables::parseCalibration(text, "cal.yaml", c.nominal);
    EXPECT_EQ(back.independent, c.base.calibration.independent);
    EXPECT_EQ(back.beta, c.base.calibration.beta);  // round-trip precision
    // made for the 3-RRR: its parameter names exist there but not its base columns
    const Model rrr(io::exampleRobot("3-rrr"));
    try {
        (void)tables::parseCalibration("base_parameters:\n  - {parameter: 'limb9.body1.m', value: 1}\n", "bad.yaml",
                                       c.nominal);
        FAIL() << "unknown parameter accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.yaml:2"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("limb9.body1.m"), std::string::npos) << e.what();
    }
    IdentificationOptions options;
    options.calibration = Calibration{{bodyParameterIndex(rrr.platformBody())}, Eigen::VectorXd::Ones(1)};
    std::mt19937 rng(5);
    const Motion motion = exactMotion(c.nominal, trajectoryAround(c.nominal.home, rng), 60, 0.005);
    try {
        (void)identifyPayload(c.nominal, motion, options);
        FAIL() << "foreign calibration accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("not made for this robot"), std::string::npos) << e.what();
    }
    options.calibration = c.base.calibration;
    options.friction = true;
    EXPECT_THROW((void)identifyPayload(c.nominal, motion, options), Error);
}

TEST(PhysicalConsistency, ANegativeInertiaFallsBackToTheBestFitWithNone) {
    // the "payload" the data hold has 0.5 kg at C but takes 2e-4 kg m^2 away from the platform
    const RobotDescription file = io::exampleRobot("paper-3prr-general");
    RobotDescription plant = file;
    plant.platform.mass += 0.5;
    plant.platform.inertia -= 2e-4;
    const Model nominal(file), model(plant);
    std::mt19937 rng(9);
    const PoseTrajectory trajectory = trajectoryAround(nominal.home, rng);
    const Motion motion = exactMotion(model, trajectory, 200, 0.005);
    const PayloadResult r = identifyPayload(nominal, motion);
    EXPECT_TRUE(r.inertia_constrained);
    EXPECT_NEAR(r.inertia_unconstrained, -2e-4, kExact * 2e-4);
    EXPECT_EQ(r.inertia, 0.0);
    EXPECT_GT(r.mass, 0.0);
    // the constrained fit beats the naive one (the mass and c.o.m. kept, the inertia clipped)
    const Model clipped(withPayload(file, Payload{0.5, 0.0, Vector2::Zero()}));
    const Motion naive = exactMotion(clipped, trajectory, 200, 0.005);
    double fit = 0.0, clip = 0.0;
    for (int a = 0; a < 3; ++a)
        fit += r.fit.rms_fit[static_cast<std::size_t>(a)] * r.fit.rms_fit[static_cast<std::size_t>(a)];
    const auto rows = static_cast<Eigen::Index>(r.fit.fit_samples);
    clip = (naive.tau.topRows(rows) - motion.tau.topRows(rows)).squaredNorm() / static_cast<double>(rows);
    EXPECT_GT(fit, 0.0);
    EXPECT_LT(fit, clip);
}

TEST(PriorFile, ReadsBoundsWithOpenSidesAndLeavesAbsentOnesOpen) {
    const PayloadPrior prior = tables::parsePayloadPrior(
        "# bounds\npayload:\n  mass: [0.4, 0.6]\n  com_x: [-0.02, ~]\n  inertia: [0, 2e-3]\n", "prior.yaml");
    EXPECT_EQ(prior.mass.lower, 0.4);
    EXPECT_EQ(prior.mass.upper, 0.6);
    EXPECT_EQ(prior.com_x.lower, -0.02);
    EXPECT_EQ(prior.com_x.upper, std::numeric_limits<double>::infinity());
    EXPECT_EQ(prior.com_y.lower, -std::numeric_limits<double>::infinity());
    EXPECT_EQ(prior.com_y.upper, std::numeric_limits<double>::infinity());
    EXPECT_EQ(prior.inertia.lower, 0.0);
    EXPECT_EQ(prior.inertia.upper, 2e-3);
    const PayloadPrior flow = tables::parsePayloadPrior("payload: {mass: [0.5, 0.5]}", "p.yaml");
    EXPECT_EQ(flow.mass.lower, 0.5);
    EXPECT_EQ(flow.mass.upper, 0.5);
}

TEST(PriorFile, BadFilesNameTheLineAndTheField) {
    const std::pair<const char*, const char*> cases[] = {
        {"payload:\n  mass: [0.4, 0.6]\n  density: [1, 2]\n", "prior.yaml:3: payload.density: unknown key"},
        {"payload:\n  com_x: [0.02, -0.02]\n",
         "prior.yaml:2: payload.com_x: lower bound 0.02 is above upper bound -0.02"},
        {"payload:\n  mass: [0, 0.6]\n", "prior.yaml:2: payload.mass.lower: must be > 0 kg"},
        {"payload:\n\n  inertia: [~, -1e-4]\n", "prior.yaml:3: payload.inertia.upper: must be >= 0 kg m^2"},
        {"payload:\n  mass: 0.5\n", "prior.yaml:2: payload.mass: expected [lower, upper]"},
        {"payload:\n  mass: [0.4, 0.6, 0.8]\n", "prior.yaml:2: payload.mass: expected [lower, upper]"},
        {"payload:\n  com_y: [-0.01, abc]\n", "prior.yaml:2: payload.com_y.upper: 'abc'"},
        {"robot: x\n", "prior.yaml:1: robot: unknown key"},
        {"{}\n", "prior.yaml:1: payload: required"},
    };
    for (const auto& [text, expected] : cases) {
        try {
            (void)tables::parsePayloadPrior(text, "prior.yaml");
            ADD_FAILURE() << "accepted: " << text;
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(expected, 0), 0u) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
}

}  // namespace
}  // namespace nocdyn::test
