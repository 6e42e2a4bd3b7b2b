// Excitation design (excitation.hpp): the designed trajectory stays within every limit along an
// independent inverse-dynamics pass, is better conditioned than the paper's trajectories (the
// condition number checked against an SVD of the stacked regressor), identifies a payload from
// exact data, and bad options are refused by name.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/SVD>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/excitation.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"

namespace nocdyn::test {
namespace {

const Payload kGuess{0.5, 8e-4, Vector2(0.012, -0.007)};

/// A small design budget: the test checks properties, not the optimum.
ExcitationOptions smallBudget() {
    ExcitationOptions options;
    options.base_frequency = 2.0;
    options.harmonics = 4;
    options.samples = 48;
    options.check_samples = 400;
    options.evaluations = 50;
    options.random_shapes = 20;
    return options;
}

struct Designed {
    RobotDescription robot = io::exampleRobot("paper-3prr-general");
    Model loaded{withPayload(robot, kGuess)};
    ExcitationOptions options = smallBudget();
    ExcitationResult result = designExcitation(loaded, 1.0, options);
};

const Designed& designed() {
    static const Designed d;
    return d;
}

/// The column-scaled stacked regressor's condition number by an SVD (independent of the
/// normal-matrix eigenvalues the design uses).
double conditionBySvd(const Model& model, const PoseTrajectory& trajectory, double period, int samples,
                      const std::vector<int>& columns) {
    const auto k = static_cast<Eigen::Index>(columns.size());
    Eigen::MatrixXd stacked(samples * model.actuators, k);
    Data data(model);
    RegressorMatrix Y;
    for (int i = 0; i < samples; ++i) {
        Pose p, dp, ddp;
        trajectory.evaluate(period * i / samples, p, dp, ddp);
        EXPECT_TRUE(inverseDynamicsRegressor(model, data, p, dp, ddp, Y).ok());
        for (Eigen::Index c = 0; c < k; ++c)
            stacked.block(i * model.actuators, c, model.actuators, 1) = Y.col(columns[static_cast<std::size_t>(c)]);
    }
    for (Eigen::Index c = 0; c < k; ++c) stacked.col(c).normalize();
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(stacked);
    return svd.singularValues()(0) / svd.singularValues()(k - 1);
}

TEST(Excitation, StaysWithinEveryLimitWithTheMarginAlongInverseDynamics) {
    const Designed& d = designed();
    ASSERT_TRUE(d.result.assessment.feasible) << d.result.assessment.failure;
    const Model& model = d.loaded;
    const double allowed = 1.0 - d.options.margin;
    Data data(model), home(model);
    ASSERT_TRUE(inverseDisplacement(model, home, model.home).ok());
    double peak_effort = 0.0, peak_range = 0.0;
    // 10 kHz over one period (0.5 s), independently of the design's samples
    for (int i = 0; i <= 5000; ++i) {
        Pose p, dp, ddp;
        d.result.trajectory.evaluate(i * 1e-4, p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok()) << "t = " << i * 1e-4;
        ASSERT_TRUE(checkJointLimits(model, data).ok());
        ASSERT_TRUE(checkEffort(model, data).ok());
        for (int a = 0; a < 3; ++a) {
            const double u = data.limb[static_cast<std::size_t>(a)].q(0);
            const double u0 = home.limb[static_cast<std::size_t>(a)].q(0);
            // slider range +-12.45 mm about home 0, effort 262 N (robots/paper-3prr-general.yaml)
            peak_range = std::max(peak_range, std::abs(u - u0) / (allowed * 0.01245));
            peak_effort = std::max(peak_effort, std::abs(data.tau(a)) / (allowed * 262.0));
        }
        EXPECT_LE(data.cond_A, d.options.max_condition);
    }
    EXPECT_LE(peak_range, 1.0 + 1e-6);
    EXPECT_LE(peak_effort, 1.0 + 1e-6);
    // scaled to the limits: one of them binds (within the design's final bisection step)
    EXPECT_GE(d.result.assessment.use.worst(), 0.99);
    EXPECT_NEAR(std::max(peak_range, peak_effort), d.result.assessment.use.worst(), 2e-3);
}

TEST(Excitation, StartsAndEndsEachPeriodAtHomeAtRest) {
    const Designed& d = designed();
    for (const double t : {0.0, 0.5, 1.0}) {
        Pose p, dp, ddp;
        d.result.trajectory.evaluate(t, p, dp, ddp);
        EXPECT_LE((p - d.loaded.home).cwiseAbs().maxCoeff(), 1e-12) << t;
        EXPECT_LE(dp.cwiseAbs().maxCoeff(), 1e-10) << t;
        EXPECT_LE(ddp.cwiseAbs().maxCoeff(), 1e-8) << t;
    }
    EXPECT_EQ(*d.result.trajectory.duration, 1.0);
    for (const Harmonic& h : d.result.trajectory.x.harmonics)
        EXPECT_NEAR(std::remainder(h.frequency, 2.0), 0.0, 1e-12);  // multiples of f0
}

TEST(Excitation, IsBetterConditionedThanBothPaperTrajectories) {
    const Designed& d = designed();
    const std::vector<int> columns = excitedColumns(d.loaded, d.options);
    ASSERT_EQ(columns.size(), 4U);
    const double by_svd = conditionBySvd(d.loaded, d.result.trajectory, 0.5, d.options.check_samples, columns);
    EXPECT_NEAR(d.result.assessment.condition, by_svd, 1e-6 * by_svd);
    for (const PoseTrajectory& paper : {paperTrajectory1(), paperTrajectory2()}) {
        const ExcitationAssessment a = assessExcitation(d.loaded, aboutHome(d.loaded, paper), 0.2, 400, d.options);
        EXPECT_NEAR(a.condition, conditionBySvd(d.loaded, paper, 0.2, 400, columns), 1e-6 * a.condition);
        EXPECT_LT(d.result.assessment.condition, a.condition) << paper.name;
    }
}

TEST(Excitation, IdentifiesThePayloadExactlyFromExactDataAlongIt) {
    const Designed& d = designed();
    const Payload truth{0.43, 6e-4, Vector2(-0.009, 0.015)};  // not the guess
    const Model nominal(d.robot), loaded(withPayload(d.robot, truth));
    Motion motion;
    Data data(loaded);
    const int N = 400;
    motion.tau.resize(N, 3);
    for (int i = 0; i < N; ++i) {
        Pose p, dp, ddp;
        motion.t.push_back(i * 1.0 / N);
        d.result.trajectory.evaluate(motion.t.back(), p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(loaded, data, p, dp, ddp).ok());
        motion.p.push_back(p);
        motion.dp.push_back(dp);
        motion.ddp.push_back(ddp);
        motion.tau.row(i) = data.tau.transpose();
    }
    const PayloadResult r = identifyPayload(nominal, motion);
    EXPECT_NEAR(r.mass, truth.mass, 1e-9 * truth.mass);
    EXPECT_NEAR(r.com.x(), truth.com.x(), 1e-9 * 0.015);
    EXPECT_NEAR(r.com.y(), truth.com.y(), 1e-9 * 0.015);
    EXPECT_NEAR(r.inertia, truth.inertia, 1e-9 * truth.inertia);
}

TEST(Excitation, TheWrittenFileReadsBackAsTheSameTrajectory) {
    const Designed& d = designed();
    const PoseTrajectory back = io::parseTrajectory(io::trajectoryToYaml(d.result.trajectory), "excitation.yaml");
    for (const double t : {0.0123, 0.2777, 0.4991}) {
        Pose p, dp, ddp, q, dq, ddq;
        d.result.trajectory.evaluate(t, p, dp, ddp);
        back.evaluate(t, q, dq, ddq);
        EXPECT_LE((p - q).cwiseAbs().maxCoeff(), 1e-15);
        EXPECT_LE((ddp - ddq).cwiseAbs().maxCoeff(), 1e-10 * ddp.cwiseAbs().maxCoeff());
    }
    EXPECT_EQ(back.duration, d.result.trajectory.duration);
}

TEST(Excitation, IsDeterministicForASeed) {
    const Model model(io::exampleRobot("paper-3prr-general"));
    ExcitationOptions options = smallBudget();
    options.evaluations = options.random_shapes = 4;
    const ExcitationResult a = designExcitation(model, 0.5, options), b = designExcitation(model, 0.5, options);
    ASSERT_EQ(a.trajectory.theta.harmonics.size(), b.trajectory.theta.harmonics.size());
    for (std::size_t k = 0; k < a.trajectory.theta.harmonics.size(); ++k)
        EXPECT_EQ(a.trajectory.theta.harmonics[k].amplitude, b.trajectory.theta.harmonics[k].amplitude);
    EXPECT_EQ(a.assessment.condition, b.assessment.condition);
}

void expectError(const Model& model, double duration, const ExcitationOptions& options, const std::string& words) {
    try {
        (void)designExcitation(model, duration, options);
        FAIL() << "accepted; expected: " << words;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
}

TEST(Excitation, RefusesBadOptionsNamingThem) {
    const Model model(io::exampleRobot("paper-3prr-general"));
    ExcitationOptions options = smallBudget();
    expectError(model, 0.75, options, "not a whole number of base periods");
    options.harmonics = 2;
    expectError(model, 1.0, options, "harmonics");
    options = smallBudget();
    options.margin = 0.95;
    expectError(model, 1.0, options, "margin");
    // a condition-number bound the home posture itself exceeds
    options = smallBudget();
    options.max_condition = 1.0001;
    expectError(model, 1.0, options, "at rest at home");
}

}  // namespace
}  // namespace nocdyn::test
