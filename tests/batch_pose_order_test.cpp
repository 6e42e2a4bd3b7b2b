// The batches' pose column order (PoseColumns) and their limit check (ActuatorLimits): the
// [x, y, theta] columns of the tables and of Python give the twist order's numbers bit for bit,
// in column-major and row-major (NumPy's C order) layouts, and the fused check names the same
// first sample and Status as the full path's checkJointLimits and checkEffort.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "batch_packets.hpp"
#include "nocdyn/batch.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/pose_order.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

/// The batch's tests on packets of four and of eight samples.
class PoseColumnsBatch : public BatchPacketsTest {};
NOCDYN_BATCH_PACKETS(PoseColumnsBatch);
class BatchLimits : public BatchPacketsTest {};
NOCDYN_BATCH_PACKETS(BatchLimits);

using Stride = Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>;
using Map = Eigen::Map<Eigen::ArrayXXd, 0, Stride>;

/// An N x columns array over `storage`, column-major or row-major (NumPy's C order).
Map view(std::vector<double>& storage, Eigen::Index rows, Eigen::Index columns, bool row_major) {
    storage.assign(static_cast<std::size_t>(rows * columns), 0.0);
    return {storage.data(), rows, columns, row_major ? Stride(1, columns) : Stride(rows, 1)};
}

/// Trajectory 1 about home, with a sample of each batch out of reach, in `order`.
void fill(const Model& model, PoseColumns order, Map& p, Map& dp, Map& ddp) {
    const PoseTrajectory trajectory = paperTrajectory1();
    for (Eigen::Index k = 0; k < p.rows(); ++k) {
        Pose pk, dpk, ddpk;
        trajectory.evaluate(static_cast<double>(k) * 3e-4, pk, dpk, ddpk);
        pk += model.home;
        if (k == 13) pk(1) += 0.5;  // x 0.5 m away: out of reach
        for (int i = 0; i < 3; ++i) {
            p(k, poseColumn(order, i)) = pk(i);
            dp(k, poseColumn(order, i)) = dpk(i);
            ddp(k, poseColumn(order, i)) = ddpk(i);
        }
    }
}

TEST(PoseColumns, XYThetaIsTheTablesOrder) {
    EXPECT_EQ(poseColumn(PoseColumns::x_y_theta, 0), 2);  // theta last
    EXPECT_EQ(poseColumn(PoseColumns::x_y_theta, 1), 0);  // x first
    EXPECT_EQ(poseColumn(PoseColumns::x_y_theta, 2), 1);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(poseColumn(PoseColumns::theta_x_y, i), i);
    // the user's pose of pose_order.hpp: coordinate i of the core at column poseColumn(x_y_theta, i)
    const Pose p(0.25, -1.5, 3.0);
    const Vector3 user = userPose(p);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(user(poseColumn(PoseColumns::x_y_theta, i)), p(i));
    EXPECT_EQ(corePose(user), p);
}

TEST_P(PoseColumnsBatch, EveryBatchGivesTheTwistOrdersNumbersBitForBit) {
    for (const std::string robot : {"paper-3prr", "3-rrr", "4-rrr"}) {
        const Model model(io::exampleRobot(robot));
        const Eigen::Index N = 41, n = model.actuators;  // not a multiple of 4: the tail too
        for (const bool row_major : {false, true}) {
            std::vector<double> store[2][3];
            std::vector<double> outs[2][4], derivatives[2][3], reactions[2];
            Eigen::ArrayXXd results[2][4], d[2][3], r[2];
            BatchResult batch[2];
            for (const int o : {0, 1}) {
                const PoseColumns order = o == 0 ? PoseColumns::theta_x_y : PoseColumns::x_y_theta;
                Map p = view(store[o][0], N, 3, row_major), dp = view(store[o][1], N, 3, row_major),
                    ddp = view(store[o][2], N, 3, row_major);
                fill(model, order, p, dp, ddp);
                Map u = view(outs[o][0], N, n, row_major), du = view(outs[o][1], N, n, row_major),
                    ddu = view(outs[o][2], N, n, row_major), tau = view(outs[o][3], N, n, row_major);
                batch[o] = inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1, order);
                results[o][0] = u, results[o][1] = du, results[o][2] = ddu, results[o][3] = tau;
                Map dp_ = view(derivatives[o][0], N, 3 * n, true), ddp_ = view(derivatives[o][1], N, 3 * n, true),
                    dddp_ = view(derivatives[o][2], N, 3 * n, true);
                EXPECT_EQ(inverseDynamicsDerivativesBatch(model, p, dp, ddp, dp_, ddp_, dddp_, 1, order).failed, 1);
                // d tau_a/d x_i at column 3 a + poseColumn(order, i): back to the twist order
                for (int c = 0; c < 3; ++c) {
                    const Map& m = c == 0 ? dp_ : c == 1 ? ddp_ : dddp_;
                    d[o][c].resize(N, 3 * n);
                    for (Eigen::Index a = 0; a < n; ++a)
                        for (int i = 0; i < 3; ++i) d[o][c].col(3 * a + i) = m.col(3 * a + poseColumn(order, i));
                }
                Map reaction = view(reactions[o], N, 9 * model.limbs, row_major);
                EXPECT_EQ(reactionsBatch(model, p, dp, ddp, reaction, 1, order).failed, 1);
                r[o] = reaction;
            }
            const std::string where = robot + (row_major ? ", row-major" : ", column-major");
            EXPECT_EQ(batch[0].failed, 1) << where;
            EXPECT_EQ(batch[1].failed, 1) << where;
            EXPECT_EQ(batch[1].first_failure, 13) << where;
            EXPECT_EQ(batch[1].status.code, batch[0].status.code) << where;
            for (int i = 0; i < 4; ++i) {
                EXPECT_TRUE(results[1][i].isNaN().row(13).all()) << where;
                results[0][i].row(13).setZero(), results[1][i].row(13).setZero();
                EXPECT_TRUE((results[0][i] == results[1][i]).all()) << where << ", output " << i;
            }
            for (int c = 0; c < 3; ++c) {
                d[0][c].row(13).setZero(), d[1][c].row(13).setZero();
                EXPECT_TRUE((d[0][c] == d[1][c]).all()) << where << ", derivative " << c;
            }
            r[0].row(13).setZero(), r[1].row(13).setZero();
            EXPECT_TRUE((r[0] == r[1]).all()) << where << ", reactions";
        }
    }
}

TEST_P(BatchLimits, TheBatchNamesTheFullPathsFirstSampleAndStatus) {
    const Model model(io::exampleRobot("paper-3prr"));  // ranges +-12.45 mm, efforts 262 N
    const Eigen::Index N = 64;
    Eigen::ArrayX3d p(N, 3), dp = Eigen::ArrayX3d::Zero(N, 3), ddp = Eigen::ArrayX3d::Zero(N, 3);
    for (Eigen::Index k = 0; k < N; ++k) p.row(k) = model.home.transpose();
    // sample 22: an effort beyond 262 N; sample 37: actuator 1 at 20 mm; sample 50 both
    ddp(22, 1) = 1000.0;
    p(37, 1) = 0.02;
    p(50, 1) = 0.02;
    ddp(50, 1) = 1000.0;
    const Eigen::Index n = model.actuators;
    Eigen::ArrayXXd u(N, n), du(N, n), ddu(N, n), tau(N, n);
    Data data(model);
    const auto expected = [&](Eigen::Index k) {
        EXPECT_TRUE(inverseDynamics(model, data, p.row(k).transpose(), dp.row(k).transpose(), ddp.row(k).transpose()));
        const Status range = checkJointLimits(model, data);
        return range ? checkEffort(model, data) : range;
    };
    for (const unsigned threads : {1u, 2u}) {
        const BatchResult result = inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, threads,
                                                        PoseColumns::theta_x_y, ActuatorLimits::check);
        EXPECT_TRUE(result.ok());
        ASSERT_EQ(result.first_beyond_limits, 22) << threads;
        const Status full = expected(22);
        EXPECT_EQ(result.limits.code, StatusCode::effort_exceeded);
        EXPECT_EQ(result.limits.code, full.code);
        EXPECT_EQ(result.limits.limb, full.limb);
        EXPECT_EQ(result.limits.joint, full.joint);
        EXPECT_NEAR(result.limits.value, full.value, 1e-12 * std::abs(full.value));
        // the outputs are written all the same
        EXPECT_TRUE(tau.allFinite());
    }
    ddp(22, 1) = 0.0;
    const BatchResult range =
        inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1, PoseColumns::theta_x_y, ActuatorLimits::check);
    ASSERT_EQ(range.first_beyond_limits, 37);
    EXPECT_EQ(range.limits.code, StatusCode::joint_limit_exceeded);
    EXPECT_EQ(range.limits.code, expected(37).code);
    EXPECT_EQ(range.limits.value, expected(37).value);
    const Status one = checkActuatorLimits(model, data.u, data.du, data.tau);
    EXPECT_EQ(one.code, StatusCode::joint_limit_exceeded);
    // without the check nothing is named
    EXPECT_EQ(inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1).first_beyond_limits, BatchResult::npos);
}

/// The 3-RPR with a range of +-0.01 rad on limb 1's passive base pivot: a limit the
/// kernel's check from u, du and tau cannot see.
Model limitedPassivePivot() {
    RobotDescription robot = io::exampleRobot("3-rpr");
    robot.limbs[0].joints[0].limits.lower = -0.01;
    robot.limbs[0].joints[0].limits.upper = 0.01;
    return Model(robot);
}

TEST_P(BatchLimits, EveryJointChecksALimitedPassiveJointByTheFullPathAsOneSampleIsChecked) {
    const Model model = limitedPassivePivot();
    EXPECT_FALSE(limitsOnActuatedJointsOnly(model));
    EXPECT_TRUE(limitsOnActuatedJointsOnly(Model(io::exampleRobot("3-rpr"))));
    const Eigen::Index N = 6;
    Eigen::ArrayX3d p(N, 3), dp = Eigen::ArrayX3d::Zero(N, 3), ddp = Eigen::ArrayX3d::Zero(N, 3);
    for (Eigen::Index k = 0; k < N; ++k) p.row(k) = model.home.transpose();
    p(4, 1) += 0.005;  // x 5 mm off home: limb 1's pivot turns beyond 0.01 rad
    Eigen::ArrayXXd u(N, model.actuators), du(N, model.actuators), ddu(N, model.actuators), tau(N, model.actuators);
    // the single sample's own check: the full path's checkJointLimits, then checkEffort
    Data data(model);
    ASSERT_TRUE(inverseDynamics(model, data, p.row(4).transpose(), dp.row(4).transpose(), ddp.row(4).transpose()));
    const Status one = checkSampleLimits(model, data);
    ASSERT_EQ(one.code, StatusCode::joint_limit_exceeded);
    EXPECT_EQ(one.limb, 0);
    EXPECT_EQ(one.joint, 0);
    // ActuatorLimits::check sees only the actuated joints; every_joint sees the pivot
    const BatchResult actuated =
        inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1, PoseColumns::theta_x_y, ActuatorLimits::check);
    EXPECT_EQ(actuated.first_beyond_limits, BatchResult::npos);
    for (const unsigned threads : {1u, 2u}) {
        const BatchResult every = inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, threads,
                                                       PoseColumns::theta_x_y, ActuatorLimits::every_joint);
        EXPECT_TRUE(every.ok());
        ASSERT_EQ(every.first_beyond_limits, 4) << threads;
        EXPECT_EQ(every.limits.code, one.code);
        EXPECT_EQ(every.limits.value, one.value);
        // the words both front ends show: the sample numbered from 1
        EXPECT_EQ(describeLimits(model, every), "sample 5: " + describe(one, model));
        EXPECT_EQ(describeFailure(model, every, N), "");
    }
    // the same numbers as without any check
    Eigen::ArrayXXd u0(N, model.actuators), du0(N, model.actuators), ddu0(N, model.actuators), tau0(N, model.actuators);
    ASSERT_TRUE(inverseDynamicsBatch(model, p, dp, ddp, u0, du0, ddu0, tau0).ok());
    EXPECT_TRUE((tau0 == tau).all());
}

TEST_P(BatchLimits, EveryJointOnActuatedLimitsIsTheKernelsCheckAndAFailureIsNamedFromOne) {
    const Model model(io::exampleRobot("paper-3prr"));
    ASSERT_TRUE(limitsOnActuatedJointsOnly(model));
    const Eigen::Index N = 8;
    Eigen::ArrayX3d p(N, 3), dp = Eigen::ArrayX3d::Zero(N, 3), ddp = Eigen::ArrayX3d::Zero(N, 3);
    for (Eigen::Index k = 0; k < N; ++k) p.row(k) = model.home.transpose();
    p(2, 1) = 0.5;   // out of reach
    p(6, 1) = 0.02;  // actuator 1 at 20 mm on a 12.45 mm range
    Eigen::ArrayXXd u(N, 3), du(N, 3), ddu(N, 3), tau(N, 3);
    const BatchResult check =
        inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1, PoseColumns::theta_x_y, ActuatorLimits::check);
    const BatchResult every = inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, 1, PoseColumns::theta_x_y,
                                                   ActuatorLimits::every_joint);
    ASSERT_EQ(every.first_beyond_limits, 6);
    EXPECT_EQ(every.first_beyond_limits, check.first_beyond_limits);
    EXPECT_EQ(every.limits.code, check.limits.code);
    EXPECT_EQ(every.limits.value, check.limits.value);
    ASSERT_EQ(every.first_failure, 2);
    EXPECT_EQ(describeFailure(model, every, N),
              "sample 3: " + describe(every.status, model) + " (1 of 8 samples failed)");
    EXPECT_EQ(describeLimits(model, every), "sample 7: " + describe(every.limits, model));
}

}  // namespace
}  // namespace nocdyn::test
