// The frozen 3-PRR kernel against its own 3-PRR engine models: Simbody (reference) and MuJoCo, on the
// paper's trajectories and on random robots driven along random multi-harmonic
// trajectories inside the workspace. Forces within 1e-9 of the peak force; the joint-space
// inertia against Simbody's N^T M N to 1e-10.
#include <gtest/gtest.h>

#include <cstdio>

#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/prr3/mujoco_robot.hpp"
#include "nocdyn/prr3/simbody_robot.hpp"
#include "baseline_support.hpp"

namespace nocdyn::test {
namespace {

constexpr double kForceOfPeak = 1e-9;
constexpr double kInertiaRelative = 1e-10;

/// The 3-PRR model's inverse dynamics at each time.
struct Series {
    std::vector<double> t;
    std::vector<Pose> p;
    std::vector<prr3::JointVector> u, tau;
};
Series inverseDynamicsAlong(const prr3::Model& model, const PoseTrajectory& trajectory,
                            const std::vector<double>& times) {
    Series series;
    prr3::Data data;
    for (const double t : times) {
        Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        const auto status = prr3::inverseDynamics(model, data, p, dp, ddp);
        EXPECT_TRUE(status.ok()) << "t = " << t << ": " << describe(status, model.parameters);
        series.t.push_back(t);
        series.p.push_back(p);
        series.u.push_back(data.u);
        series.tau.push_back(data.tau);
    }
    return series;
}

/// Largest |tau - tau_engine| over the peak |tau| of our model.
template <typename Samples>
double forceErrorOfPeak(const Series& ours, const Samples& engine) {
    double peak = 0.0, worst = 0.0;
    for (std::size_t k = 0; k < ours.t.size(); ++k) {
        peak = std::max(peak, ours.tau[k].cwiseAbs().maxCoeff());
        worst = std::max(worst, (ours.tau[k] - engine[k].tau).cwiseAbs().maxCoeff());
        EXPECT_LT((ours.u[k] - engine[k].u).cwiseAbs().maxCoeff(), 1e-12) << "t = " << ours.t[k];
    }
    return worst / peak;
}

io::RobotParameters randomRobot(std::mt19937& rng) {
    auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    io::RobotParameters robot;
    robot.name = "random";
    robot.base_side = uniform(0.3, 0.5);
    robot.platform_side = uniform(0.05, 0.15);
    const double d_ref = 0.5 * (robot.baseCircumradius() - robot.platformCircumradius());
    robot.link_length = d_ref / uniform(0.35, 0.75);
    robot.link_com = robot.link_length * uniform(0.0, 1.0);
    robot.slider_mass = uniform(0.5, 3.0);
    robot.link_mass = uniform(0.2, 1.5);
    robot.link_inertia = robot.link_mass * robot.link_length * robot.link_length * uniform(0.02, 0.15);
    robot.platform_mass = uniform(0.5, 4.0);
    robot.platform_inertia =
        robot.platform_mass * robot.platformCircumradius() * robot.platformCircumradius() * uniform(0.2, 1.0);
    robot.stroke = 1.0;  // limits are not what this test is about
    robot.peak_force = 1e6;
    return robot;
}

PoseTrajectory randomTrajectory(std::mt19937& rng, double scale) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0), frequency(1.0, 30.0), phase(-3.0, 3.0);
    auto axis = [&](double size) {
        AxisMotion motion{0.3 * size * unit(rng), {}};
        for (int k = 0; k < 3; ++k) motion.harmonics.push_back({0.25 * size * unit(rng), frequency(rng), phase(rng)});
        return motion;
    };
    PoseTrajectory trajectory;
    trajectory.name = "random";
    trajectory.theta = axis(0.15);
    trajectory.x = axis(scale);
    trajectory.y = axis(scale);
    return trajectory;
}

TEST(Validation, PaperTrajectoriesAgreeWithSimbodyAndMujoco) {
    const io::RobotParameters robot;
    const prr3::Model model(robot);
    prr3::SimbodyRobot simbody(robot);
    prr3::MujocoRobot mujoco(robot);
    const auto times = sampleTimes(0.2, 2000.0);
    for (const PoseTrajectory& trajectory : {paperTrajectory1(), paperTrajectory2()}) {
        const auto ours = inverseDynamicsAlong(model, trajectory, times);
        EXPECT_LT(forceErrorOfPeak(ours, simbody.inverseDynamics(trajectory, times)), kForceOfPeak) << trajectory.name;
        EXPECT_LT(forceErrorOfPeak(ours, mujoco.inverseDynamics(trajectory, times)), kForceOfPeak) << trajectory.name;
    }
}

TEST(Validation, RandomRobotsOnRandomTrajectoriesAgreeWithSimbodyAndMujoco) {
    std::mt19937 rng(31);
    const auto times = sampleTimes(0.25, 400.0);
    int tried = 0, compared = 0;
    while (compared < 12 && tried < 200) {
        ++tried;
        const io::RobotParameters robot = randomRobot(rng);
        const prr3::Model model(robot);
        const PoseTrajectory trajectory = randomTrajectory(rng, 0.15 * robot.link_length);
        // Keep trajectories that stay inside the workspace, well away from singularities.
        bool inside = true;
        prr3::Data data;
        for (double t : times) {
            Pose p, dp, ddp;
            trajectory.evaluate(t, p, dp, ddp);
            inside =
                inside && prr3::inverseDynamics(model, data, p, dp, ddp).ok() && data.cond_H < 100 && data.cond_D < 100;
        }
        if (!inside) continue;
        ++compared;
        const auto ours = inverseDynamicsAlong(model, trajectory, times);
        prr3::SimbodyRobot simbody(robot);
        prr3::MujocoRobot mujoco(robot);
        const double simbody_error = forceErrorOfPeak(ours, simbody.inverseDynamics(trajectory, times));
        const double mujoco_error = forceErrorOfPeak(ours, mujoco.inverseDynamics(trajectory, times));
        EXPECT_LT(simbody_error, kForceOfPeak) << "random robot " << compared << ", link_com " << robot.link_com;
        EXPECT_LT(mujoco_error, kForceOfPeak) << "random robot " << compared << ", link_com " << robot.link_com;
        // Inertia at a few postures of the trajectory.
        for (std::size_t k = 0; k < times.size(); k += 25) {
            ASSERT_TRUE(prr3::inverseDynamics(model, data, ours.p[k], Twist::Zero(), Twist::Zero()).ok());
            const Matrix3 reference = simbody.jointSpaceInertia(ours.p[k]);
            EXPECT_LT((data.I - reference).norm(), kInertiaRelative * reference.norm()) << describePose(ours.p[k]);
        }
    }
    EXPECT_EQ(compared, 12) << "only " << compared << " of " << tried << " random cases stayed inside the workspace";
}

TEST(Validation, InertiaAgreesWithSimbodyAcrossTheWorkspace) {
    const prr3::Model model;
    prr3::SimbodyRobot simbody(model.parameters);
    BaselineSampler sampler(model, 99);
    prr3::Data data;
    for (int k = 0; k < 100; ++k) {
        const Pose p = sampler.next();
        ASSERT_TRUE(prr3::inverseDynamics(model, data, p, Twist::Zero(), Twist::Zero()).ok());
        const Matrix3 reference = simbody.jointSpaceInertia(p);
        EXPECT_LT((data.I - reference).norm(), kInertiaRelative * reference.norm()) << describePose(p);
    }
}

}  // namespace
}  // namespace nocdyn::test
