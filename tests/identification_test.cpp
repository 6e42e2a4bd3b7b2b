// Identification (identification.hpp): the regressor reproduces inverse dynamics on every example
// robot and on random robots of every limb type (gravity, friction, redundancy); the base
// parameters reproduce it too; a payload is recovered exactly from exact data.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/examples.hpp"
#include "random_robots.hpp"
#include "identification_support.hpp"

namespace nocdyn::test {
namespace {

constexpr double kRegressorTolerance = 1e-12;  // relative to the largest force of the sample
constexpr double kExactRecovery = 1e-9;        // relative, payload from exact data

RobotDescription withGravityAndFriction(RobotDescription robot) {
    robot.gravity = Eigen::Vector2d(1.5, -9.81);
    int k = 0;
    for (LimbDescription& limb : robot.limbs) {
        for (JointDescription& joint : limb.joints) {
            joint.damping = 0.5 + 0.25 * (k % 3);
            joint.friction = 0.3 + 0.1 * (k % 4);
            ++k;
        }
    }
    return robot;
}

/// Y pi against inverse dynamics along a random trajectory around home.
void expectRegressorMatchesInverseDynamics(const RobotDescription& description, std::mt19937& rng,
                                           const std::string& name) {
    const Model model(description);
    Data data(model), check(model);
    const ParameterVector pi = standardParameters(model);
    const PoseTrajectory trajectory = trajectoryAround(model.home, rng);
    RegressorMatrix Y;
    int tested = 0;
    for (int s = 0; s < 40; ++s) {
        Pose p, dp, ddp;
        trajectory.evaluate(0.0123 * s, p, dp, ddp);
        if (!inverseDynamics(model, check, p, dp, ddp)) continue;
        ASSERT_TRUE(inverseDynamicsRegressor(model, data, p, dp, ddp, Y).ok()) << name;
        ASSERT_EQ(Y.rows(), model.actuators);
        ASSERT_EQ(Y.cols(), parameterCount(model));
        const ActuatorVector tau = Y * pi;
        const double scale = check.tau.cwiseAbs().maxCoeff();
        EXPECT_LE((tau - check.tau).cwiseAbs().maxCoeff(), kRegressorTolerance * scale)
            << name << " sample " << s << ": Y pi = " << tau.transpose() << ", inverse dynamics "
            << check.tau.transpose();
        ++tested;
    }
    EXPECT_GE(tested, 15) << name;  // random robots may leave their workspace part of the way
}

TEST(Regressor, TimesStandardParametersEqualsInverseDynamicsOnExampleRobots) {
    std::mt19937 rng(11);
    for (const std::string& name : io::exampleRobotNames()) {
        const RobotDescription robot = io::exampleRobot(name);
        expectRegressorMatchesInverseDynamics(robot, rng, name);
        expectRegressorMatchesInverseDynamics(withGravityAndFriction(robot), rng, name + " with gravity and friction");
    }
}

TEST(Regressor, TimesStandardParametersEqualsInverseDynamicsOnRandomRobots) {
    std::mt19937 rng(5);
    int robots = 0;
    for (const std::string& type : limbTypes()) {
        for (const int limbs : {3, 4}) {
            RandomRobotSpec spec;
            spec.limb_types.assign(static_cast<std::size_t>(limbs), type);
            spec.actuators = limbs;  // redundant with four limbs
            spec.gravity = true;
            spec.friction = true;
            for (int attempt = 0; attempt < 20; ++attempt) {
                if (const auto robot = randomRobot(spec, rng)) {
                    expectRegressorMatchesInverseDynamics(*robot, rng, type + " x" + std::to_string(limbs));
                    ++robots;
                    break;
                }
            }
        }
    }
    EXPECT_GE(robots, 12);
}

TEST(Regressor, ParameterNamesAndStandardValuesFollowTheRobotFile) {
    const Model model(io::exampleRobot("3-rrr"));
    EXPECT_EQ(parameterCount(model), 4 * 7 + 2 * 9);
    EXPECT_EQ(parameterName(model, bodyParameterIndex(model.platformBody())), "platform.m");
    EXPECT_EQ(parameterName(model, bodyParameterIndex(model.body(1, 1)) + 3), "limb2.body2.I_O");
    EXPECT_EQ(parameterName(model, jointParameterIndex(model, 2, 0) + 1), "limb3.joint1.friction");
    const ParameterVector pi = standardParameters(model);
    // proximal link of limb 1: 0.30 kg at (0.04, -0.165875), 0.000276452 about its c.o.m.
    const int i = bodyParameterIndex(model.body(0, 0));
    EXPECT_DOUBLE_EQ(pi(i), 0.30);
    EXPECT_DOUBLE_EQ(pi(i + 1), 0.30 * 0.04);
    EXPECT_DOUBLE_EQ(pi(i + 2), 0.30 * -0.165875);
    EXPECT_DOUBLE_EQ(pi(i + 3), 0.000276452 + 0.30 * (0.04 * 0.04 + 0.165875 * 0.165875));
}

TEST(BaseParameters, ReproduceInverseDynamicsOnFreshMotions) {
    std::mt19937 rng(3);
    for (const std::string& name : {std::string("paper-3prr-general"), std::string("3-rrr"), std::string("4-rrr")}) {
        const Model model(withGravityAndFriction(io::exampleRobot(name)));
        BaseParameterOptions options;
        options.samples = 60;
        const BaseParameters base = baseParameters(model, options);
        EXPECT_LT(base.rank, parameterCount(model)) << name;
        EXPECT_GT(base.rank, 4) << name;
        const Eigen::VectorXd beta = base.K * standardParameters(model);
        Data data(model);
        RegressorMatrix Y;
        const PoseTrajectory trajectory = trajectoryAround(model.home, rng);
        int tested = 0;
        for (int s = 0; s < 20; ++s) {
            Pose p, dp, ddp;
            trajectory.evaluate(0.017 * s, p, dp, ddp);
            if (!inverseDynamicsRegressor(model, data, p, dp, ddp, Y)) continue;
            Eigen::VectorXd tau_base = Eigen::VectorXd::Zero(model.actuators);
            for (int k = 0; k < base.rank; ++k)
                tau_base += Y.col(base.independent[static_cast<std::size_t>(k)]) * beta(k);
            const Eigen::VectorXd tau = Y * standardParameters(model);
            EXPECT_LE((tau_base - tau).cwiseAbs().maxCoeff(), 1e-8 * tau.cwiseAbs().maxCoeff())
                << name << " sample " << s;
            ++tested;
        }
        // the example robots stay regular along the motion: every sample is checked
        EXPECT_EQ(tested, 20) << name;
    }
}

TEST(BaseParameters, ATranslatingSliderHasNoIdentifiableRotationalInertia) {
    // the paper's sliders only translate: their I_O and m c have no effect of their own
    const Model model(io::exampleRobot("paper-3prr-general"));
    BaseParameterOptions options;
    options.samples = 40;
    const BaseParameters base = baseParameters(model, options);
    const int slider = bodyParameterIndex(model.body(0, 0));
    const auto& u = base.unidentifiable;
    EXPECT_NE(std::find(u.begin(), u.end(), slider + 3), u.end()) << describeBaseParameters(model, base);
    EXPECT_NE(describeBaseParameters(model, base).find("limb1.body1.I_O"), std::string::npos);
}

TEST(PayloadIdentification, RecoversThePayloadExactlyFromExactMotion) {
    std::mt19937 rng(21);
    const Payload payload{0.5, 8e-4, Vector2(0.012, -0.007)};
    for (const std::string& name : io::exampleRobotNames()) {
        const RobotDescription robot = withGravityAndFriction(io::exampleRobot(name));
        const Model nominal(robot);
        const Model loaded(withPayload(robot, payload));
        const Motion motion = exactMotion(loaded, trajectoryAround(nominal.home, rng), 200, 0.005);
        const PayloadResult result = identifyPayload(nominal, motion);
        EXPECT_NEAR(result.mass, payload.mass, kExactRecovery * payload.mass) << name;
        EXPECT_NEAR(result.com.x(), payload.com.x(), kExactRecovery * 0.012) << name;
        EXPECT_NEAR(result.com.y(), payload.com.y(), kExactRecovery * 0.012) << name;
        EXPECT_NEAR(result.inertia, payload.inertia, kExactRecovery * payload.inertia) << name;
        EXPECT_FALSE(result.inertia_constrained);
        EXPECT_LE(result.fit.rms_holdout[0], 1e-9 * result.fit.rms_measured[0]) << name;
    }
}

TEST(PayloadIdentification, RecoversThePayloadFromActuatorPositionsRatesAndAccelerations) {
    // the logger's view: u, du, ddu and tau only; the pose comes from the direct kinematics
    std::mt19937 rng(8);
    const Payload payload{0.5, 8e-4, Vector2(0.012, -0.007)};
    for (const std::string& name : {std::string("paper-3prr-general"), std::string("4-rrr")}) {
        const RobotDescription robot = withGravityAndFriction(io::exampleRobot(name));
        const Model nominal(robot);
        const Model loaded(withPayload(robot, payload));
        const Motion exact = exactMotion(loaded, trajectoryAround(nominal.home, rng), 150, 0.005);
        Measurements measured;
        const auto N = static_cast<Eigen::Index>(exact.t.size());
        const int n = loaded.actuators;
        measured.t = exact.t;
        measured.u.resize(N, n);
        measured.du.resize(N, n);
        measured.ddu.resize(N, n);
        measured.tau = exact.tau;
        Data data(loaded);
        for (Eigen::Index k = 0; k < N; ++k) {
            const auto kk = static_cast<std::size_t>(k);
            ASSERT_TRUE(inverseDynamics(loaded, data, exact.p[kk], exact.dp[kk], exact.ddp[kk]).ok());
            measured.u.row(k) = data.u.transpose();
            measured.du.row(k) = data.du.transpose();
            measured.ddu.row(k) = data.ddu.transpose();
        }
        const Motion motion = reconstructMotion(nominal, measured);
        const PayloadResult result = identifyPayload(nominal, motion);
        EXPECT_NEAR(result.mass, payload.mass, kExactRecovery * payload.mass) << name;
        EXPECT_NEAR(result.com.x(), payload.com.x(), kExactRecovery * 0.012) << name;
        EXPECT_NEAR(result.com.y(), payload.com.y(), kExactRecovery * 0.012) << name;
        EXPECT_NEAR(result.inertia, payload.inertia, kExactRecovery * payload.inertia) << name;
    }
}

TEST(PayloadIdentification, FrictionOfTheActuatorsIsIdentifiedAlongside) {
    std::mt19937 rng(4);
    const Payload payload{0.5, 8e-4, Vector2(0.012, -0.007)};
    const RobotDescription file = io::exampleRobot("paper-3prr-general");
    RobotDescription plant = withGravityAndFriction(file);  // friction the file does not know
    const Model nominal(withGravityAndFriction(file));
    for (LimbDescription& limb : plant.limbs) {
        for (JointDescription& joint : limb.joints) {
            if (joint.actuated) {
                joint.damping = 7.0;
                joint.friction = 1.5;
            }
        }
    }
    const Model loaded(withPayload(plant, payload));
    const Motion motion = exactMotion(loaded, trajectoryAround(nominal.home, rng), 200, 0.005);
    IdentificationOptions options;
    options.friction = true;
    const PayloadResult result = identifyPayload(nominal, motion, options);
    EXPECT_NEAR(result.mass, payload.mass, kExactRecovery * payload.mass);
    EXPECT_NEAR(result.inertia, payload.inertia, kExactRecovery * payload.inertia);
    ASSERT_EQ(result.friction.size(), 6U);
    EXPECT_NEAR(result.friction[0].value, 7.0, 1e-7);
    EXPECT_NEAR(result.friction[1].value, 1.5, 1e-7);
}

TEST(PayloadIdentification, FilteredPositionsGiveThePayloadWithinAPercent) {
    // no du, ddu columns: u and tau low-pass filtered (zero phase) and u differentiated
    std::mt19937 rng(2);
    const Payload payload{0.5, 8e-4, Vector2(0.012, -0.007)};
    const RobotDescription robot = io::exampleRobot("paper-3prr-general");
    const Model nominal(robot);
    const Model loaded(withPayload(robot, payload));
    const double rate = 2000.0;
    const Motion exact = exactMotion(loaded, trajectoryAround(nominal.home, rng, 0.5), 4000, 1.0 / rate);
    Measurements measured;
    const auto N = static_cast<Eigen::Index>(exact.t.size());
    ASSERT_EQ(N, 4000);
    measured.t = exact.t;
    measured.u.resize(N, 3);
    measured.tau = exact.tau;
    Data data(loaded);
    for (Eigen::Index k = 0; k < N; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        ASSERT_TRUE(inverseDisplacement(loaded, data, exact.p[kk]).ok());
        measured.u.row(k) = data.u.transpose();
    }
    const Motion motion = reconstructMotion(nominal, measured);
    const PayloadResult result = identifyPayload(nominal, motion);
    EXPECT_NEAR(result.mass, payload.mass, 0.01 * payload.mass);
    EXPECT_NEAR(result.com.x(), payload.com.x(), 2e-4);
    EXPECT_NEAR(result.com.y(), payload.com.y(), 2e-4);
    EXPECT_NEAR(result.inertia, payload.inertia, 0.02 * payload.inertia);
}

TEST(PayloadIdentification, RejectsNonMonotonicTimeAndTooFewSamples) {
    const Model model(io::exampleRobot("paper-3prr-general"));
    Measurements measured;
    measured.t = {0.0, 0.1, 0.1, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    measured.u = Eigen::MatrixXd::Zero(11, 3);
    measured.tau = Eigen::MatrixXd::Zero(11, 3);
    try {
        (void)reconstructMotion(model, measured);
        FAIL() << "non-monotonic time accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("sample 3"), std::string::npos) << e.what();
    }
    Motion motion;
    motion.t = {0.0, 0.1};
    motion.p.assign(2, model.home);
    motion.dp.assign(2, Twist::Zero());
    motion.ddp.assign(2, Twist::Zero());
    motion.tau = Eigen::MatrixXd::Zero(2, 3);
    EXPECT_THROW((void)identifyPayload(model, motion), Error);
}

TEST(PayloadIdentification, ARestingPlatformLeavesTheInertiaUnidentifiable) {
    // without rotation nor gravity the payload's inertia has no effect: named in the error
    const Model model(io::exampleRobot("paper-3prr-general"));
    Motion motion;
    const int N = 50;
    motion.tau = Eigen::MatrixXd::Zero(N, 3);
    for (int k = 0; k < N; ++k) {
        motion.t.push_back(0.01 * k);
        motion.p.push_back(model.home);
        motion.dp.push_back(Twist::Zero());
        motion.ddp.push_back(Twist(0.0, 1.0, 0.5));
    }
    try {
        (void)identifyPayload(model, motion);
        FAIL() << "unidentifiable inertia accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("payload inertia"), std::string::npos) << e.what();
    }
}

/// The payload identification problem on exact data: the stacked platform columns Y_P of the
/// regressor and b = tau - Y pi_robot, so that the residual of a payload is |b - Y_P x|^2.
struct PayloadProblem {
    Eigen::MatrixXd Y_P;
    Eigen::VectorXd b;
    [[nodiscard]] double residual(double mass, const Vector2& com, double inertia) const {
        return (b - Y_P * inertialParameters(mass, com, inertia)).squaredNorm();
    }
};

PayloadProblem payloadProblem(const Model& nominal, const Motion& motion) {
    const int n = nominal.actuators;
    const auto N = static_cast<Eigen::Index>(motion.t.size());
    PayloadProblem problem;
    problem.Y_P.resize(N * n, kBodyParameters);
    problem.b.resize(N * n);
    const ParameterVector pi = standardParameters(nominal);
    Data data(nominal);
    RegressorMatrix Y;
    for (Eigen::Index k = 0; k < N; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        EXPECT_TRUE(inverseDynamicsRegressor(nominal, data, motion.p[kk], motion.dp[kk], motion.ddp[kk], Y).ok());
        problem.Y_P.middleRows(k * n, n) = Y.middleCols<kBodyParameters>(bodyParameterIndex(nominal.platformBody()));
        problem.b.segment(k * n, n) = motion.tau.row(k).transpose() - Y * pi;
    }
    return problem;
}

struct PriorCase {
    const char* name;
    PayloadPrior prior;
    std::vector<std::pair<std::string, bool>> active;  // parameter, on its upper bound
};

/// The paper's prototype carrying a known payload along a random motion, exactly measured.
struct PriorSetup {
    explicit PriorSetup(unsigned seed) : rng(seed) {
        motion = exactMotion(Model(withPayload(robot, payload)), trajectoryAround(nominal.home, rng), 80, 0.005);
    }
    RobotDescription robot = io::exampleRobot("paper-3prr-general");
    Payload payload{0.5, 8e-4, Vector2(0.012, -0.007)};
    Model nominal{robot};
    std::mt19937 rng;
    Motion motion;
};

TEST(PayloadPrior, ABoxHoldingTheTruthChangesNothingOnExactData) {
    const PriorSetup setup(31);
    const Payload& payload = setup.payload;
    const Model& nominal = setup.nominal;
    const Motion& motion = setup.motion;
    IdentificationOptions options;
    options.prior = PayloadPrior{{0.4, 0.6}, {-0.02, 0.02}, {-0.02, 0.02}, {0.0, 2e-3}};
    const PayloadResult bounded = identifyPayload(nominal, motion, options);
    const PayloadResult free = identifyPayload(nominal, motion);
    EXPECT_TRUE(bounded.active_bounds.empty());
    EXPECT_EQ(bounded.mass, free.mass);
    EXPECT_EQ(bounded.com, free.com);
    EXPECT_EQ(bounded.inertia, free.inertia);
    EXPECT_NEAR(bounded.mass, payload.mass, kExactRecovery * payload.mass);
    EXPECT_NEAR(bounded.com.x(), payload.com.x(), kExactRecovery * 0.012);
    EXPECT_NEAR(bounded.inertia, payload.inertia, kExactRecovery * payload.inertia);
}

TEST(PayloadPrior, ABoxExcludingTheTruthGivesTheBestFitOnItsBound) {
    // exact data (equal weights): the estimate's residual is no larger than that of any feasible
    // payload, sampled at random over the box and next to the estimate along each free parameter
    PriorSetup setup(32);
    const Model& nominal = setup.nominal;
    const Motion& motion = setup.motion;
    std::mt19937& rng = setup.rng;
    const PayloadProblem problem = payloadProblem(nominal, motion);
    const double inf = std::numeric_limits<double>::infinity();
    const std::vector<PriorCase> cases = {
        {"mass above", {{0.3, 0.45}, {}, {}, {}}, {{"mass", true}}},
        {"c.o.m. x below", {{}, {0.0, 0.01}, {}, {}}, {{"com_x", true}}},
        {"inertia above", {{}, {}, {}, {0.0, 5e-4}}, {{"inertia", true}}},
        {"mass and inertia below",
         {{0.55, inf}, {}, {-0.005, 0.005}, {1e-3, 2e-3}},
         {{"mass", false}, {"com_y", false}, {"inertia", false}}},
        {"mass known", {{0.48, 0.48}, {}, {}, {}}, {{"mass", true}}},  // the unbounded fit is above
        {"mass known above", {{0.52, 0.52}, {}, {}, {}}, {{"mass", false}}},
    };
    for (const PriorCase& c : cases) {
        IdentificationOptions options;
        options.holdout = 0.0;
        options.prior = c.prior;
        const PayloadResult r = identifyPayload(nominal, motion, options);
        ASSERT_EQ(r.active_bounds.size(), c.active.size()) << c.name;
        for (std::size_t i = 0; i < c.active.size(); ++i) {
            EXPECT_EQ(r.active_bounds[i].parameter, c.active[i].first) << c.name;
            EXPECT_EQ(r.active_bounds[i].upper, c.active[i].second) << c.name;
        }
        const Bounds box[4] = {c.prior.mass, c.prior.com_x, c.prior.com_y, c.prior.inertia};
        const double estimate[4] = {r.mass, r.com.x(), r.com.y(), r.inertia};
        for (const ActiveBound& b : r.active_bounds) {
            const int i = b.parameter == "mass" ? 0 : b.parameter == "com_x" ? 1 : b.parameter == "com_y" ? 2 : 3;
            EXPECT_EQ(estimate[i], b.upper ? box[i].upper : box[i].lower) << c.name << " " << b.parameter;
        }
        for (int i = 0; i < 4; ++i) {
            EXPECT_GE(estimate[i], box[i].lower) << c.name;
            EXPECT_LE(estimate[i], box[i].upper) << c.name;
        }
        EXPECT_GE(r.inertia, 0.0);
        const double best = problem.residual(r.mass, r.com, r.inertia);
        EXPECT_GT(best, 0.0) << c.name;
        // where a side is open, sample around the truth
        const double around[4][2] = {{0.3, 0.7}, {-0.03, 0.03}, {-0.03, 0.03}, {0.0, 3e-3}};
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        const auto feasible = [&](int i, double v) {
            return v >= box[i].lower && v <= box[i].upper && (i != 3 || v >= 0);
        };
        for (int s = 0; s < 200; ++s) {
            double v[4];
            for (int i = 0; i < 4; ++i) {
                const double lo = std::isfinite(box[i].lower) ? box[i].lower : around[i][0];
                const double hi = std::isfinite(box[i].upper) ? box[i].upper : around[i][1];
                v[i] = lo + (hi - lo) * unit(rng);
            }
            EXPECT_LE(best, problem.residual(v[0], Vector2(v[1], v[2]), v[3])) << c.name << " sample " << s;
        }
        const double step[4] = {1e-5, 1e-6, 1e-6, 1e-7};
        for (int i = 0; i < 4; ++i) {
            for (const double sign : {-1.0, 1.0}) {
                double v[4] = {r.mass, r.com.x(), r.com.y(), r.inertia};
                v[i] += sign * step[i];
                if (!feasible(i, v[i])) continue;
                EXPECT_LE(best, problem.residual(v[0], Vector2(v[1], v[2]), v[3]) * (1.0 + 1e-12))
                    << c.name << ": parameter " << i << " moved by " << sign * step[i];
            }
        }
    }
}

}  // namespace
}  // namespace nocdyn::test
