// The exact derivatives allocate nothing per sample (derivatives.hpp): inverseDynamicsDerivatives,
// forwardDynamicsDerivatives and actuatorVariableDerivatives on a trajectory of every example
// robot, and both batches on the calling thread, a sample out of reach among them (its Status is
// found without allocating either).
#include <gtest/gtest.h>

#include "allocation_counter.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "nocdyn/batch.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

Model exampleRobot(const std::string& name) {
    std::string path = NOCDYN_SOURCE_DIR;
    path.append("/robots/").append(name).append(".yaml");
    return Model(io::loadRobotDescription(path));
}

TEST(DerivativesRealTime, PerSampleDerivativesAndTheirBatchesAllocateNothing) {
    for (const char* robot : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        const Model model = exampleRobot(robot);
        const int n = model.actuators;
        const PoseTrajectory trajectory = paperTrajectory1();
        const Eigen::Index N = 200;
        Eigen::ArrayXXd P(N, 3), dP(N, 3), ddP(N, 3);
        Pose p, dp, ddp;
        for (Eigen::Index k = 0; k < N; ++k) {
            trajectory.evaluate(static_cast<double>(k) * 2e-4, p, dp, ddp);
            P.row(k) = (p + model.home).transpose();
            dP.row(k) = dp.transpose();
            ddP.row(k) = ddp.transpose();
        }
        P(N / 2, 1) = 1e3;  // far out of reach
        Eigen::ArrayXXd d_p(N, 3 * n), d_dp(N, 3 * n), d_ddp(N, 3 * n);
        std::vector<Eigen::ArrayXXd> values(3, Eigen::ArrayXXd(N, n)), jacobians(6, Eigen::ArrayXXd(N, 3 * n));
        std::vector<Status> status(static_cast<std::size_t>(N));
        Data data(model);
        InverseDynamicsDerivatives id;
        ForwardDynamicsDerivatives fd;
        ActuatorVariableDerivatives ad;
        const ActuatorVector tau = ActuatorVector::Constant(n, 2.0);
        const long before = allocationCount();
        int failed = 0;
        double checksum = 0.0;
        for (Eigen::Index k = 0; k < N; ++k) {
            const Pose pk = P.row(k).transpose();
            const Twist dpk = dP.row(k).transpose(), ddpk = ddP.row(k).transpose();
            const Status a = inverseDynamicsDerivatives(model, data, pk, dpk, ddpk, id);
            const Status b = forwardDynamicsDerivatives(model, data, pk, dpk, tau, fd);
            const Status c = actuatorVariableDerivatives(model, data, pk, dpk, ddpk, ad);
            failed += !a.ok() + !b.ok() + !c.ok();
            if (a && b && c) checksum += id.d_p(0, 0) + fd.d_p(0, 0) + ad.ddu_p(0, 0);
        }
        const BatchResult inverse = inverseDynamicsDerivativesBatch(model, P, dP, ddP, d_p, d_dp, d_ddp, 1);
        const BatchResult actuator =
            actuatorVariableDerivativesBatch(model, P, dP, ddP,
                                             {values[0], values[1], values[2], jacobians[0], jacobians[1], jacobians[2],
                                              jacobians[3], jacobians[4], jacobians[5], status},
                                             1);
        const long after = allocationCount();
        EXPECT_EQ(after - before, 0) << robot;
        EXPECT_EQ(failed, 3) << robot;
        EXPECT_EQ(inverse.failed, 1) << robot;
        EXPECT_EQ(actuator.failed, 1) << robot;
        EXPECT_EQ(actuator.first_failure, N / 2) << robot;
        EXPECT_FALSE(status[static_cast<std::size_t>(N / 2)].ok()) << robot;
        EXPECT_EQ(status[static_cast<std::size_t>(N / 2)].code, actuator.status.code) << robot;
        EXPECT_TRUE(std::isnan(jacobians[3](N / 2, 0))) << robot;
        EXPECT_TRUE(std::isfinite(checksum + jacobians[3].row(0).sum() + d_p.row(0).sum())) << robot;
    }
}

}  // namespace
}  // namespace nocdyn::test
