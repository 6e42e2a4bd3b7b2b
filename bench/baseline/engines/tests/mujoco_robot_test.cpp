// Tests of the independent MuJoCo model of the 3-PRR robot: golden values, power balance,
// reference posture, loop closure.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "nocdyn/error.hpp"
#include "nocdyn/prr3/mujoco_robot.hpp"

// Allocation counting for the allocation-free test: every C++ allocation in this program,
// and MuJoCo's own (mju_malloc goes through mju_user_malloc when it is set).
namespace {
std::atomic<long> g_allocations{0};
void* countingMujocoMalloc(std::size_t size) {
    ++g_allocations;
    return std::malloc(size);
}
}  // namespace

void* operator new(std::size_t size) {
    ++g_allocations;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
// GCC flags free() in a replacement operator delete as mismatched with operator new, though
// the replacement pair above allocates with malloc by construction.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#ifndef NOCDYN_GOLDEN_DIR
#error "NOCDYN_GOLDEN_DIR must be defined by the build"
#endif

namespace {

using nocdyn::PoseTrajectory;
using nocdyn::io::RobotParameters;
using nocdyn::prr3::MujocoRobot;
using nocdyn::prr3::MujocoSample;

struct Golden {
    std::vector<std::string> header;
    std::vector<std::vector<double>> rows;
    [[nodiscard]] std::size_t column(const std::string& name) const {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it == header.end()) throw std::runtime_error("golden column missing: " + name);
        return static_cast<std::size_t>(it - header.begin());
    }
};

Golden readGolden(const std::string& file) {
    const std::string path = std::string(NOCDYN_GOLDEN_DIR) + "/" + file;
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open golden file " + path);
    Golden g;
    std::string line;
    std::getline(in, line);
    {
        std::stringstream ss(line);
        std::string cell;
        while (std::getline(ss, cell, ',')) g.header.push_back(cell);
    }
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::stringstream ss(line);
        std::string cell;
        std::vector<double> row;
        while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
        g.rows.push_back(row);
    }
    return g;
}

struct ColumnError {
    double max_abs = 0.0;
    double peak = 0.0;
};

void compareWithGolden(const std::string& file, const PoseTrajectory& trajectory) {
    const Golden g = readGolden(file);
    ASSERT_FALSE(g.rows.empty());
    std::vector<double> times;
    for (const auto& row : g.rows) times.push_back(row[g.column("t")]);

    MujocoRobot robot(RobotParameters{});
    const std::vector<MujocoSample> samples = robot.inverseDynamics(trajectory, times);
    ASSERT_EQ(samples.size(), times.size());

    const std::array<std::string, 4> groups = {"u", "du", "ddu", "tau"};
    for (const std::string& group : groups) {
        for (int j = 0; j < 3; ++j) {
            const std::string name = group + std::to_string(j + 1);
            const std::size_t col = g.column(name);
            ColumnError err;
            for (std::size_t k = 0; k < samples.size(); ++k) {
                const MujocoSample& s = samples[k];
                const double mine = group == "u"     ? s.u(j)
                                    : group == "du"  ? s.du(j)
                                    : group == "ddu" ? s.ddu(j)
                                                     : s.tau(j);
                const double ref = g.rows[k][col];
                err.peak = std::max(err.peak, std::abs(ref));
                err.max_abs = std::max(err.max_abs, std::abs(mine - ref));
            }
            ::testing::Test::RecordProperty(file + ":" + name + "_max_abs_error", std::to_string(err.max_abs));
            std::printf("%s %-5s peak %.6e  max |err| %.3e  relative %.3e\n", file.c_str(), name.c_str(), err.peak,
                        err.max_abs, err.max_abs / err.peak);
            EXPECT_LE(err.max_abs, 1e-9 * err.peak) << file << " column " << name;
        }
    }
    // Kinetic energy, MuJoCo's 0.5 qvel^T M qvel, against the golden column.
    const std::size_t kcol = g.column("kinetic");
    double kpeak = 0.0, kerr = 0.0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        kpeak = std::max(kpeak, std::abs(g.rows[k][kcol]));
        kerr = std::max(kerr, std::abs(samples[k].kinetic - g.rows[k][kcol]));
    }
    std::printf("%s kinetic peak %.6e  max |err| %.3e  relative %.3e\n", file.c_str(), kpeak, kerr, kerr / kpeak);
    EXPECT_LE(kerr, 1e-9 * kpeak) << file << " kinetic energy";
}

}  // namespace

TEST(MujocoRobot, GoldenPaperTrajectory1) { compareWithGolden("paper_trajectory1.csv", nocdyn::paperTrajectory1()); }

TEST(MujocoRobot, GoldenPaperTrajectory2) { compareWithGolden("paper_trajectory2.csv", nocdyn::paperTrajectory2()); }

TEST(MujocoRobot, ReferencePostureHasZeroSliderPositions) {
    MujocoRobot robot(RobotParameters{});
    Eigen::Vector3d u, du, ddu, tau;
    robot.inverseDynamicsSample(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), u, du, ddu,
                                tau);
    EXPECT_LT(u.cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT(du.cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT(ddu.cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT(tau.cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT(robot.lastClosureResidual(), 1e-12);
}

TEST(MujocoRobot, LoopClosureResidualAfterSolve) {
    MujocoRobot robot(RobotParameters{});
    const PoseTrajectory traj = nocdyn::paperTrajectory1();
    std::vector<double> times;
    for (int k = 0; k <= 200; ++k) times.push_back(1e-3 * k);
    const auto samples = robot.inverseDynamics(traj, times);
    double worst = 0.0;
    for (const auto& s : samples) worst = std::max(worst, s.closure_residual);
    std::printf("largest loop-closure residual over trajectory 1: %.3e m\n", worst);
    EXPECT_LT(worst, 1e-12);
}

// Power balance: the actuators' power sum_j tau_j du_j equals dT/dt, T = MuJoCo's kinetic
// energy. dT/dt by a five-point central difference of T along the trajectory (h = 1e-4 s:
// truncation and round-off both far below the tolerance).
TEST(MujocoRobot, PowerBalance) {
    for (const PoseTrajectory& traj : {nocdyn::paperTrajectory1(), nocdyn::paperTrajectory2()}) {
        MujocoRobot robot(RobotParameters{});
        const double h = 1e-4;
        double peak = 0.0, worst = 0.0;
        for (int k = 0; k < 100; ++k) {
            const double t = 0.001 + 0.00197 * k;
            const std::vector<double> times = {t - 2 * h, t - h, t, t + h, t + 2 * h};
            const auto s = robot.inverseDynamics(traj, times);
            const double dT = (s[0].kinetic - 8 * s[1].kinetic + 8 * s[3].kinetic - s[4].kinetic) / (12 * h);
            const double power = s[2].tau.dot(s[2].du);
            peak = std::max(peak, std::abs(power));
            worst = std::max(worst, std::abs(power - dT));
        }
        std::printf("%s: power peak %.6e W, max |tau.du - dT/dt| %.3e W\n", traj.name.c_str(), peak, worst);
        EXPECT_LE(worst, 1e-7 * peak) << traj.name;
    }
}

// A robot other than the prototype: heavier, off-centre link c.o.m., longer links.
TEST(MujocoRobot, PowerBalanceOtherRobot) {
    RobotParameters robot;
    robot.name = "other";
    robot.base_side = 0.45;
    robot.platform_side = 0.12;
    robot.link_length = 0.2;
    robot.link_com = 0.06;
    robot.slider_mass = 2.1;
    robot.link_mass = 0.9;
    robot.link_inertia = 3.1e-3;
    robot.platform_mass = 2.4;
    robot.platform_inertia = 9.7e-3;
    MujocoRobot model(robot);
    const PoseTrajectory traj = nocdyn::paperTrajectory1();
    const double h = 1e-4;
    double peak = 0.0, worst = 0.0;
    for (int k = 0; k < 50; ++k) {
        const double t = 0.0013 + 0.0019 * k;
        const auto s = model.inverseDynamics(traj, {t - 2 * h, t - h, t, t + h, t + 2 * h});
        const double dT = (s[0].kinetic - 8 * s[1].kinetic + 8 * s[3].kinetic - s[4].kinetic) / (12 * h);
        const double power = s[2].tau.dot(s[2].du);
        peak = std::max(peak, std::abs(power));
        worst = std::max(worst, std::abs(power - dT));
        EXPECT_LT(s[2].closure_residual, 1e-12);
    }
    EXPECT_LE(worst, 1e-7 * peak);
}

TEST(MujocoRobot, MjcfIsGeneratedFromParameters) {
    RobotParameters p;
    p.link_length = 0.17;
    MujocoRobot robot(p);
    const std::string xml = robot.mjcf();
    EXPECT_NE(xml.find("<connect"), std::string::npos);
    EXPECT_NE(xml.find("0.17"), std::string::npos);
    EXPECT_NE(xml.find("contact=\"disable\""), std::string::npos);
    MujocoRobot moved(std::move(robot));
    EXPECT_EQ(moved.mjcf(), xml);
}

TEST(MujocoRobot, RejectsUnphysicalRobot) {
    RobotParameters p;
    p.link_length = 0.05;  // shorter than the reference rail-to-vertex distance
    EXPECT_THROW({ MujocoRobot robot(p); }, nocdyn::Error);
}

TEST(MujocoRobot, RejectsPoseOutsideWorkspace) {
    MujocoRobot robot(RobotParameters{});
    Eigen::Vector3d u, du, ddu, tau;
    EXPECT_THROW(robot.inverseDynamicsSample(Eigen::Vector3d(0.0, 0.0, 0.2), Eigen::Vector3d::Zero(),
                                             Eigen::Vector3d::Zero(), u, du, ddu, tau),
                 nocdyn::Error);
}

TEST(MujocoRobot, SampleIsAllocationFree) {
    MujocoRobot robot(RobotParameters{});
    const PoseTrajectory traj = nocdyn::paperTrajectory2();
    constexpr int n = 200;
    std::vector<Eigen::Vector3d> P(n), DP(n), DDP(n);
    for (int k = 0; k < n; ++k) {
        nocdyn::Pose p, dp, ddp;
        traj.evaluate(1e-3 * k, p, dp, ddp);
        P[k] = p;
        DP[k] = dp;
        DDP[k] = ddp;
    }
    Eigen::Vector3d u, du, ddu, tau;
    robot.inverseDynamicsSample(P[0], DP[0], DDP[0], u, du, ddu, tau);
    mju_user_malloc = countingMujocoMalloc;
    const long before = g_allocations.load();
    for (int k = 0; k < n; ++k) robot.inverseDynamicsSample(P[k], DP[k], DDP[k], u, du, ddu, tau);
    const long after = g_allocations.load();
    // the counter does see allocations: a string copy and a MuJoCo allocation
    { const std::string copy = robot.mjcf(); }
    void* block = mju_malloc(64);
    mju_free(block);
    const long check = g_allocations.load();
    mju_user_malloc = nullptr;
    EXPECT_EQ(after - before, 0);
    EXPECT_GE(check - after, 2);
}

// Rough per-sample time (reported, never asserted).
TEST(MujocoRobot, PerSampleTiming) {
    MujocoRobot robot(RobotParameters{});
    const PoseTrajectory traj = nocdyn::paperTrajectory1();
    constexpr int n = 1000;
    std::vector<Eigen::Vector3d> P(n), DP(n), DDP(n);
    for (int k = 0; k < n; ++k) {
        nocdyn::Pose p, dp, ddp;
        traj.evaluate(1e-4 * k, p, dp, ddp);
        P[k] = p;
        DP[k] = dp;
        DDP[k] = ddp;
    }
    Eigen::Vector3d u, du, ddu, tau;
    double sink = 0.0;
    for (int k = 0; k < n; ++k) robot.inverseDynamicsSample(P[k], DP[k], DDP[k], u, du, ddu, tau);
    const int reps = 20;
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) {
        for (int k = 0; k < n; ++k) {
            robot.inverseDynamicsSample(P[k], DP[k], DDP[k], u, du, ddu, tau);
            sink += tau(0);
        }
    }
    const auto t1 = std::chrono::steady_clock::now();
    const double us = std::chrono::duration<double, std::micro>(t1 - t0).count() / (reps * n);
    std::printf("inverseDynamicsSample: %.2f us per sample (checksum %.3f)\n", us, sink);
    RecordProperty("us_per_sample", std::to_string(us));
    SUCCEED();
}
