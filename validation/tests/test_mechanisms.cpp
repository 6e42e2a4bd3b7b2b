// Tests of the general Simbody and MuJoCo models (ctest label: validation): the paper's 3-PRR
// against the golden values, and random robots of every limb type
// and actuation choice (redundant ones too, with gravity and friction) where the two engines
// must agree with each other and satisfy the power balance.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "nocdyn/description.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/short_form.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/validation/mujoco_mechanism.hpp"
#include "nocdyn/validation/simbody_mechanism.hpp"

using nocdyn::JointType;
using nocdyn::PoseTrajectory;
using nocdyn::RobotDescription;
using nocdyn::io::RobotParameters;
using nocdyn::validation::MechanismSample;
using nocdyn::validation::MujocoMechanism;
using nocdyn::validation::SimbodyMechanism;

namespace {

// Agreement required of forces (and joint motions), relative to the peak over the samples.
constexpr double kRelativeTolerance = 1e-9;
// Power balance residual relative to the peak actuator power (5-point derivative, h = 1e-4 s).
constexpr double kPowerTolerance = 1e-6;
// Condition number above which a random robot counts as singular (skipped).
constexpr double kMaxCondition = 1e3;

struct Table {
    std::vector<std::string> header;
    std::vector<std::vector<double>> rows;
    [[nodiscard]] std::size_t col(const std::string& name) const {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it == header.end()) throw std::runtime_error("golden column missing: " + name);
        return static_cast<std::size_t>(it - header.begin());
    }
};

Table readTable(const std::string& path) {
    Table g;
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::string line;
    std::getline(in, line);
    std::stringstream hs(line);
    for (std::string f; std::getline(hs, f, ',');) g.header.push_back(f);
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        std::vector<double> row;
        std::stringstream ss(line);
        for (std::string f; std::getline(ss, f, ',');) row.push_back(std::stod(f));
        g.rows.push_back(row);
    }
    return g;
}

double peakAbs(const std::vector<MechanismSample>& s, Eigen::VectorXd MechanismSample::*field) {
    double peak = 0.0;
    for (const auto& x : s) peak = std::max(peak, (x.*field).cwiseAbs().maxCoeff());
    return peak;
}

double maxDiff(const std::vector<MechanismSample>& a, const std::vector<MechanismSample>& b,
               Eigen::VectorXd MechanismSample::*field) {
    double err = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k)
        err = std::max(err, ((a[k].*field) - (b[k].*field)).cwiseAbs().maxCoeff());
    return err;
}

template <class Engine>
void checkGolden(const char* engine, const std::string& file, const PoseTrajectory& trajectory) {
    const Table g = readTable(std::string(NOCDYN_GOLDEN_DIR) + "/" + file);
    std::vector<double> times;
    for (const auto& r : g.rows) times.push_back(r[g.col("t")]);
    Engine model(nocdyn::io::expand(RobotParameters{}));
    const std::vector<MechanismSample> s = model.inverseDynamics(trajectory, times);
    ASSERT_EQ(s.size(), times.size());
    const std::array<std::pair<const char*, Eigen::VectorXd MechanismSample::*>, 4> fields = {
        {{"u", &MechanismSample::u},
         {"du", &MechanismSample::du},
         {"ddu", &MechanismSample::ddu},
         {"tau", &MechanismSample::tau}}};
    for (const auto& [name, field] : fields) {
        for (int j = 0; j < 3; ++j) {
            const std::size_t c = g.col(name + std::to_string(j + 1));
            double peak = 0.0, err = 0.0;
            for (std::size_t k = 0; k < s.size(); ++k) {
                peak = std::max(peak, std::abs(g.rows[k][c]));
                err = std::max(err, std::abs((s[k].*field)[j] - g.rows[k][c]));
            }
            std::printf("[%s %s] %s%d max |err| = %.3e (peak %.6g, rel %.3e)\n", engine, file.c_str(), name, j + 1, err,
                        peak, err / peak);
            EXPECT_LE(err, kRelativeTolerance * peak) << engine << " " << file << " " << name << j + 1;
        }
    }
    double peak = 0.0, err = 0.0;
    for (std::size_t k = 0; k < s.size(); ++k) {
        const double ref = g.rows[k][g.col("kinetic")];
        peak = std::max(peak, ref);
        err = std::max(err, std::abs(s[k].kinetic - ref));
        EXPECT_NEAR(s[k].pose[0], g.rows[k][g.col("theta")], 1e-12);
        EXPECT_NEAR(s[k].pose[1], g.rows[k][g.col("x")], 1e-12);
        EXPECT_NEAR(s[k].pose[2], g.rows[k][g.col("y")], 1e-12);
    }
    EXPECT_LE(err, kRelativeTolerance * peak) << engine << " " << file << " kinetic";
}

std::vector<double> linspace(double t0, double t1, int n) {
    std::vector<double> t(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) t[static_cast<std::size_t>(i)] = t0 + (t1 - t0) * i / (n - 1);
    return t;
}

// ---------------------------------------------------------------------------------------
// Random robots
// ---------------------------------------------------------------------------------------
const std::array<const char*, 7> kLimbTypes = {"RRR", "RPR", "PRR", "RRP", "PRP", "RPP", "PPR"};

class RandomRobots {
public:
    explicit RandomRobots(unsigned seed) : rng_(seed) {}

    double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
    Eigen::Vector2d direction() {
        const double a = uniform(-std::numbers::pi, std::numbers::pi);
        return {std::cos(a), std::sin(a)};
    }

    /// `limbs` limbs of `type`, nothing actuated yet; home pose near the origin.
    RobotDescription geometry(const std::string& type, int limbs) {
        RobotDescription r;
        r.name = "random-" + std::to_string(limbs) + "-" + type;
        r.home = {uniform(-0.3, 0.3), uniform(-0.02, 0.02), uniform(-0.02, 0.02)};
        r.max_condition = kMaxCondition;
        r.platform.mass = uniform(0.1, 2.0);
        r.platform.inertia = uniform(1e-4, 1e-2);
        r.platform.com = {uniform(-0.02, 0.02), uniform(-0.02, 0.02)};
        const Eigen::Vector2d C(r.home[1], r.home[2]);
        const Eigen::Rotation2Dd Rh(r.home[0]);
        for (int j = 0; j < limbs; ++j) {
            const double phi = 2.0 * std::numbers::pi * j / limbs + uniform(-0.3, 0.3);
            const Eigen::Vector2d base = uniform(0.15, 0.3) * Eigen::Vector2d(std::cos(phi), std::sin(phi));
            const double psi = phi + uniform(-0.6, 0.6);
            const Eigen::Vector2d tip = C + Rh * (uniform(0.03, 0.08) * Eigen::Vector2d(std::cos(psi), std::sin(psi)));
            const Eigen::Vector2d along = tip - base;
            const Eigen::Vector2d normal(-along.y(), along.x());
            // The middle joint off the base-platform line, so that the limb is far from its
            // straight (singular) posture.
            const double offset = (uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0) * uniform(0.2, 0.5);
            const Eigen::Vector2d middle = base + uniform(0.35, 0.65) * along + offset * normal;
            const std::array<Eigen::Vector2d, 3> points = {base, middle, tip};
            nocdyn::LimbDescription limb;
            limb.name = "limb" + std::to_string(j + 1);
            for (std::size_t k = 0; k < 3; ++k) {
                auto& joint = limb.joints[k];
                joint.type = type[k] == 'R' ? JointType::revolute : JointType::prismatic;
                joint.point = points[k];
                joint.direction = direction();
            }
            for (std::size_t b = 0; b < 2; ++b) {
                auto& body = limb.bodies[b];
                body.mass = uniform(0.1, 2.0);
                body.inertia = uniform(1e-4, 1e-2);
                body.com =
                    0.5 * (points[b] + points[b + 1]) + Eigen::Vector2d(uniform(-0.02, 0.02), uniform(-0.02, 0.02));
            }
            r.limbs.push_back(limb);
        }
        return r;
    }

    void physics(RobotDescription& r, bool gravity, bool friction) {
        if (gravity) r.gravity = 9.81 * direction();
        if (friction) {
            for (auto& limb : r.limbs) {
                for (auto& joint : limb.joints) {
                    joint.damping = uniform(0.0, joint.type == JointType::revolute ? 0.05 : 5.0);
                    joint.friction = uniform(0.0, joint.type == JointType::revolute ? 0.1 : 2.0);
                }
            }
        }
    }

    /// Small smooth motion around home: two harmonics per axis, 2-20 Hz, a few mm / degrees.
    PoseTrajectory trajectory(const RobotDescription& r) {
        PoseTrajectory t;
        t.name = "random";
        const auto axis = [&](nocdyn::AxisMotion& a, double offset, double amplitude) {
            a.offset = offset;
            for (int h = 0; h < 2; ++h)
                a.harmonics.push_back(
                    {uniform(0.3, 1.0) * amplitude, uniform(2.0, 20.0), uniform(0.0, 2.0 * std::numbers::pi)});
        };
        axis(t.theta, r.home[0], 0.03);
        axis(t.x, r.home[1], 0.003);
        axis(t.y, r.home[2], 0.003);
        return t;
    }

private:
    std::mt19937 rng_;
};

/// Actuator power residual tau . du - dE/dt - dissipation at the centre of five samples
/// h apart (E = kinetic + potential, 4th-order central difference), relative to |tau| |du|.
double powerResidual(const std::vector<MechanismSample>& s, double h, double& scale) {
    const auto E = [&](std::size_t k) { return s[k].kinetic + s[k].potential; };
    const double dEdt = (E(0) - 8.0 * E(1) + 8.0 * E(3) - E(4)) / (12.0 * h);
    const MechanismSample& c = s[2];
    scale = c.tau.cwiseAbs().dot(c.du.cwiseAbs()) + std::abs(dEdt) + c.dissipation;
    return c.tau.dot(c.du) - dEdt - c.dissipation;
}

struct TypeReport {
    int robots = 0, kept = 0, redundant = 0, geometries_rejected = 0;
    double max_abs = 0.0, max_rel = 0.0, max_power = 0.0;
};

std::string describe(const RobotDescription& r) {
    std::ostringstream o;
    o << r.name << " actuated:";
    for (std::size_t j = 0; j < r.limbs.size(); ++j)
        for (std::size_t k = 0; k < 3; ++k)
            if (r.limbs[j].joints[k].actuated) o << " " << j + 1 << "." << k + 1;
    o << " gravity [" << r.gravity.transpose() << "]";
    return o.str();
}

/// A geometry whose limbs all reach along the trajectory, regular: MuJoCo with every joint
/// actuated (the actuation map then has full rank whenever the limbs are regular).
RobotDescription reachableGeometry(RandomRobots& random, const std::string& type, int limbs, PoseTrajectory& trajectory,
                                   int& rejected) {
    for (;;) {
        RobotDescription r = random.geometry(type, limbs);
        trajectory = random.trajectory(r);
        for (auto& limb : r.limbs)
            for (auto& joint : limb.joints) joint.actuated = true;
        try {
            (void)MujocoMechanism(r).inverseDynamics(trajectory, linspace(0.0, 0.1, 11));
            for (auto& limb : r.limbs)
                for (auto& joint : limb.joints) joint.actuated = false;
            return r;
        } catch (const nocdyn::Error& e) {
            if (std::getenv("NOCDYN_VERBOSE") != nullptr) std::printf("geometry rejected: %s\n", e.what());
            ++rejected;
        }
    }
}

/// Runs both engines on one robot; false when either finds it singular or out of reach.
bool compareEngines(const RobotDescription& r, const PoseTrajectory& trajectory, bool power, TypeReport& report) {
    const std::vector<double> times = linspace(0.0, 0.05, 11);
    std::vector<MechanismSample> a, b;
    try {
        SimbodyMechanism simbody(r);
        MujocoMechanism mujoco(r);
        b = mujoco.inverseDynamics(trajectory, times);
        a = simbody.inverseDynamics(trajectory, times);
        if (power) {
            const double h = 1e-4;
            for (const double t : {0.023, 0.071}) {
                const std::vector<double> around = {t - 2 * h, t - h, t, t + h, t + 2 * h};
                for (const auto& s :
                     {simbody.inverseDynamics(trajectory, around), mujoco.inverseDynamics(trajectory, around)}) {
                    double scale = 0.0;
                    const double res = powerResidual(s, h, scale);
                    report.max_power = std::max(report.max_power, std::abs(res) / scale);
                    EXPECT_LE(std::abs(res), kPowerTolerance * scale) << describe(r) << " t=" << t;
                }
            }
        }
    } catch (const nocdyn::Error& e) {
        if (std::getenv("NOCDYN_VERBOSE") != nullptr) std::printf("skipped %s: %s\n", describe(r).c_str(), e.what());
        return false;
    }
    const double peak = std::max(peakAbs(a, &MechanismSample::tau), peakAbs(b, &MechanismSample::tau));
    const double err = maxDiff(a, b, &MechanismSample::tau);
    report.max_abs = std::max(report.max_abs, err);
    report.max_rel = std::max(report.max_rel, err / peak);
    EXPECT_LE(err, kRelativeTolerance * peak)
        << describe(r) << ": |tau_simbody - tau_mujoco| = " << err << " N, peak " << peak;
    for (auto field : {&MechanismSample::u, &MechanismSample::du, &MechanismSample::ddu}) {
        const double p = std::max(peakAbs(a, field), 1e-12);
        EXPECT_LE(maxDiff(a, b, field), kRelativeTolerance * p) << describe(r);
    }
    for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_NEAR(a[k].kinetic, b[k].kinetic, 1e-10 * std::max(1e-9, a[k].kinetic)) << describe(r);
    }
    return true;
}

}  // namespace

TEST(GeneralMechanism, SimbodyMatchesGoldenPaperTrajectories) {
    checkGolden<SimbodyMechanism>("simbody", "paper_trajectory1.csv", nocdyn::paperTrajectory1());
    checkGolden<SimbodyMechanism>("simbody", "paper_trajectory2.csv", nocdyn::paperTrajectory2());
}

TEST(GeneralMechanism, MujocoMatchesGoldenPaperTrajectories) {
    checkGolden<MujocoMechanism>("mujoco", "paper_trajectory1.csv", nocdyn::paperTrajectory1());
    checkGolden<MujocoMechanism>("mujoco", "paper_trajectory2.csv", nocdyn::paperTrajectory2());
}

/// Both engines' inverse dynamics of the paper's prototype, one call per engine.
template <class F>
void forEachEngine(F&& f) {
    SimbodyMechanism simbody(nocdyn::io::expand(RobotParameters{}));
    MujocoMechanism mujoco(nocdyn::io::expand(RobotParameters{}));
    f("simbody",
      [&](const PoseTrajectory& t, const std::vector<double>& times) { return simbody.inverseDynamics(t, times); });
    f("mujoco",
      [&](const PoseTrajectory& t, const std::vector<double>& times) { return mujoco.inverseDynamics(t, times); });
}

TEST(GeneralMechanism, PaperRobotAtHomeHasZeroActuatorsAndNoForce) {
    forEachEngine([](const char* engine, auto inverseDynamics) {
        const PoseTrajectory still;  // every axis zero: held at home
        for (const MechanismSample& s : inverseDynamics(still, {0.0, 0.5})) {
            EXPECT_LT(s.u.cwiseAbs().maxCoeff(), 1e-14) << engine;
            EXPECT_LT(s.tau.cwiseAbs().maxCoeff(), 1e-12) << engine;
        }
    });
    SimbodyMechanism plant(nocdyn::io::expand(RobotParameters{}));
    plant.resetPlant(Eigen::Vector3d::Zero());
    EXPECT_LT(plant.u().cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT(plant.pose().cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_EQ(plant.kineticEnergy(), 0.0);
}

TEST(GeneralMechanism, PaperRobotAssemblesAtTheRequestedPose) {
    const PoseTrajectory trajectory = nocdyn::paperTrajectory1();
    const std::vector<double> times = linspace(0.0, 0.1, 41);
    forEachEngine([&](const char* engine, auto inverseDynamics) {
        const auto s = inverseDynamics(trajectory, times);
        for (std::size_t k = 0; k < s.size(); ++k) {
            nocdyn::Pose p, dp, ddp;
            trajectory.evaluate(times[k], p, dp, ddp);
            EXPECT_LT((s[k].pose - p).cwiseAbs().maxCoeff(), 1e-13) << engine << " t = " << times[k];
        }
    });
    SimbodyMechanism plant(nocdyn::io::expand(RobotParameters{}));
    const Eigen::Vector3d pose(0.05, 0.004, -0.003), rate(0.7, -0.02, 0.03);
    plant.resetPlant(pose, rate);
    EXPECT_LT((plant.pose() - pose).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT((plant.poseRate() - rate).cwiseAbs().maxCoeff(), 1e-13);
    EXPECT_GT(plant.u().cwiseAbs().maxCoeff(), 1e-3);  // the sliders moved
}

TEST(GeneralMechanism, PaperRobotLargeStepsBetweenSamplesStayOnTheHomeBranch) {
    // Large rotations sampled coarsely: the continuation from the previous sample is far off,
    // yet every sample equals the end of a fine, continuous sampling up to it.
    PoseTrajectory trajectory;
    trajectory.theta.harmonics = {{0.8, 3.0, std::numbers::pi / 2}};  // first sample at 0.8 rad
    trajectory.x.harmonics = {{0.01, 2.0, 0.0}};
    trajectory.y.harmonics = {{-0.008, 4.0, 1.0}};
    const std::vector<double> coarse = {0.0, 0.16, 0.02, 0.17, 0.31};
    forEachEngine([&](const char* engine, auto inverseDynamics) {
        const auto a = inverseDynamics(trajectory, coarse);
        for (std::size_t k = 0; k < coarse.size(); ++k) {
            const MechanismSample fine = inverseDynamics(trajectory, linspace(0.0, coarse[k], 400)).back();
            EXPECT_LT((a[k].u - fine.u).cwiseAbs().maxCoeff(), 1e-12) << engine << " t = " << coarse[k];
            EXPECT_LT((a[k].tau - fine.tau).cwiseAbs().maxCoeff(), 1e-10 * (1.0 + fine.tau.cwiseAbs().maxCoeff()))
                << engine << " t = " << coarse[k];
        }
    });
}

TEST(GeneralMechanism, SimbodyPlantConservesKineticEnergyWithoutForces) {
    SimbodyMechanism plant(nocdyn::io::expand(RobotParameters{}));
    plant.resetPlant(Eigen::Vector3d(0.01, 0.001, -0.002), Eigen::Vector3d(0.8, 0.03, -0.02));
    const double T0 = plant.kineticEnergy();
    ASSERT_GT(T0, 1e-4);
    double worst = 0.0;
    for (int k = 0; k < 10; ++k) {
        plant.advance(0.01);
        worst = std::max(worst, std::abs(plant.kineticEnergy() - T0) / T0);
    }
    std::printf("[plant] kinetic energy drift over 0.1 s: %.3e (relative)\n", worst);
    EXPECT_NEAR(plant.time(), 0.1, 1e-14);
    EXPECT_LT(worst, 1e-8);
    EXPECT_GT(std::abs(plant.pose()[0] - 0.01), 0.01);  // it really moved
}

TEST(GeneralMechanism, SimbodyPlantAcceleratesAsInverseDynamicsPredicts) {
    // Forward dynamics with the inverse-dynamics forces gives back the actuator accelerations:
    // an independent check of the sign and size of tau.
    SimbodyMechanism engine(nocdyn::io::expand(RobotParameters{}));
    SimbodyMechanism plant(nocdyn::io::expand(RobotParameters{}));
    const PoseTrajectory trajectory = nocdyn::paperTrajectory1();
    for (double t0 : {0.0, 0.013, 0.042}) {
        const MechanismSample s = engine.inverseDynamics(trajectory, linspace(0.0, t0, 20)).back();
        nocdyn::Pose p, dp, ddp;
        trajectory.evaluate(t0, p, dp, ddp);
        plant.resetPlant(p, dp);
        EXPECT_LT((plant.du() - s.du).cwiseAbs().maxCoeff(), 1e-12);
        plant.setActuatorForces(s.tau);
        const double h = 1e-6;
        plant.advance(h);
        const Eigen::VectorXd ddu = (plant.du() - s.du) / h;
        EXPECT_LT((ddu - s.ddu).cwiseAbs().maxCoeff(), 1e-3 * s.ddu.cwiseAbs().maxCoeff())
            << "t0 = " << t0 << " plant " << ddu.transpose() << " vs " << s.ddu.transpose();
    }
}

/// Random robots whose limbs are all of one type (the parameter): one geometry with every
/// choice of three actuated joints among the nine, and four redundant robots (four limbs with
/// four actuators, three limbs with five); gravity and friction alternately on and off.
class RandomRobotsOfLimbType : public ::testing::TestWithParam<int> {};

TEST_P(RandomRobotsOfLimbType, EnginesAgreeAndPowerBalanceHolds) {
    const std::string type = kLimbTypes[static_cast<std::size_t>(GetParam())];
    RandomRobots random(20261122u + static_cast<unsigned>(GetParam()));
    TypeReport report;
    int case_index = 0;
    PoseTrajectory trajectory;
    const RobotDescription base = reachableGeometry(random, type, 3, trajectory, report.geometries_rejected);
    for (int a = 0; a < 9; ++a) {
        for (int b = a + 1; b < 9; ++b) {
            for (int c = b + 1; c < 9; ++c) {
                RobotDescription r = base;
                for (int k : {a, b, c})
                    r.limbs[static_cast<std::size_t>(k / 3)].joints[static_cast<std::size_t>(k % 3)].actuated = true;
                random.physics(r, case_index % 2 == 0, case_index % 3 != 2);
                ++report.robots;
                if (compareEngines(r, trajectory, case_index % 6 == 0, report)) ++report.kept;
                ++case_index;
            }
        }
    }
    for (int i = 0; i < 4; ++i) {
        const bool four = i % 2 == 0;
        PoseTrajectory redundant_trajectory;
        RobotDescription r =
            reachableGeometry(random, type, four ? 4 : 3, redundant_trajectory, report.geometries_rejected);
        const int joints = 3 * static_cast<int>(r.limbs.size());
        std::vector<int> order(static_cast<std::size_t>(joints));
        for (int k = 0; k < joints; ++k) order[static_cast<std::size_t>(k)] = k;
        std::shuffle(order.begin(), order.end(), std::mt19937(static_cast<unsigned>(case_index)));
        for (int k = 0; k < (four ? 4 : 5); ++k) {
            const int q = order[static_cast<std::size_t>(k)];
            r.limbs[static_cast<std::size_t>(q / 3)].joints[static_cast<std::size_t>(q % 3)].actuated = true;
        }
        random.physics(r, i < 2, i % 2 == 1 || i == 2);
        ++report.robots;
        ++report.redundant;
        if (compareEngines(r, redundant_trajectory, true, report)) ++report.kept;
        ++case_index;
    }
    std::printf(
        "[random %s] %d robots (%d redundant), %d kept, %d skipped as singular; %d geometries out of "
        "reach rejected; max |tau_simbody - tau_mujoco| = %.3e N, rel. to peak %.3e; max power residual %.3e\n",
        type.c_str(), report.robots, report.redundant, report.kept, report.robots - report.kept,
        report.geometries_rejected, report.max_abs, report.max_rel, report.max_power);
    EXPECT_GE(report.kept, report.robots / 2) << type << ": too many random robots skipped";
}

INSTANTIATE_TEST_SUITE_P(EveryLimbType, RandomRobotsOfLimbType,
                         ::testing::Range(0, static_cast<int>(kLimbTypes.size())),
                         [](const ::testing::TestParamInfo<int>& info) {
                             return std::string(kLimbTypes[static_cast<std::size_t>(info.param)]);
                         });

TEST(GeneralMechanism, RedundantForcesAreMinimumNorm) {
    // A 4-RRR with every base joint actuated: tau must be orthogonal to the null space of the
    // actuation map, so adding any null-space force changes the platform balance or grows |tau|.
    // Checked through the engines alone: both give the same tau, and the 3-actuator subset
    // solutions are never smaller in norm.
    RandomRobots random(7u);
    PoseTrajectory trajectory;
    int rejected = 0;
    RobotDescription r = reachableGeometry(random, "RRR", 4, trajectory, rejected);
    for (auto& limb : r.limbs) limb.joints[0].actuated = true;
    const std::vector<double> times = {0.01, 0.03};
    const auto redundant = SimbodyMechanism(r).inverseDynamics(trajectory, times);
    for (int drop = 0; drop < 4; ++drop) {
        RobotDescription sub = r;
        sub.limbs[static_cast<std::size_t>(drop)].joints[0].actuated = false;
        std::vector<MechanismSample> s;
        try {
            s = MujocoMechanism(sub).inverseDynamics(trajectory, times);
        } catch (const nocdyn::Error&) {
            continue;
        }
        for (std::size_t k = 0; k < times.size(); ++k) {
            EXPECT_LE(redundant[k].tau.norm(), s[k].tau.norm() * (1.0 + 1e-12));
        }
    }
}

TEST(GeneralMechanism, ReportsTheTimeOfAnUnreachablePose) {
    RobotDescription r = nocdyn::io::expand(RobotParameters{});
    PoseTrajectory far;
    far.x.harmonics = {{0.2, 1.0, 0.0}};  // 20 cm: far beyond the 3-PRR's workspace
    const std::vector<double> times = linspace(0.0, 0.25, 6);
    for (int engine = 0; engine < 2; ++engine) {
        try {
            if (engine == 0)
                SimbodyMechanism(r).inverseDynamics(far, times);
            else
                MujocoMechanism(r).inverseDynamics(far, times);
            ADD_FAILURE() << "no error";
        } catch (const nocdyn::Error& e) {
            EXPECT_NE(std::string(e.what()).find("t="), std::string::npos) << e.what();
        }
    }
}

// Per-sample cost of each engine on the paper robot (reported, never asserted).
TEST(GeneralMechanism, PerSampleTiming) {
    const std::vector<double> times = linspace(0.0, 0.2, 2001);
    const auto run = [&](auto& engine, const char* name, const PoseTrajectory& trajectory) {
        (void)engine.inverseDynamics(trajectory, {0.0});
        const auto t0 = std::chrono::steady_clock::now();
        const auto s = engine.inverseDynamics(trajectory, times);
        const auto t1 = std::chrono::steady_clock::now();
        std::printf("[timing] %s: %.1f us per sample (%zu samples)\n", name,
                    std::chrono::duration<double, std::micro>(t1 - t0).count() / static_cast<double>(s.size()),
                    s.size());
    };
    SimbodyMechanism simbody(nocdyn::io::expand(RobotParameters{}));
    MujocoMechanism mujoco(nocdyn::io::expand(RobotParameters{}));
    run(simbody, "SimbodyMechanism paper 3-PRR", nocdyn::paperTrajectory1());
    run(mujoco, "MujocoMechanism paper 3-PRR", nocdyn::paperTrajectory1());
    // A random 4-RRR with its four base joints actuated (redundant), gravity and friction.
    RandomRobots random(11u);
    PoseTrajectory trajectory;
    int rejected = 0;
    RobotDescription r = reachableGeometry(random, "RRR", 4, trajectory, rejected);
    for (auto& limb : r.limbs) limb.joints[0].actuated = true;
    random.physics(r, true, true);
    SimbodyMechanism simbody4(r);
    MujocoMechanism mujoco4(r);
    run(simbody4, "SimbodyMechanism random 4-RRR", trajectory);
    run(mujoco4, "MujocoMechanism random 4-RRR", trajectory);
    SUCCEED();
}
