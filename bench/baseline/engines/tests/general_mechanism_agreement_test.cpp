// The general engine models (validation/) of the paper's robot against the 3-PRR engine models
// written for it alone: the same actuator motions and forces, in Simbody and in MuJoCo.
#include <algorithm>
#include <cstdio>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "nocdyn/io/short_form.hpp"
#include "nocdyn/description.hpp"
#include "nocdyn/prr3/mujoco_robot.hpp"
#include "nocdyn/prr3/simbody_robot.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/validation/mujoco_mechanism.hpp"
#include "nocdyn/validation/simbody_mechanism.hpp"

using nocdyn::PoseTrajectory;
using nocdyn::io::RobotParameters;
using nocdyn::validation::MujocoMechanism;
using nocdyn::validation::SimbodyMechanism;

namespace {

// Agreement required of forces, relative to the peak over the samples.
constexpr double kRelativeTolerance = 1e-9;

std::vector<double> linspace(double t0, double t1, int n) {
    std::vector<double> t(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) t[static_cast<std::size_t>(k)] = t0 + (t1 - t0) * k / (n - 1);
    return t;
}

TEST(GeneralMechanism, PaperRobotAgreesWith3PrrEngineModels) {
    const std::vector<double> times = linspace(0.0, 0.2, 401);
    for (const PoseTrajectory& trajectory : {nocdyn::paperTrajectory1(), nocdyn::paperTrajectory2()}) {
        SimbodyMechanism simbody(nocdyn::io::expand(RobotParameters{}));
        MujocoMechanism mujoco(nocdyn::io::expand(RobotParameters{}));
        nocdyn::prr3::SimbodyRobot simbody_3prr{RobotParameters{}};
        nocdyn::prr3::MujocoRobot mujoco_3prr{RobotParameters{}};
        const auto a = simbody.inverseDynamics(trajectory, times);
        const auto b = mujoco.inverseDynamics(trajectory, times);
        const auto c = simbody_3prr.inverseDynamics(trajectory, times);
        const auto d = mujoco_3prr.inverseDynamics(trajectory, times);
        double peak = 0.0, err_ab = 0.0, err_ac = 0.0, err_bd = 0.0;
        for (std::size_t k = 0; k < times.size(); ++k) {
            const Eigen::Vector3d ta = a[k].tau, tb = b[k].tau;
            peak = std::max(peak, c[k].tau.cwiseAbs().maxCoeff());
            err_ab = std::max(err_ab, (ta - tb).cwiseAbs().maxCoeff());
            err_ac = std::max(err_ac, (ta - c[k].tau).cwiseAbs().maxCoeff());
            err_bd = std::max(err_bd, (tb - d[k].tau).cwiseAbs().maxCoeff());
            EXPECT_LE((Eigen::Vector3d(a[k].u) - c[k].u).cwiseAbs().maxCoeff(), 1e-13);
            EXPECT_LE((Eigen::Vector3d(b[k].u) - d[k].u).cwiseAbs().maxCoeff(), 1e-13);
        }
        std::printf(
            "[paper %s] peak %.3f N; |general simbody - mujoco| %.3e N (%.2e), "
            "|general - 3-PRR| simbody %.3e N, mujoco %.3e N\n",
            trajectory.name.c_str(), peak, err_ab, err_ab / peak, err_ac, err_bd);
        EXPECT_LE(err_ab, kRelativeTolerance * peak);
        EXPECT_LE(err_ac, kRelativeTolerance * peak);
        EXPECT_LE(err_bd, kRelativeTolerance * peak);
    }
}

}  // namespace
