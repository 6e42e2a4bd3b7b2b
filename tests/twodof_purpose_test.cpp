// Two-DOF planar robots (motion: translation, pose [x, y] of a point tool) through the
// identification and drawing commands: regressor, identify, excite and animate.
//   - The regressor: Y pi equals the inverse dynamics' forces on the shipped five-bar
//     (horizontal) and biglide (vertical, under gravity), with joint friction added, at random
//     poses, rates and accelerations in x, y; the platform's m c_x, m c_y and I_O columns are
//     exactly zero (a point mass that never turns), and `regressor` says so.
//   - identify: a known point payload's mass from a simulated log (exact u, du, ddu; Gaussian
//     force noise) comes back within the standard deviation the report prints; no c.o.m. or
//     inertia is reported, and a prior bounding them is refused.
//   - excite: the designed trajectory moves x, y only, stays within every joint range, velocity
//     and effort limit with the margin, and its condition number is finite and reported.
//   - animate: the page's frames hold the five-bar's drawing at the trajectory's samples (the
//     tool point at x, y, each arm and forearm its length) and at a recorded motion's; a theta
//     motion is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "app/animate.hpp"
#include "app/excite.hpp"
#include "app/identify.hpp"
#include "app/regressor.hpp"
#include "cli_support.hpp"
#include "nocdyn/drawing.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::test {
namespace {

constexpr double kPi = std::numbers::pi;
// Measured: |Y pi - tau| <= 8.3e-16 (five-bar), 6.0e-16 (biglide) of the largest force, friction included.
constexpr double kRegressorTolerance = 1e-12;

RobotDescription shipped(const std::string& name) {
    return io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml");
}

app::RobotSource sourceOf(const RobotDescription& robot) {
    app::RobotSource source;
    source.description = robot;
    return source;
}

/// The x, y motion of the identification log about the tool's home: two sines per axis.
struct TaskMotion {
    Vector2 home;
    void at(double t, TaskVector& p, TaskVector& dp, TaskVector& ddp) const {
        static constexpr double a[2][2] = {{0.04, 0.015}, {0.03, 0.02}};
        static constexpr double f[2][2] = {{1.3, 3.1}, {1.7, 2.3}};
        p = TaskVector(2);
        dp = TaskVector::Zero(2);
        ddp = TaskVector::Zero(2);
        for (int i = 0; i < 2; ++i) {
            p(i) = home(i);
            for (int k = 0; k < 2; ++k) {
                const double w = 2.0 * kPi * f[i][k];
                p(i) += a[i][k] * std::sin(w * t);
                dp(i) += a[i][k] * w * std::cos(w * t);
                ddp(i) -= a[i][k] * w * w * std::sin(w * t);
            }
        }
    }
};

TEST(TwoDofCommands, RegressorTimesParametersIsTheInverseDynamics) {
    for (const char* name : {"five-bar", "biglide"}) {
        SCOPED_TRACE(name);
        RobotDescription robot = shipped(name);
        // friction on the joints that take it (not the last R joint, which the pose does not set):
        // their columns are checked too
        for (LimbDescription& limb : robot.limbs) {
            for (std::size_t k = 0; k < 2; ++k) {
                limb.joints[k].damping = 0.01 * static_cast<double>(k + 1);
                limb.joints[k].friction = 0.02 * static_cast<double>(k + 1);
            }
        }
        const Model model(robot);
        ASSERT_EQ(model.task_dimension, 2);
        const ParameterVector pi = standardParameters(model);
        const int platform = bodyParameterIndex(model.platformBody());
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> unit(-1.0, 1.0);
        Data data(model), data_y(model);
        RegressorMatrix Y;
        int checked = 0;
        double worst = 0.0;
        for (int s = 0; s < 200 && checked < 50; ++s) {
            const Pose p = poseOfTask(model, model.home.tail<2>() + 0.03 * Vector2(unit(rng), unit(rng)));
            const Twist dp = rateOfTask(model, 0.5 * Vector2(unit(rng), unit(rng)));
            const Twist ddp = rateOfTask(model, 5.0 * Vector2(unit(rng), unit(rng)));
            if (!inverseDynamics(model, data, p, dp, ddp)) continue;
            ASSERT_TRUE(inverseDynamicsRegressor(model, data_y, p, dp, ddp, Y));
            ASSERT_EQ(Y.rows(), model.actuators);
            ASSERT_EQ(Y.cols(), parameterCount(model));
            const ActuatorVector tau = data.tau;
            const ActuatorVector predicted = Y * pi;
            const double scale = tau.cwiseAbs().maxCoeff();
            ASSERT_GT(scale, 0.0);
            worst = std::max(worst, (predicted - tau).cwiseAbs().maxCoeff() / scale);
            // a point mass that never turns: its first moments and rotary inertia act on nothing
            for (int c = 1; c < kBodyParameters; ++c) EXPECT_EQ(Y.col(platform + c).norm(), 0.0);
            EXPECT_GT(Y.col(platform).norm(), 0.0);
            // nor does friction at the last R joints, which turn with the fictitious theta
            for (int j = 0; j < model.limbs; ++j) {
                EXPECT_EQ(Y.col(jointParameterIndex(model, j, 2)).norm(), 0.0);
                EXPECT_EQ(Y.col(jointParameterIndex(model, j, 2) + 1).norm(), 0.0);
                EXPECT_GT(Y.col(jointParameterIndex(model, j, 0)).norm(), 0.0);
            }
            ++checked;
        }
        EXPECT_EQ(checked, 50);
        EXPECT_LE(worst, kRegressorTolerance);
    }
    // the command: the five-bar is taken, and the platform's inert parameters are named
    app::RegressorOptions options;
    options.robot = sourceOf(shipped("five-bar"));
    const app::RegressorResult result = app::runRegressor(options, app::silent());
    EXPECT_NE(result.text.find("only platform.m acts"), std::string::npos) << result.text;
    const std::size_t inert = result.text.find("unidentifiable (no effect on the actuator forces):");
    ASSERT_NE(inert, std::string::npos) << result.text;
    const std::string inert_line = result.text.substr(inert, result.text.find('\n', inert) - inert);
    for (const char* p : {"platform.mc_x", "platform.mc_y", "platform.I_O"})
        EXPECT_NE(inert_line.find(p), std::string::npos) << inert_line;
    EXPECT_EQ(inert_line.find("platform.m "), std::string::npos) << inert_line;
}

/// The log of the five-bar carrying `payload` kg at its tool point along TaskMotion: t, u, du,
/// ddu exact, tau with Gaussian noise of `noise` N m.
io::Table fiveBarLog(double payload, double noise, unsigned seed) {
    const RobotDescription robot = withPayload(shipped("five-bar"), Payload{payload, 0.0, Vector2::Zero()});
    const Model model(robot);
    const TaskMotion motion{model.home.tail<2>()};
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    io::Table table;
    table.columns = {"t", "u1", "u2", "du1", "du2", "ddu1", "ddu2", "tau1", "tau2"};
    Data data(model);
    TaskVector p, dp, ddp;
    for (int k = 0; k < 1000; ++k) {
        const double t = 2e-3 * k;
        motion.at(t, p, dp, ddp);
        const Status status =
            inverseDynamics(model, data, poseOfTask(model, p), rateOfTask(model, dp), rateOfTask(model, ddp));
        EXPECT_TRUE(status) << describe(status, model);
        table.rows.push_back({t, data.u(0), data.u(1), data.du(0), data.du(1), data.ddu(0), data.ddu(1),
                              data.tau(0) + noise * normal(rng), data.tau(1) + noise * normal(rng)});
    }
    return table;
}

TEST(TwoDofCommands, IdentifyRecoversAPointPayloadsMassWithinItsUncertainty) {
    constexpr double kMass = 0.2;  // [kg] at the tool point, on top of the tool's 0.3 kg
    app::IdentifyOptions options;
    options.robot = sourceOf(shipped("five-bar"));
    options.data = "five-bar log";
    options.data_table = fiveBarLog(kMass, 2e-3, 3);
    const app::IdentifyResult result = app::runIdentify(options, app::silent());
    ASSERT_TRUE(result.payload);
    const PayloadResult& r = *result.payload;
    // the report prints the mass and its standard deviation, and no c.o.m. or inertia
    std::ostringstream mass, sd;
    mass.precision(12);
    sd.precision(12);
    mass << r.mass;
    sd << r.mass_sd;
    EXPECT_NE(result.text.find("payload: {mass: " + mass.str() + "}"), std::string::npos) << result.text;
    EXPECT_NE(result.text.find("standard_deviation: {mass: " + sd.str() + "}"), std::string::npos) << result.text;
    EXPECT_NE(result.text.find("point mass at the tool point"), std::string::npos) << result.text;
    EXPECT_EQ(result.text.find("com: ["), std::string::npos) << result.text;
    EXPECT_EQ(result.text.find(", inertia: "), std::string::npos) << result.text;
    EXPECT_EQ(r.covariance.rows(), 1);
    // Measured: mass 0.200089 kg, standard deviation 5.2e-5 kg (1.7 of them off; noise 2e-3 N m on
    // held-out rms forces of 0.50 and 1.15 N m)
    EXPECT_GT(r.mass_sd, 0.0);
    EXPECT_LT(r.mass_sd, 0.01 * kMass);
    EXPECT_LE(std::abs(r.mass - kMass), 3.0 * r.mass_sd) << "mass " << r.mass << " sd " << r.mass_sd;
    EXPECT_EQ(r.com, Vector2::Zero());
    EXPECT_EQ(r.inertia, 0.0);
    // the file: the robot with the mass added to its tool
    const Model merged(io::parseRobotDescription(result.yaml, "merged"));
    EXPECT_NEAR(merged.description.platform.mass, 0.3 + r.mass, 1e-12);
    EXPECT_EQ(merged.task_dimension, 2);

    // exact forces: the mass to round-off
    options.data_table = fiveBarLog(kMass, 0.0, 3);
    EXPECT_NEAR(app::runIdentify(options, app::silent()).payload->mass, kMass, 1e-9);

    // a prior on the c.o.m. or inertia of a point payload has no meaning
    options.prior_bounds = PayloadPrior{};
    options.prior_bounds->inertia = Bounds{0.0, 1e-3};
    try {
        (void)app::runIdentify(options, app::silent());
        FAIL() << "a prior on the inertia of a two-DOF robot's payload was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("only its mass is identified"), std::string::npos) << e.what();
    }
    // a prior on the mass is kept: the estimate lies on the bound the unbounded fit crosses
    options.prior_bounds = PayloadPrior{};
    options.prior_bounds->mass = Bounds{0.1, 0.15};
    const app::IdentifyResult bounded = app::runIdentify(options, app::silent());
    EXPECT_EQ(bounded.payload->mass, 0.15);
    ASSERT_EQ(bounded.payload->active_bounds.size(), 1U);
    EXPECT_TRUE(bounded.payload->active_bounds[0].upper);
}

TEST(TwoDofCommands, ExciteMovesXYWithinTheLimitsWithAFiniteCondition) {
    const RobotDescription robot = shipped("five-bar");
    app::ExciteOptions options;
    options.robot = sourceOf(robot);
    options.friction = true;  // the mass and both motors' damping and Coulomb friction: 5 unknowns
    options.duration = 1.0;
    options.base_frequency = 1.0;
    options.harmonics = 3;
    options.evaluations = 40;
    options.random_shapes = 20;
    options.check_samples = 400;
    const app::ExciteResult result = app::runExcite(options, app::silent());
    ASSERT_TRUE(std::isfinite(result.condition));
    EXPECT_GE(result.condition, 1.0);
    EXPECT_NE(result.text.find("designed: {condition_number: "), std::string::npos) << result.text;
    EXPECT_NE(result.text.find("per axis (x, y)"), std::string::npos) << result.text;
    // theta stays at home; x and y move
    EXPECT_TRUE(result.trajectory.theta.harmonics.empty());
    EXPECT_EQ(result.trajectory.theta.offset, 0.0);
    EXPECT_FALSE(result.trajectory.x.harmonics.empty());
    EXPECT_FALSE(result.trajectory.y.harmonics.empty());
    // every sample within the ranges, velocities and efforts, with the margin (10 %)
    const Model model(robot);
    Data data(model);
    Pose p, dp, ddp;
    double use = 0.0, condition = 0.0;  // of the limits, and the largest of J_j's and A's condition numbers
    for (int k = 0; k <= 1000; ++k) {
        result.trajectory.evaluate(1e-3 * k, p, dp, ddp);
        EXPECT_EQ(p(0), 0.0);
        EXPECT_EQ(dp(0), 0.0);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp)) << "t = " << 1e-3 * k;
        condition = std::max({condition, data.cond_A, data.limb[0].cond, data.limb[1].cond});
        for (int a = 0; a < model.actuators; ++a) {
            const JointLimits& limits = robot.limbs[static_cast<std::size_t>(a)].joints[0].limits;
            const double mid = 0.5 * (limits.lower + limits.upper), half = 0.5 * (limits.upper - limits.lower);
            use = std::max({use, std::abs(data.u(a) - mid) / half, std::abs(data.du(a)) / limits.velocity,
                            std::abs(data.tau(a)) / limits.effort});
        }
    }
    // Measured: 48 % of a limit at most, and condition numbers up to 97.8: the singularity limit binds
    EXPECT_LE(use, 0.9 + 1e-6);
    EXPECT_LE(condition, options.max_condition);
    EXPECT_GT(std::max(use, condition / options.max_condition), 0.9);  // scaled up to a limit, not left tiny
    // the report's condition number is the assessment's
    std::ostringstream reported;
    reported << "designed: {condition_number: " << text::number(result.condition);
    EXPECT_NE(result.text.find(reported.str()), std::string::npos) << result.text;

    // a payload guess off the tool point has no meaning for a point payload
    options.payload_guess = {0.1, 0.01, 0.0, 0.0};
    EXPECT_THROW((void)app::runExcite(options, app::silent()), app::OptionError);
}

/// The integers of the JSON array `"key":[...]` in `page` after `from`.
std::vector<long long> jsonIntegers(const std::string& page, const std::string& key, std::size_t from = 0) {
    const std::size_t start = page.find("\"" + key + "\":[", from);
    EXPECT_NE(start, std::string::npos) << key;
    if (start == std::string::npos) return {};
    const std::size_t open = page.find('[', start), close = page.find(']', open);
    std::vector<long long> out;
    std::stringstream items(page.substr(open + 1, close - open - 1));
    for (std::string item; std::getline(items, item, ',');) out.push_back(std::stoll(item));
    return out;
}

TEST(TwoDofCommands, AnimateDrawsTheFiveBarsArmsForearmsAndToolPoint) {
    const std::filesystem::path dir = freshScratchDirectory("twodof_commands");
    const std::string trajectory_file = (dir / "circle.yaml").string();
    {
        std::ofstream out(trajectory_file);
        out << "name: circle\nduration: 1\n"
               "x: {offset: 0.0, harmonics: [{amplitude: 0.04, frequency: 1, phase: 0}]}\n"
               "y: {offset: 0.35, harmonics: [{amplitude: 0.04, frequency: 1, phase: 1.5707963267948966}]}\n";
    }
    const RobotDescription robot = shipped("five-bar");
    app::AnimateOptions options;
    options.robot = sourceOf(robot);
    options.trajectory = trajectory_file;
    options.duration = 1.0;
    options.rate = 100.0;
    const app::AnimateResult result = app::runAnimate(options, app::silent());
    EXPECT_FALSE(result.frame);  // none asked for
    const std::string& page = result.html;
    // per frame: per limb its three R joints (motor, elbow, tool point), then C, in micrometres
    const std::size_t stride_at = page.find("\"stride\":");
    ASSERT_NE(stride_at, std::string::npos);
    EXPECT_EQ(std::stoll(page.substr(stride_at + 9)), 14);
    const std::vector<long long> points = jsonIntegers(page, "points", page.find("\"frames\":{\"t\":"));
    ASSERT_EQ(points.size(), 100U * 14U);  // 100 samples, every one a frame
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(trajectory_file);
    const auto at = [&](std::size_t f, std::size_t i) -> Vector2 {  // [m]
        return Vector2(static_cast<double>(points[14 * f + 2 * i]), static_cast<double>(points[14 * f + 2 * i + 1])) *
               1e-6;
    };
    const double arm = std::hypot(0.1, 0.2), forearm = 0.25;
    for (std::size_t f = 0; f < 100; f += 7) {
        Pose p, dp, ddp;
        trajectory.evaluate(0.01 * static_cast<double>(f), p, dp, ddp);
        const Vector2 tool = p.tail<2>();
        EXPECT_LE((at(f, 6) - tool).norm(), 1e-6) << "frame " << f;  // C
        for (std::size_t j = 0; j < 2; ++j) {
            EXPECT_LE((at(f, 3 * j + 2) - tool).norm(), 1e-6) << "frame " << f;       // the forearm ends at the tool
            EXPECT_LE((at(f, 3 * j) - robot.limbs[j].joints[0].point).norm(), 1e-6);  // the motor stays
            EXPECT_NEAR((at(f, 3 * j + 1) - at(f, 3 * j)).norm(), arm, 2e-6) << "frame " << f;
            EXPECT_NEAR((at(f, 3 * j + 2) - at(f, 3 * j + 1)).norm(), forearm, 2e-6) << "frame " << f;
        }
    }
    // a recorded motion: t, x, y, tau1, tau2 (a theta column only at home)
    io::Table recorded;
    recorded.columns = {"t", "x", "y", "theta", "tau1", "tau2"};
    recorded.rows = {{0.0, 0.0, 0.35, 0.0, 0.1, -0.1}, {0.1, 0.01, 0.34, 0.0, 0.2, -0.2}};
    options.trajectory.clear();
    options.motion_table = recorded;
    const std::string replayed = app::runAnimate(options, app::silent()).html;
    const std::vector<long long> drawn = jsonIntegers(replayed, "points", replayed.find("\"frames\":{\"t\":"));
    ASSERT_EQ(drawn.size(), 2U * 14U);
    EXPECT_EQ(drawn[14 + 12], 10000);  // the second sample's tool point [um]
    EXPECT_EQ(drawn[14 + 13], 340000);
    options.motion_table->rows[1][3] = 0.1;
    try {
        (void)app::runAnimate(options, app::silent());
        FAIL() << "a turning theta was animated on a two-DOF robot";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("column 'theta': 0.1, but a two-DOF robot"), std::string::npos)
            << e.what();
    }
    options.motion_table.reset();
    // theta is no coordinate: a trajectory that turns it is refused
    const std::string turning = (dir / "turning.yaml").string();
    {
        std::ofstream out(turning);
        out << "name: turning\nduration: 1\nx: {offset: 0.0}\ny: {offset: 0.35}\n"
               "theta: {offset: 0.0, harmonics: [{amplitude: 0.1, frequency: 1, phase: 0}]}\n";
    }
    options.trajectory = turning;
    try {
        (void)app::runAnimate(options, app::silent());
        FAIL() << "a theta motion was animated on a two-DOF robot";
    } catch (const app::OptionError& e) {
        EXPECT_NE(std::string(e.what()).find("has no theta"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace nocdyn::test
