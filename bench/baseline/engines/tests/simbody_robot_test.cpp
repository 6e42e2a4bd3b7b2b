// Tests of the independent Simbody model of the 3-PRR robot (ctest label: validation).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "nocdyn/error.hpp"
#include "nocdyn/io/short_form.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/prr3/simbody_robot.hpp"

using nocdyn::PoseTrajectory;
using nocdyn::io::RobotParameters;
using nocdyn::prr3::EngineSample;
using nocdyn::prr3::SimbodyRobot;

namespace {

std::vector<double> linspace(double t0, double t1, int n) {
    std::vector<double> t(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) t[static_cast<std::size_t>(i)] = t0 + (t1 - t0) * i / (n - 1);
    return t;
}

/// Trajectory whose every axis is offset + a cos(2 pi f t): at rest at t = 0.
PoseTrajectory restingTrajectory() {
    PoseTrajectory tr;
    tr.name = "resting";
    const double half_pi = 1.5707963267948966;
    tr.theta.offset = 0.01;
    tr.theta.harmonics = {{0.04, 7.0, half_pi}};
    tr.x.offset = 0.002;
    tr.x.harmonics = {{-0.003, 11.0, half_pi}};
    tr.y.offset = -0.001;
    tr.y.harmonics = {{0.004, 5.0, half_pi}};
    return tr;
}

struct GoldenTable {
    std::vector<std::string> header;
    std::vector<std::vector<double>> rows;
    int col(const std::string& name) const {
        const auto it = std::find(header.begin(), header.end(), name);
        return it == header.end() ? -1 : static_cast<int>(it - header.begin());
    }
};

GoldenTable readGolden(const std::string& path) {
    GoldenTable g;
    std::ifstream in(path);
    if (!in) return g;
    std::string line;
    std::getline(in, line);
    {
        std::stringstream ss(line);
        std::string f;
        while (std::getline(ss, f, ',')) g.header.push_back(f);
    }
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::vector<double> row;
        std::stringstream ss(line);
        std::string f;
        while (std::getline(ss, f, ',')) row.push_back(std::stod(f));
        g.rows.push_back(row);
    }
    return g;
}

void compareWithGolden(const std::string& file, const PoseTrajectory& trajectory) {
    const GoldenTable g = readGolden(std::string(NOCDYN_GOLDEN_DIR) + "/" + file);
    ASSERT_FALSE(g.rows.empty()) << "cannot read " << NOCDYN_GOLDEN_DIR << "/" << file;
    const int ct = g.col("t");
    ASSERT_GE(ct, 0);
    std::vector<double> times;
    for (const auto& r : g.rows) times.push_back(r[static_cast<std::size_t>(ct)]);

    SimbodyRobot robot{RobotParameters{}};
    const std::vector<EngineSample> s = robot.inverseDynamics(trajectory, times);
    ASSERT_EQ(s.size(), times.size());

    struct Quantity {
        const char* name;
        Eigen::Vector3d EngineSample::*field;
    };
    const Quantity quantities[] = {
        {"u", &EngineSample::u}, {"du", &EngineSample::du}, {"ddu", &EngineSample::ddu}, {"tau", &EngineSample::tau}};
    for (const Quantity& q : quantities) {
        for (int j = 0; j < 3; ++j) {
            const std::string name = std::string(q.name) + std::to_string(j + 1);
            const int c = g.col(name);
            ASSERT_GE(c, 0) << name;
            double peak = 0.0;
            double err = 0.0;
            for (std::size_t k = 0; k < s.size(); ++k) {
                const double ref = g.rows[k][static_cast<std::size_t>(c)];
                peak = std::max(peak, std::abs(ref));
                err = std::max(err, std::abs((s[k].*(q.field))[j] - ref));
            }
            std::printf("[golden %s] %-5s max |err| = %.3e  peak = %.6g  rel = %.3e\n", file.c_str(), name.c_str(), err,
                        peak, err / peak);
            EXPECT_LE(err, 1e-9 * peak) << file << " " << name;
        }
    }
    // Pose and kinetic energy too.
    const char* pose_cols[] = {"theta", "x", "y"};
    for (int i = 0; i < 3; ++i) {
        const int c = g.col(pose_cols[i]);
        ASSERT_GE(c, 0);
        for (std::size_t k = 0; k < s.size(); ++k) {
            EXPECT_NEAR(s[k].pose[i], g.rows[k][static_cast<std::size_t>(c)], 1e-12);
        }
    }
    const int ck = g.col("kinetic");
    ASSERT_GE(ck, 0);
    double peak = 0.0;
    double err = 0.0;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const double ref = g.rows[k][static_cast<std::size_t>(ck)];
        peak = std::max(peak, std::abs(ref));
        err = std::max(err, std::abs(s[k].kinetic - ref));
    }
    std::printf("[golden %s] kinetic max |err| = %.3e  peak = %.6g  rel = %.3e\n", file.c_str(), err, peak, err / peak);
    EXPECT_LE(err, 1e-9 * peak);
}

}  // namespace

TEST(SimbodyRobot, SliderCoordinatesVanishAtReferencePosture) {
    SimbodyRobot robot{RobotParameters{}};
    robot.resetPlant(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    EXPECT_LT(robot.u().cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT(robot.pose().cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_EQ(robot.kineticEnergy(), 0.0);

    // A robot with other proportions too.
    RobotParameters other;
    other.base_side = 0.5;
    other.platform_side = 0.2;
    other.link_length = 0.12;
    other.link_com = 0.03;
    SimbodyRobot robot2{other};
    robot2.resetPlant(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    EXPECT_LT(robot2.u().cwiseAbs().maxCoeff(), 1e-14);

    // Held at the reference posture: no motion, no force.
    const PoseTrajectory still;  // all axes zero
    const auto s = robot.inverseDynamics(still, {0.0, 0.5});
    for (const auto& e : s) {
        EXPECT_LT(e.u.cwiseAbs().maxCoeff(), 1e-14);
        EXPECT_LT(e.tau.cwiseAbs().maxCoeff(), 1e-12);
    }
}

TEST(SimbodyRobot, AssembledPoseEqualsRequestedPose) {
    SimbodyRobot robot{RobotParameters{}};
    const PoseTrajectory tr = nocdyn::paperTrajectory1();
    const auto times = linspace(0.0, 0.1, 41);
    const auto s = robot.inverseDynamics(tr, times);
    for (std::size_t k = 0; k < s.size(); ++k) {
        Eigen::Vector3d p, dp, ddp;
        tr.evaluate(times[k], p, dp, ddp);
        EXPECT_LT((s[k].pose - p).cwiseAbs().maxCoeff(), 1e-13) << "t = " << times[k];
    }
    const Eigen::Vector3d pose(0.05, 0.004, -0.003);
    const Eigen::Vector3d rate(0.7, -0.02, 0.03);
    robot.resetPlant(pose, rate);
    EXPECT_LT((robot.pose() - pose).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT((robot.poseRate() - rate).cwiseAbs().maxCoeff(), 1e-13);
    // The sliders moved: u is far from zero at that pose.
    EXPECT_GT(robot.u().cwiseAbs().maxCoeff(), 1e-3);
}

TEST(SimbodyRobot, ActuatorForcesSatisfyPowerBalance) {
    // sum_j tau_j du_j = dT/dt (no gravity in the horizontal plane, no friction), with T from
    // Simbody's calcKineticEnergy differentiated by a 4th-order central difference.
    SimbodyRobot robot{RobotParameters{}};
    const PoseTrajectory tr = nocdyn::paperTrajectory1();
    const double h = 1e-4;
    double peak = 0.0;
    double err = 0.0;
    for (double t : linspace(0.003, 0.097, 19)) {
        const auto s = robot.inverseDynamics(tr, {t - 2 * h, t - h, t, t + h, t + 2 * h});
        const double dT = (s[0].kinetic - 8 * s[1].kinetic + 8 * s[3].kinetic - s[4].kinetic) / (12 * h);
        const double power = s[2].tau.dot(s[2].du);
        peak = std::max(peak, std::abs(power));
        err = std::max(err, std::abs(power - dT));
    }
    std::printf("[power balance] max |tau.du - dT/dt| = %.3e W, peak power %.4g W\n", err, peak);
    ASSERT_GT(peak, 1.0);
    EXPECT_LT(err, 1e-6 * peak);
}

TEST(SimbodyRobot, JointSpaceInertiaIsSymmetricPositiveDefinite) {
    SimbodyRobot robot{RobotParameters{}};
    const Eigen::Vector3d poses[] = {
        {0.0, 0.0, 0.0}, {0.05, 0.004, -0.003}, {-0.08, -0.006, 0.005}, {0.02, 0.008, 0.008}};
    for (const auto& p : poses) {
        const Eigen::Matrix3d I = robot.jointSpaceInertia(p);
        EXPECT_LT((I - I.transpose()).cwiseAbs().maxCoeff(), 1e-12 * I.cwiseAbs().maxCoeff());
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (I + I.transpose()));
        EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
        // Every slider carries at least its own mass.
        for (int j = 0; j < 3; ++j) EXPECT_GT(I(j, j), RobotParameters{}.slider_mass);
    }
    // By the robot's symmetry, the reference-posture inertia has equal diagonal entries.
    const Eigen::Matrix3d I0 = robot.jointSpaceInertia(Eigen::Vector3d::Zero());
    EXPECT_NEAR(I0(0, 0), I0(1, 1), 1e-12);
    EXPECT_NEAR(I0(0, 0), I0(2, 2), 1e-12);
}

TEST(SimbodyRobot, InertiaTimesAccelerationEqualsForceAtRest) {
    // At rest (du = 0) the inverse dynamics reduces to tau = I(u) ddu: ties the two
    // computations (findMotionForces and N^T M N) together.
    SimbodyRobot robot{RobotParameters{}};
    const PoseTrajectory tr = restingTrajectory();
    const auto s = robot.inverseDynamics(tr, {0.0});
    ASSERT_LT(s[0].du.cwiseAbs().maxCoeff(), 1e-15);
    const Eigen::Matrix3d I = robot.jointSpaceInertia(s[0].pose);
    const Eigen::Vector3d tau = I * s[0].ddu;
    EXPECT_LT((tau - s[0].tau).cwiseAbs().maxCoeff(), 1e-10 * s[0].tau.cwiseAbs().maxCoeff());
    EXPECT_GT(s[0].tau.cwiseAbs().maxCoeff(), 1.0);
}

TEST(SimbodyRobot, MatchesGoldenTrajectory1) { compareWithGolden("paper_trajectory1.csv", nocdyn::paperTrajectory1()); }

TEST(SimbodyRobot, MatchesGoldenTrajectory2) { compareWithGolden("paper_trajectory2.csv", nocdyn::paperTrajectory2()); }

TEST(SimbodyRobot, PlantConservesKineticEnergyWithoutForces) {
    SimbodyRobot robot{RobotParameters{}};
    robot.resetPlant(Eigen::Vector3d(0.01, 0.001, -0.002), Eigen::Vector3d(0.8, 0.03, -0.02));
    const double T0 = robot.kineticEnergy();
    ASSERT_GT(T0, 1e-4);
    double worst = 0.0;
    for (int k = 0; k < 10; ++k) {
        robot.advance(0.01);
        worst = std::max(worst, std::abs(robot.kineticEnergy() - T0) / T0);
    }
    std::printf("[plant] kinetic energy drift over 0.1 s: %.3e (relative)\n", worst);
    EXPECT_NEAR(robot.time(), 0.1, 1e-14);
    EXPECT_LT(worst, 1e-8);
    // It really moved.
    EXPECT_GT(std::abs(robot.pose()[0] - 0.01), 0.01);
}

TEST(SimbodyRobot, PlantAcceleratesAsInverseDynamicsPredicts) {
    // Forward dynamics with the inverse-dynamics forces gives back the slider accelerations:
    // an independent check of the sign and size of tau.
    SimbodyRobot robot{RobotParameters{}};
    const PoseTrajectory tr = nocdyn::paperTrajectory1();
    for (double t0 : {0.0, 0.013, 0.042}) {
        const auto s = robot.inverseDynamics(tr, {t0});
        Eigen::Vector3d p, dp, ddp;
        tr.evaluate(t0, p, dp, ddp);
        robot.resetPlant(p, dp);
        EXPECT_LT((robot.du() - s[0].du).cwiseAbs().maxCoeff(), 1e-12);
        robot.setActuatorForces(s[0].tau);
        const double h = 1e-6;
        robot.advance(h);
        const Eigen::Vector3d ddu = (robot.du() - s[0].du) / h;
        EXPECT_LT((ddu - s[0].ddu).cwiseAbs().maxCoeff(), 1e-3 * s[0].ddu.cwiseAbs().maxCoeff())
            << "t0 = " << t0 << " plant " << ddu.transpose() << " vs " << s[0].ddu.transpose();
    }
}

TEST(SimbodyRobot, LargeStepsBetweenSamplesStayOnTheIntendedBranch) {
    // Large rotations sampled coarsely: the continuation seed is far off, so the fallbacks
    // (Assembler, then a seed on the intended branch) must give the same answer as a fine,
    // continuous sampling.
    PoseTrajectory tr;
    tr.theta.harmonics = {{0.8, 3.0, 1.5707963267948966}};  // first sample at -> 0.8 rad
    tr.x.harmonics = {{0.01, 2.0, 0.0}};
    tr.y.harmonics = {{-0.008, 4.0, 1.0}};
    const std::vector<double> coarse = {0.0, 0.16, 0.02, 0.17, 0.31};
    SimbodyRobot robot{RobotParameters{}};
    const auto a = robot.inverseDynamics(tr, coarse);
    for (std::size_t k = 0; k < coarse.size(); ++k) {
        // Fine sampling up to the same instant.
        const auto b = robot.inverseDynamics(tr, linspace(0.0, coarse[k], 400));
        const EngineSample& fine = b.back();
        EXPECT_LT((a[k].u - fine.u).cwiseAbs().maxCoeff(), 1e-13) << "t = " << coarse[k];
        EXPECT_LT((a[k].tau - fine.tau).cwiseAbs().maxCoeff(), 1e-11 * (1.0 + fine.tau.cwiseAbs().maxCoeff()))
            << "t = " << coarse[k];
    }
}

TEST(SimbodyRobot, PoseOutsideWorkspaceIsRejected) {
    SimbodyRobot robot{RobotParameters{}};
    PoseTrajectory far;
    far.y.offset = -0.2;  // the platform would cross the base side of limb 1
    try {
        (void)robot.inverseDynamics(far, {0.0});
        FAIL() << "expected nocdyn::Error";
    } catch (const nocdyn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("outside the workspace"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)robot.jointSpaceInertia(Eigen::Vector3d(0.0, 0.3, 0.0)), nocdyn::Error);
}
