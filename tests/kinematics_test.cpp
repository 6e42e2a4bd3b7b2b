// Velocity kinematics (eqs. 3-5) of the general model checked by finite differences of the
// inverse displacement and by inverting eq. 5, on the example robots and on random robots of
// every limb type; and what the per-sample path reports outside the workspace and at the
// singularities of the paper's robot (both forms of its file): the limb named, the value,
// a message that calls a non-finite value what it is.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "random_robots.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

constexpr int kPoses = 300;                 // per robot
constexpr double kFiniteDifference = 1e-7;  // relative
constexpr double kRoundOff = 1e-12;         // relative

/// The two forms of the paper's robot file.
const std::vector<std::string> kPaperForms{"paper-3prr", "paper-3prr-general"};

/// The example robots and random robots of every limb type.
const std::vector<RobotCase>& cases() {
    static const std::vector<RobotCase> all = exampleAndRandomRobots(3, 29);
    return all;
}

TEST(VelocityKinematics, RatesMatchFiniteDifferencesOfInverseDisplacement) {
    // fourth-order differences: the random robots' rates reach ~300 rad/s near their limbs'
    // singularities (within the sampler's condition bound)
    static constexpr double h = 1e-6;
    const int checked = forEachPose(cases(), kPoses, [](const RobotCase& c, const Pose& p, WorkspaceSampler& sampler) {
        const Model& model = *c.model;
        Data data(model), moved(model);
        const Twist t = sampler.twist();
        EXPECT_TRUE(inverseDisplacement(model, data, p).ok()) << c.name << ", " << describePose(p);
        EXPECT_TRUE(velocityFromPlatformTwist(model, data, t).ok()) << c.name << ", " << describePose(p);
        // u, then every limb's joint variables q
        const Eigen::VectorXd fd = centralDifference(
            [&](double s) {
                EXPECT_TRUE(inverseDisplacement(model, moved, p + s * t).ok()) << c.name << ", " << describePose(p);
                Eigen::VectorXd out(model.actuators + 3 * model.limbs);
                out.head(model.actuators) = moved.u;
                for (int j = 0; j < model.limbs; ++j) {
                    out.segment<3>(model.actuators + 3 * j) = moved.limb[static_cast<std::size_t>(j)].q;
                }
                return out;
            },
            h);
        for (int a = 0; a < model.actuators; ++a) {
            EXPECT_NEAR(data.du(a), fd(a), kFiniteDifference * (1 + std::abs(fd(a))))
                << c.name << ", " << describePose(p) << ", actuator " << a + 1;
        }
        for (int j = 0; j < model.limbs; ++j) {
            SCOPED_TRACE(c.name + ", " + describePose(p) + ", limb " + std::to_string(j + 1));
            const LimbData& limb = data.limb[static_cast<std::size_t>(j)];
            for (int q = 0; q < 3; ++q) {
                const double q_fd = fd(model.actuators + 3 * j + q);
                EXPECT_NEAR(limb.gamma_dot(q), q_fd, kFiniteDifference * (1 + std::abs(q_fd))) << "joint " << q + 1;
            }
            // eq. 3: xi_P = J_j gamma_dot_j, the platform twist referred to O
            EXPECT_LT((limb.J * limb.gamma_dot - data.xi_P).norm(), kRoundOff * (1 + data.xi_P.norm()));
        }
        return true;
    });
    EXPECT_GE(checked, kPoses * (5 + 7 * 3));
}

TEST(VelocityKinematics, PlatformTwistFromActuatorRatesInvertsEquation5) {
    const int checked = forEachPose(cases(), kPoses, [](const RobotCase& c, const Pose& p, WorkspaceSampler& sampler) {
        const Model& model = *c.model;
        if (model.actuators != 3) return false;  // the platform twist from the rates needs exactly three
        Data data(model);
        const Twist t = sampler.twist();
        EXPECT_TRUE(inverseDisplacement(model, data, p).ok()) << c.name << ", " << describePose(p);
        EXPECT_TRUE(velocityFromPlatformTwist(model, data, t).ok()) << c.name << ", " << describePose(p);
        const ActuatorVector du = data.du;
        EXPECT_TRUE(velocityFromActuatorRates(model, data, du).ok()) << c.name << ", " << describePose(p);
        EXPECT_LT((data.t_M - t).norm(), kRoundOff * (1 + t.norm())) << c.name << ", " << describePose(p);
        return true;
    });
    EXPECT_GE(checked, kPoses * (4 + 7 * 3));
}

TEST(Messages, NonFiniteValuesAreNotCalledMeasurements) {
    // A NaN pose is not "beyond its reach by nan mm", a NaN force not "effort limit exceeded".
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const std::string& name : io::exampleRobotNames()) {
        SCOPED_TRACE(name);
        const Model model(io::exampleRobot(name));
        Data data(model);
        const Status pose = inverseDisplacement(model, data, Pose(nan, 0.0, 0.0));
        ASSERT_EQ(pose.code, StatusCode::not_finite);
        const std::string pose_message = describe(pose, model);
        EXPECT_EQ(pose_message.find("nan mm"), std::string::npos) << pose_message;
        EXPECT_EQ(pose_message.find("beyond"), std::string::npos) << pose_message;
        EXPECT_NE(pose_message.find("not a finite number"), std::string::npos) << pose_message;

        ASSERT_TRUE(inverseDynamics(model, data, model.home, Twist::Zero(), Twist::Zero()).ok());
        data.tau(1) = nan;
        const Status force = checkEffort(model, data);
        ASSERT_EQ(force.code, StatusCode::effort_exceeded);
        EXPECT_EQ(force.limb, model.actuator_limb[1]);
        const std::string force_message = describe(force, model);
        EXPECT_EQ(force_message.find("limit exceeded"), std::string::npos) << force_message;
        EXPECT_NE(force_message.find("not finite: actuator 2 (limb " + std::to_string(force.limb + 1)),
                  std::string::npos)
            << force_message;
    }
}

TEST(Workspace, PoseOutOfReachIsRejectedNamingTheLimbAndTheDistance) {
    for (const std::string& name : kPaperForms) {
        SCOPED_TRACE(name);
        const Model model(io::exampleRobot(name));
        Data data(model);
        // C far above: M_1 is farther from rail L_1 than the link can reach.
        const Status above = inverseDisplacement(model, data, Pose(0.0, 0.0, 0.08));
        EXPECT_EQ(above.code, StatusCode::unreachable);
        EXPECT_EQ(above.limb, 0);
        EXPECT_GT(above.value, 0.0);
        const std::string message = describe(above, model);
        EXPECT_NE(message.find("limb 1"), std::string::npos) << message;
        EXPECT_NE(message.find("beyond its reach"), std::string::npos) << message;
        // C far below: M_1 crosses the lower base side L_1; the limb still closes (its link
        // folds past the rail), and the stroke of actuator 1 refuses the pose.
        ASSERT_TRUE(inverseDisplacement(model, data, Pose(0.0, 0.0, -0.09)).ok());
        const Status below = checkJointLimits(model, data);
        EXPECT_EQ(below.code, StatusCode::joint_limit_exceeded);
        EXPECT_EQ(below.limb, 0);
        EXPECT_EQ(below.joint, 0);
        // NaN never passes as a pose.
        EXPECT_FALSE(inverseDisplacement(model, data, Pose(std::nan(""), 0.0, 0.0)).ok());
    }
}

TEST(Workspace, LinkNormalToItsRailIsASingularPostureNotANaN) {
    for (const std::string& name : kPaperForms) {
        SCOPED_TRACE(name);
        const Model model(io::exampleRobot(name));
        Data data(model);
        // Raise C until d_1^M = l (1 - 1e-10): cos phi_A1 ~ 1.4e-5, det J_1 = l cos phi_A1.
        const io::RobotParameters paper;
        const double y =
            paper.link_length * (1 - 1e-10) - 0.5 * (paper.baseCircumradius() - paper.platformCircumradius());
        ASSERT_TRUE(inverseDisplacement(model, data, Pose(0.0, 0.0, y)).ok());
        const Status status = velocityFromPlatformTwist(model, data, Twist(0.0, 0.0, 1.0));
        EXPECT_EQ(status.code, StatusCode::singular_limb);
        EXPECT_EQ(status.limb, 0);
        EXPECT_GT(status.value, model.max_condition);
        const std::string message = describe(status, model);
        EXPECT_NE(message.find("limb 1"), std::string::npos) << message;
    }
}

TEST(Workspace, ConcurrentLinkLinesAreAnActuationSingularity) {
    // Rotating the platform about O, the three link lines meet at C when h_j1 = 0 (eq. 7): the
    // actuators cannot resist a moment about C (near theta = -2.08 rad, where phi_Mj = pi/6).
    const double lo = concurrentLinkLinesRotation();
    for (const std::string& name : kPaperForms) {
        SCOPED_TRACE(name);
        const Model model(io::exampleRobot(name));
        Data data(model);
        ASSERT_TRUE(inverseDisplacement(model, data, Pose(lo, 0.0, 0.0)).ok());
        const Status status = velocityFromPlatformTwist(model, data, Twist(1.0, 0.0, 0.0));
        EXPECT_EQ(status.code, StatusCode::singular_actuation) << "theta = " << lo;
        EXPECT_GT(status.value, model.max_condition);
        // Away from it the same rotation direction is fine.
        ASSERT_TRUE(inverseDisplacement(model, data, Pose(lo + 0.3, 0.0, 0.0)).ok());
        EXPECT_TRUE(velocityFromPlatformTwist(model, data, Twist(1.0, 0.0, 0.0)).ok());
    }
}

TEST(Workspace, StrokeBeyondTheActuatorIsReportedForTheRightLimb) {
    for (const std::string& name : kPaperForms) {
        SCOPED_TRACE(name);
        const Model model(io::exampleRobot(name));
        Data data(model);
        const double half_stroke = 0.5 * io::RobotParameters{}.stroke;
        ASSERT_TRUE(inverseDisplacement(model, data, Pose(0.0, 0.0, 0.0)).ok());
        EXPECT_TRUE(checkJointLimits(model, data).ok());
        ASSERT_TRUE(inverseDisplacement(model, data, Pose(0.0, 0.03, 0.0)).ok());
        const Status status = checkJointLimits(model, data);
        ASSERT_EQ(status.code, StatusCode::joint_limit_exceeded);
        // The first limb (in the paper's order) beyond +-stroke/2 is named, with its u_j.
        ASSERT_GE(status.limb, 0);
        EXPECT_EQ(status.joint, 0);
        EXPECT_EQ(status.value, data.u(status.limb));
        EXPECT_GT(std::abs(status.value), half_stroke);
        for (int j = 0; j < status.limb; ++j) EXPECT_LE(std::abs(data.u(j)), half_stroke);
        const std::string message = describe(status, model);
        EXPECT_NE(message.find("limb " + std::to_string(status.limb + 1)), std::string::npos) << message;
        EXPECT_NE(message.find("range"), std::string::npos) << message;
    }
}

/// S(c) and its companions (planar.hpp) agree with each other: S^-1 S = 1, S^-T S^T = 1, the
/// vector forms equal the matrix ones, dS/dt equals the central difference of S(c(t)), and the
/// power of a wrench is the same in both coordinates (w^T S dp = (S^T w)^T dp).
TEST(PlatformTwistMap, CompanionsAreConsistentWithTheMatrix) {
    const Vector2 c(0.13, -0.27);
    const Twist dp(0.7, -0.2, 0.45);
    const Wrench w(-1.5, 3.0, 0.25);
    const Matrix3 S = platformTwistMap(c);
    EXPECT_LT((platformTwistOfPoseRate(c, dp) - S * dp).cwiseAbs().maxCoeff(), 1e-16);
    EXPECT_LT((poseRateOfPlatformTwist(c, S * dp) - dp).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((poseForceOfPlatformWrench(c, w) - S.transpose() * w).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((platformWrenchOfPoseForce(c, S.transpose() * w) - w).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_NEAR(w.dot(S * dp), poseForceOfPlatformWrench(c, w).dot(dp), 1e-15);
    const double h = 1e-6;
    const Matrix3 dS = (platformTwistMap(c + h * dp.tail<2>()) - platformTwistMap(c - h * dp.tail<2>())) / (2.0 * h);
    EXPECT_LT((dS - platformTwistMapRate(dp)).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_GT(std::abs(S(1, 0)), 0.1) << "S(c) is not the identity for this c";
}

}  // namespace
}  // namespace nocdyn::test
