// The spatial NOC (nocdyn/spatial.hpp) against identities that need no engine: every limb closes
// on the platform's displacement; Lagrange's equations by finite differences of the kinetic and
// potential energies (the generalised forces (du/dp)^T tau, friction off); the power balance with
// friction; on the shipped Delta, 6-UPS and 6-RUS and on random 6-UPS and 6-RUS hexapods.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "cli_support.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/sim/spatial_control.hpp"
#include "nocdyn/sim/spatial_simulator.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_limits.hpp"
#include "nocdyn/spatial_reactions.hpp"

namespace nocdyn::spatial {
namespace {

SpatialRobotDescription shipped(const std::string& name) {
    return io::loadSpatialRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml");
}

SpatialRobotDescription frictionless(SpatialRobotDescription d) {
    for (SpatialLimbDescription& limb : d.limbs) {
        for (SpatialJointDescription& joint : limb.joints) joint.damping = joint.friction = 0.0;
    }
    return d;
}

/// A random physically possible inertia tensor: principal moments obeying the triangle
/// inequalities, turned by a random rotation.
Eigen::Matrix3d randomInertia(std::mt19937& rng, double scale) {
    std::uniform_real_distribution<double> u(0.2, 1.0);
    std::normal_distribution<double> n(0.0, 1.0);
    const double a = u(rng), b = u(rng);
    const Eigen::Vector3d moments = scale * Eigen::Vector3d(a, b, 0.5 * (a + b) + 0.4 * std::abs(a - b));
    const Eigen::Matrix3d R = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
    return R * moments.asDiagonal() * R.transpose();
}

/// A random hexapod of six legs: base points on a circle of radius ~1 at z = 0, platform points
/// on a circle of ~0.6 at z = h, each leg a UPS (the actuated P along the leg) or an RUS (a crank
/// about a horizontal axis, actuated), bodies of random mass, c.o.m. and inertia.
SpatialRobotDescription randomHexapod(std::mt19937& rng, bool rus) {
    std::uniform_real_distribution<double> jitter(-0.08, 0.08);
    std::uniform_real_distribution<double> mass(0.5, 5.0);
    SpatialRobotDescription d;
    d.name = rus ? "random-6rus" : "random-6ups";
    d.motion = PlatformMotion::full;
    d.gravity = {0.3, -0.2, -9.81};
    const double h = 1.0 + jitter(rng);
    d.home << jitter(rng), jitter(rng), h, jitter(rng), jitter(rng), jitter(rng);
    d.platform.mass = 20.0 + 10.0 * mass(rng);
    d.platform.com = {jitter(rng), jitter(rng), 0.05 + jitter(rng)};
    d.platform.inertia = randomInertia(rng, 5.0);
    const Eigen::Matrix3d R_home = rotation(d.home(3), d.home(4), d.home(5));
    for (int i = 0; i < 6; ++i) {
        const double base_angle = (120.0 * (i / 2) + (i % 2 == 0 ? -15.0 : 15.0)) * M_PI / 180.0 + jitter(rng);
        const double top_angle =
            (60.0 + 120.0 * ((i + 1) / 2 % 3) + (i % 2 == 0 ? 15.0 : -15.0)) * M_PI / 180.0 + jitter(rng);
        const Eigen::Vector3d b(std::cos(base_angle) * (1.0 + jitter(rng)), std::sin(base_angle) * (1.0 + jitter(rng)),
                                jitter(rng));
        const Eigen::Vector3d top_local(0.6 * std::cos(top_angle), 0.6 * std::sin(top_angle), 0.0);
        const Eigen::Vector3d top = d.home.head<3>() + R_home * top_local;
        SpatialLimbDescription limb;
        limb.name = "leg" + std::to_string(i + 1);
        SpatialJointDescription s;
        s.type = SpatialJointType::spherical;
        s.point = top;
        SpatialBodyDescription body1, body2;
        body1.mass = mass(rng);
        body2.mass = mass(rng);
        body1.inertia = randomInertia(rng, 0.05);
        body2.inertia = randomInertia(rng, 0.05);
        if (!rus) {
            const Eigen::Vector3d e = (top - b).normalized();
            SpatialJointDescription u;
            u.type = SpatialJointType::universal;
            u.point = b;
            u.axis1 = e.cross(Eigen::Vector3d::UnitZ()).normalized();
            u.axis2 = e.cross(u.axis1).normalized();
            SpatialJointDescription p;
            p.type = SpatialJointType::prismatic;
            p.direction = e;
            p.actuated = true;
            limb.joints = {u, p, s};
            body1.com = b + 0.3 * (top - b) + 0.02 * Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
            body2.com = b + 0.7 * (top - b) + 0.02 * Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
        } else {
            // a crank of 0.3 m about a horizontal axis across the radius, then a rod to the top
            const Eigen::Vector3d radial(std::cos(base_angle), std::sin(base_angle), 0.0);
            const Eigen::Vector3d axis = Eigen::Vector3d::UnitZ().cross(radial).normalized();
            const Eigen::Vector3d elbow = b + 0.3 * (0.6 * radial + 0.8 * Eigen::Vector3d::UnitZ()).normalized();
            SpatialJointDescription r;
            r.type = SpatialJointType::revolute;
            r.point = b;
            r.axis = axis;
            r.actuated = true;
            SpatialJointDescription u;
            u.type = SpatialJointType::universal;
            u.point = elbow;
            u.axis1 = axis;
            u.axis2 = (top - elbow).normalized().cross(axis).normalized();
            limb.joints = {r, u, s};
            body1.com = 0.5 * (b + elbow);
            body2.com = 0.5 * (elbow + top) + 0.01 * Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
        }
        limb.bodies = {body1, body2};
        d.limbs.push_back(limb);
    }
    return d;
}

/// The energies and actuator values as functions of the pose and its rate.
struct Probe {
    const Model& model;
    Data data;
    explicit Probe(const Model& m) : model(m), data(m) {}
    double T(const TaskVector& p, const TaskVector& v) {
        const TaskVector zero = TaskVector::Zero(model.task_dimension);
        EXPECT_TRUE(inverseDynamics(model, data, p, v, zero).ok());
        return kineticEnergy(model, data);
    }
    double V(const TaskVector& p) {
        EXPECT_TRUE(inverseKinematics(model, data, p).ok());
        return potentialEnergy(model, data);
    }
    ActuatorVector u(const TaskVector& p) {
        EXPECT_TRUE(inverseKinematics(model, data, p).ok());
        return data.u;
    }
};

/// f'(0) by the fourth-order central difference.
template <class F>
auto derivative(F f, double h) {
    // evaluated within the full expression (Eigen's expressions hold the temporaries)
    const decltype(f(h)) value = (-f(2.0 * h) + 8.0 * f(h) - 8.0 * f(-h) + f(-2.0 * h)) / (12.0 * h);
    return value;
}

/// Lagrange's equations at (p, v, a): Q_i = d/dt dT/dv_i - dT/dp_i + dV/dp_i, with Q the
/// generalised forces (du/dp)^T tau of the inverse dynamics; the largest difference over max |Q|.
double lagrangeError(const Model& model, const TaskVector& p, const TaskVector& v, const TaskVector& a) {
    const int d = model.task_dimension;
    Data data(model);
    EXPECT_TRUE(inverseDynamics(model, data, p, v, a).ok()) << describe(inverseDynamics(model, data, p, v, a), model);
    const ActuatorVector tau = data.tau;
    Probe probe(model);
    Eigen::MatrixXd J_u(model.actuators, d);
    for (int i = 0; i < d; ++i) {
        const TaskVector e = TaskVector::Unit(d, i);
        J_u.col(i) = derivative([&](double h) -> Eigen::VectorXd { return probe.u(p + h * e); }, 1e-4);
    }
    const Eigen::VectorXd Q = J_u.transpose() * tau;
    Eigen::VectorXd lagrange(d);
    for (int i = 0; i < d; ++i) {
        const TaskVector e = TaskVector::Unit(d, i);
        // T is quadratic in v: its central difference in v is exact for any step
        const auto dT_dv = [&](double t) {
            const TaskVector pt = p + t * v + 0.5 * t * t * a, vt = v + t * a;
            return 0.5 * (probe.T(pt, vt + e) - probe.T(pt, vt - e));
        };
        const double ddt = derivative(dT_dv, 1e-3);
        const double dT_dp = derivative([&](double h) { return probe.T(p + h * e, v); }, 1e-4);
        const double dV_dp = derivative([&](double h) { return probe.V(p + h * e); }, 1e-4);
        lagrange(i) = ddt - dT_dp + dV_dp;
    }
    return (lagrange - Q).cwiseAbs().maxCoeff() / Q.cwiseAbs().maxCoeff();
}

TaskVector randomTask(std::mt19937& rng, int d, double linear, double angular) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    TaskVector x(d);
    for (int i = 0; i < d; ++i) x(i) = (i < 3 ? linear : angular) * u(rng);
    return x;
}

TEST(SpatialKinematics, EveryShippedRobotClosesAtHomeWithItsJointsAtZero) {
    for (const std::string name : {"delta", "stewart", "hexa-6rus"}) {
        const Model model(shipped(name));
        Data data(model);
        ASSERT_TRUE(inverseKinematics(model, data, model.home).ok()) << name;
        for (const LimbData& ld : data.limb) EXPECT_LT(ld.q.cwiseAbs().maxCoeff(), 1e-12) << name;
        EXPECT_EQ(model.actuators, model.task_dimension) << name;
    }
}

TEST(SpatialKinematics, EachLimbsChainReachesThePlatformPointsItJoins) {
    // the last joint's point, carried by the chain, is where the platform carries it
    std::mt19937 rng(7);
    for (const std::string name : {"delta", "stewart", "hexa-6rus"}) {
        const SpatialRobotDescription d = shipped(name);
        const Model model(d);
        Data data(model);
        for (int trial = 0; trial < 20; ++trial) {
            const TaskVector p = model.home + randomTask(rng, model.task_dimension, 0.05, 0.08);
            ASSERT_TRUE(inverseKinematics(model, data, p).ok()) << name;
            const Eigen::Matrix3d R_D = data.R * model.home_rotation.transpose();
            for (int j = 0; j < model.limbs(); ++j) {
                const Limb& limb = model.limb[static_cast<std::size_t>(j)];
                Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
                Eigen::Vector3d t = Eigen::Vector3d::Zero();
                for (int k = 0; k < limb.size(); ++k) {
                    const Freedom& f = limb.freedoms[static_cast<std::size_t>(k)];
                    const double q = data.limb[static_cast<std::size_t>(j)].q(k);
                    Eigen::Matrix3d Rk = Eigen::Matrix3d::Identity();
                    Eigen::Vector3d tk = q * f.axis;
                    if (f.revolute) {
                        Rk = Eigen::AngleAxisd(q, f.axis).toRotationMatrix();
                        tk = f.point - Rk * f.point;
                    }
                    t = R * tk + t;
                    R = R * Rk;
                }
                const Eigen::Vector3d x = d.limbs[static_cast<std::size_t>(j)].joints.back().point;
                const Eigen::Vector3d expected = R_D * (x - model.home.head<3>()) + p.head<3>();
                EXPECT_LT((R * x + t - expected).norm(), 1e-12) << name << " limb " << j;
                EXPECT_LT((R - R_D).cwiseAbs().maxCoeff(), 1e-12) << name << " limb " << j;
            }
        }
    }
}

TEST(SpatialKinematics, TheClosedFormsAreNewtonsHomeBranch) {
    // every shipped limb has a closed form (Delta R-U-U, 6-UPS U-P-S, 6-RUS R-U-S), as the random
    // hexapods' legs; at random poses it solves every limb and gives Newton's joint variables,
    // Newton from home (a fresh Data) and Newton along the samples
    std::mt19937 rng(11);
    std::vector<std::pair<SpatialRobotDescription, LimbSolver>> robots{{shipped("delta"), LimbSolver::ruu},
                                                                       {shipped("stewart"), LimbSolver::ups},
                                                                       {shipped("hexa-6rus"), LimbSolver::rus}};
    for (int i = 0; i < 3; ++i) {
        for (const bool rus : {false, true})
            robots.emplace_back(randomHexapod(rng, rus), rus ? LimbSolver::rus : LimbSolver::ups);
    }
    for (const auto& [description, solver] : robots) {
        const Model model(description);
        Model newton = model;
        for (Limb& limb : newton.limb) {
            EXPECT_EQ(limb.solver, solver) << model.name << " " << limb.name;
            limb.solver = LimbSolver::newton;
        }
        Data data(model), along(newton);
        const double reach = model.task_dimension == 6 ? 0.04 : 0.08;
        for (int trial = 0; trial < 30; ++trial) {
            const TaskVector p = model.home + randomTask(rng, model.task_dimension, reach, 1.5 * reach);
            Data fresh(newton);
            data = Data(model);  // from home: the closed form (a random jump follows Newton's branch)
            ASSERT_TRUE(inverseKinematics(model, data, p).ok()) << model.name;
            ASSERT_TRUE(inverseKinematics(newton, fresh, p).ok()) << model.name;
            ASSERT_TRUE(inverseKinematics(newton, along, p).ok()) << model.name;
            for (int j = 0; j < model.limbs(); ++j) {
                const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
                EXPECT_TRUE(ld.closed_form) << model.name << " limb " << j;
                EXPECT_FALSE(fresh.limb[static_cast<std::size_t>(j)].closed_form);
                EXPECT_LT((ld.q - fresh.limb[static_cast<std::size_t>(j)].q).cwiseAbs().maxCoeff(), 1e-12)
                    << model.name << " limb " << j;
                EXPECT_LT((ld.q - along.limb[static_cast<std::size_t>(j)].q).cwiseAbs().maxCoeff(), 1e-12)
                    << model.name << " limb " << j;
            }
            // the condition numbers left by the inverse kinematics bound the exact ones
            Data exact = data;
            conditionNumbers(model, exact);
            EXPECT_GE(data.actuation_condition, exact.actuation_condition * (1.0 - 1e-12)) << model.name;
            EXPECT_LT(exact.actuation_condition, model.max_condition) << model.name;
            for (int j = 0; j < model.limbs(); ++j) {
                EXPECT_GE(data.limb[static_cast<std::size_t>(j)].condition,
                          exact.limb[static_cast<std::size_t>(j)].condition * (1.0 - 1e-12));
            }
        }
    }
}

TEST(SpatialKinematics, APoseBeyondAClosedFormsReachIsRefusedAsByNewton) {
    // 3 m up: the cranks cannot reach (the same unreachable status naming the same limb as
    // Newton's); the Stewart platform's legs, prismatic without limits, can (Newton's lengths)
    for (const std::string name : {"delta", "hexa-6rus", "stewart"}) {
        const Model model(shipped(name));
        Model newton = model;
        for (Limb& limb : newton.limb) limb.solver = LimbSolver::newton;
        Data data(model), reference(newton);
        TaskVector p = model.home;
        p(2) += 3.0;
        const Status status = inverseKinematics(model, data, p), expected = inverseKinematics(newton, reference, p);
        EXPECT_EQ(status.code, expected.code) << name;
        EXPECT_EQ(status.limb, expected.limb) << name;
        if (name != "stewart") {
            EXPECT_EQ(status.code, StatusCode::unreachable) << name;
            continue;
        }
        for (int j = 0; j < model.limbs(); ++j) {
            EXPECT_LT((data.limb[static_cast<std::size_t>(j)].q - reference.limb[static_cast<std::size_t>(j)].q)
                          .cwiseAbs()
                          .maxCoeff(),
                      1e-12);
        }
    }
}

TEST(SpatialDynamics, ShippedRobotsSatisfyLagrangesEquations) {
    std::mt19937 rng(11);
    for (const std::string name : {"delta", "stewart", "hexa-6rus"}) {
        const Model model(frictionless(shipped(name)));
        for (int trial = 0; trial < 4; ++trial) {
            const int d = model.task_dimension;
            const TaskVector p = model.home + randomTask(rng, d, 0.04, 0.06);
            const double error = lagrangeError(model, p, randomTask(rng, d, 0.5, 0.8), randomTask(rng, d, 5.0, 8.0));
            EXPECT_LT(error, 1e-7) << name << " trial " << trial;
        }
    }
}

TEST(SpatialDynamics, RandomHexapodsSatisfyLagrangesEquations) {
    std::mt19937 rng(2026);
    for (const bool rus : {false, true}) {
        for (int robot = 0; robot < 4; ++robot) {
            const Model model(randomHexapod(rng, rus));
            Data data(model);
            ASSERT_TRUE(inverseKinematics(model, data, model.home).ok()) << model.name << " " << robot;
            const TaskVector p = model.home + randomTask(rng, 6, 0.03, 0.05);
            const double error = lagrangeError(model, p, randomTask(rng, 6, 0.4, 0.6), randomTask(rng, 6, 4.0, 6.0));
            EXPECT_LT(error, 1e-7) << model.name << " " << robot;
        }
    }
}

TEST(SpatialDynamics, ThePowerOfTheActuatorsIsTheRateOfEnergyPlusTheFrictionsLoss) {
    // tau . du = dE/dt + sum_k f_friction,k gd_k along p(t) = p0 + v t + a t^2 / 2
    std::mt19937 rng(5);
    for (const std::string name : {"delta", "stewart", "hexa-6rus"}) {
        const Model model(shipped(name));
        const int d = model.task_dimension;
        const TaskVector p0 = model.home + randomTask(rng, d, 0.04, 0.06);
        const TaskVector v = randomTask(rng, d, 0.5, 0.8), a = randomTask(rng, d, 5.0, 8.0);
        Data data(model);
        const auto energy = [&](double t) {
            EXPECT_TRUE(inverseDynamics(model, data, p0 + t * v + 0.5 * t * t * a, v + t * a, a).ok());
            return kineticEnergy(model, data) + potentialEnergy(model, data);
        };
        const double dE = derivative(energy, 1e-4);
        ASSERT_TRUE(inverseDynamics(model, data, p0, v, a).ok());
        double loss = 0.0;
        for (int j = 0; j < model.limbs(); ++j) {
            const Limb& limb = model.limb[static_cast<std::size_t>(j)];
            for (int k = 0; k < limb.size(); ++k) {
                const Freedom& f = limb.freedoms[static_cast<std::size_t>(k)];
                const double gd = data.limb[static_cast<std::size_t>(j)].gd(k);
                loss += (f.damping * gd + f.friction * (gd > 0.0 ? 1.0 : -1.0)) * gd;
            }
        }
        EXPECT_GT(loss, 0.0) << name;  // the shipped robots have friction
        const double power = data.tau.dot(data.du);
        EXPECT_NEAR(power, dE + loss, 1e-7 * (std::abs(power) + std::abs(loss))) << name;
    }
}

TEST(SpatialForwardDynamics, GivesBackTheAccelerationsWhoseForcesTheInverseDynamicsComputed) {
    // tau = ID(p, dp, ddp), then FD(p, dp, tau) = ddp: friction on (the shipped robots), the
    // Delta's translation task, and random 6-UPS and 6-RUS hexapods
    std::mt19937 rng(17);
    std::vector<SpatialRobotDescription> robots{shipped("delta"), shipped("stewart"), shipped("hexa-6rus")};
    for (const bool rus : {false, true}) robots.push_back(randomHexapod(rng, rus));
    for (const SpatialRobotDescription& description : robots) {
        const Model model(description);
        const int d = model.task_dimension;
        Data data(model), back(model);
        for (int trial = 0; trial < 3; ++trial) {
            const TaskVector p = model.home + randomTask(rng, d, 0.03, 0.05);
            const TaskVector dp = randomTask(rng, d, 0.4, 0.6), ddp = randomTask(rng, d, 4.0, 6.0);
            ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok()) << model.name;
            TaskVector found;
            const Status status = forwardDynamics(model, back, p, dp, data.tau, found);
            ASSERT_TRUE(status.ok()) << model.name << ": " << describe(status, model);
            EXPECT_LT((found - ddp).cwiseAbs().maxCoeff(), 1e-9 * ddp.cwiseAbs().maxCoeff())
                << model.name << " trial " << trial;
            EXPECT_LT((back.ddu - data.ddu).cwiseAbs().maxCoeff(), 1e-9 * data.ddu.cwiseAbs().maxCoeff());
            EXPECT_EQ(back.tau, data.tau);
        }
    }
}

TEST(SpatialForwardDynamics, RefusesForcesOfTheWrongCountOrNotFinite) {
    const Model model(shipped("stewart"));
    Data data(model);
    TaskVector ddp;
    const TaskVector rest = TaskVector::Zero(6);
    EXPECT_EQ(forwardDynamics(model, data, model.home, rest, ActuatorVector::Zero(5), ddp).code,
              StatusCode::not_finite);
    ActuatorVector tau = ActuatorVector::Zero(6);
    tau(2) = std::nan("");
    EXPECT_EQ(forwardDynamics(model, data, model.home, rest, tau, ddp).code, StatusCode::not_finite);
    TaskVector tilted = model.home;
    tilted(4) = std::acos(0.0);  // pitch at 90 degrees: the Euler angles' singularity
    EXPECT_EQ(forwardDynamics(model, data, tilted, rest, ActuatorVector::Zero(6), ddp).code, StatusCode::not_finite);
    const Model delta(shipped("delta"));
    Data delta_data(delta);
    TaskVector far = delta.home;
    far(0) += 2.0;  // beyond the arms' reach
    EXPECT_EQ(forwardDynamics(delta, delta_data, far, TaskVector::Zero(3), ActuatorVector::Zero(3), ddp).code,
              StatusCode::unreachable);
    // the forces that hold the table at rest hold it; without them it falls
    ASSERT_TRUE(inverseDynamics(model, data, model.home, rest, rest).ok());
    const ActuatorVector holding = data.tau;
    ASSERT_TRUE(forwardDynamics(model, data, model.home, rest, holding, ddp).ok());
    EXPECT_LT(ddp.cwiseAbs().maxCoeff(), 1e-10);
    ASSERT_TRUE(forwardDynamics(model, data, model.home, rest, ActuatorVector::Zero(6), ddp).ok());
    EXPECT_LT(ddp(2), -1.0);
}

TEST(SpatialSimulation, ConservesTheEnergyUnderConstantForcesWithoutFriction) {
    // constant forces are conservative (potential -tau . u): H = T + V - tau . u stays constant;
    // the loops close exactly at every evaluation, so H's drift is the integrator's error
    std::mt19937 rng(23);
    for (const std::string name : {"delta", "stewart", "hexa-6rus"}) {
        const Model model(frictionless(shipped(name)));
        const int d = model.task_dimension;
        Data data(model);
        const TaskVector rest = TaskVector::Zero(d);
        ASSERT_TRUE(inverseDynamics(model, data, model.home, rest, rest).ok());
        const nocdyn::ActuatorVector holding = data.tau;
        Simulator simulator(model);
        ASSERT_TRUE(simulator.reset(model.home, randomTask(rng, d, 0.05, 0.1)).ok()) << name;
        simulator.setForces(holding);
        const auto H = [&] {
            return simulator.kineticEnergy() + simulator.potentialEnergy() - holding.dot(simulator.data().u);
        };
        const double H0 = H(), T0 = simulator.kineticEnergy();
        double drift = 0.0, travel = 0.0;
        for (int k = 1; k <= 50; ++k) {
            const Status status = simulator.advance(0.01);
            ASSERT_TRUE(status.ok()) << name << " at " << simulator.time() << ": " << describe(status, model);
            drift = std::max(drift, std::abs(H() - H0));
            travel = std::max(travel, (simulator.pose() - model.home).cwiseAbs().maxCoeff());
        }
        EXPECT_LT(drift, 1e-8 * T0) << name;
        EXPECT_GT(travel, 1e-3) << name;  // it moved
    }
}

TEST(SpatialSimulation, ReplaysTheMotionWhoseForcesTheInverseDynamicsComputed) {
    // tau(t) from the inverse dynamics of p(t) = home + a sin(2 pi f t) sampled at 1 kHz, then
    // simulated from p(0), dp(0) under the cubic spline of those forces: the motion comes back
    // (without friction, whose Coulomb jumps no spline of samples follows)
    for (const std::string name : {"delta", "stewart"}) {
        const Model model(frictionless(shipped(name)));
        const int d = model.task_dimension;
        Data data(model);
        TaskVector amplitude(d);
        for (int i = 0; i < d; ++i) amplitude(i) = i < 3 ? 0.01 : 0.02;
        const double w = 2.0 * std::acos(-1.0) * 2.0;
        std::vector<double> times;
        std::vector<nocdyn::ActuatorVector> forces;
        for (int k = 0; k <= 300; ++k) {
            const double t = 1e-3 * k;
            const TaskVector p = model.home + amplitude * std::sin(w * t), dp = amplitude * w * std::cos(w * t),
                             ddp = -amplitude * w * w * std::sin(w * t);
            ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok()) << name;
            times.push_back(t);
            forces.emplace_back(data.tau);
        }
        Simulator simulator(model);
        ASSERT_TRUE(simulator.reset(model.home, amplitude * w).ok());
        simulator.setForces(ForceSignal(times, forces, Interpolation::cubic));
        ASSERT_TRUE(simulator.advance(0.3).ok()) << name;
        const TaskVector expected = model.home + amplitude * std::sin(w * 0.3);
        EXPECT_LT((simulator.pose() - expected).cwiseAbs().maxCoeff(), 1e-9 * amplitude.maxCoeff()) << name;
    }
}

/// A forces CSV for `nocdyn simulate`: the inverse dynamics of p(t) = home + a sin(2 pi 2 t)
/// at 1 kHz over 0.1 s, with the first row's pose and either its rates or the actuators' rates.
std::string writeForces(const Model& model, const std::filesystem::path& path, bool pose_rates) {
    const int d = model.task_dimension, n = model.actuators;
    const std::vector<std::string> names = model.coordinates();
    Data data(model);
    std::ofstream out(path);
    out.precision(17);
    out << "t";
    for (const std::string& c : names) out << "," << c;
    for (int i = 0; i < d; ++i) out << (pose_rates ? ",d" + names[static_cast<std::size_t>(i)] : "");
    for (int a = 1; a <= n; ++a) out << (pose_rates ? "" : ",du" + std::to_string(a));
    for (int a = 1; a <= n; ++a) out << ",tau" << a;
    out << "\n";
    const TaskVector amplitude = TaskVector::Constant(d, 0.01);
    const double w = 4.0 * std::acos(-1.0);
    for (int k = 0; k <= 100; ++k) {
        const double t = 1e-3 * k;
        const TaskVector p = model.home + amplitude * std::sin(w * t), dp = amplitude * w * std::cos(w * t);
        EXPECT_TRUE(inverseDynamics(model, data, p, dp, -amplitude * w * w * std::sin(w * t)).ok());
        out << t;
        for (int i = 0; i < d; ++i) out << "," << p(i);
        for (int i = 0; i < (pose_rates ? d : n); ++i) out << "," << (pose_rates ? dp(i) : data.du(i));
        for (int a = 0; a < n; ++a) out << "," << data.tau(a);
        out << "\n";
    }
    return path.string();
}

TEST(SpatialSimulation, TheCommandLineWritesTheSimulatorsMotionFromTheFirstRowsState) {
    // the Delta over a shorter span: its Coulomb friction's jumps cost many steps
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_simulate");
    for (const auto& [name, duration] : {std::pair<std::string, double>{"stewart", 0.1}, {"delta", 0.02}}) {
        const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml";
        const Model model(shipped(name));
        const int d = model.task_dimension, n = model.actuators;
        const auto rows = static_cast<std::size_t>(std::lround(duration * 1000.0)) + 1;  // t = 0, 1 ms, ..
        std::vector<double> last;
        for (const bool pose_rates : {true, false}) {
            const std::string forces = writeForces(model, dir / (name + "-forces.csv"), pose_rates);
            const std::string output = (dir / (name + "-motion.csv")).string();
            const test::CliResult r =
                test::runCli("simulate --robot " + robot + " --forces " + forces + " --rate 1000 --duration " +
                             std::to_string(duration) + " -o " + output);
            ASSERT_EQ(r.exit_code, 0) << r.err;
            EXPECT_NE(r.err.find(pose_rates ? "first row's " : "and du1..du"), std::string::npos) << r.err;
            const io::Table motion = io::readCsvFile(output);
            ASSERT_EQ(motion.rows.size(), rows);
            ASSERT_EQ(motion.columns.size(), static_cast<std::size_t>(1 + d + 3 * n + 1));
            EXPECT_EQ(motion.columns[static_cast<std::size_t>(d)], d == 6 ? "yaw" : "z");
            const std::vector<double>& row = motion.rows.back();
            if (!last.empty()) {
                // the first row's rates given by du1..dun give the motion given by dx..
                for (int i = 0; i <= d; ++i) {
                    EXPECT_NEAR(row[static_cast<std::size_t>(i)], last[static_cast<std::size_t>(i)], 1e-8) << name;
                }
            }
            last = row;
        }
        // the in-process simulator from the same state under the same forces
        const io::Table table = io::readCsvFile((dir / (name + "-forces.csv")).string());
        std::vector<double> times;
        std::vector<nocdyn::ActuatorVector> forces;
        for (const std::vector<double>& row : table.rows) {
            times.push_back(row[0]);
            nocdyn::ActuatorVector tau(n);
            for (int a = 0; a < n; ++a) tau(a) = row[static_cast<std::size_t>(1 + d + n + a)];
            forces.push_back(tau);
        }
        Simulator simulator(model);
        const double w = 4.0 * std::acos(-1.0);
        ASSERT_TRUE(simulator.reset(model.home, TaskVector::Constant(d, 0.01 * w)).ok());
        simulator.setForces(ForceSignal(times, forces, Interpolation::cubic));
        ASSERT_TRUE(simulator.advance(duration).ok());
        for (int i = 0; i < d; ++i) {
            EXPECT_NEAR(last[static_cast<std::size_t>(1 + i)], simulator.pose()(i), 1e-8) << name;
        }
        // with friction the motion is near the inverse dynamics' one, not on it (Coulomb's jumps)
        EXPECT_NEAR(last[1], model.home(0) + 0.01 * std::sin(w * duration), 2e-4) << name;
    }
}

TEST(SpatialSimulation, TheCommandLineRefusesAPlanarRowOrActuatorsAloneNamingTheFile) {
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_simulate_bad");
    const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/stewart.yaml";
    const auto run = [&](const std::string& name, const std::string& text, const std::string& more = "") {
        const std::filesystem::path path = dir / name;
        std::ofstream(path) << text;
        return test::runCli("simulate --robot " + robot + " --forces " + path.string() + more);
    };
    const std::string taus = "tau1,tau2,tau3,tau4,tau5,tau6";
    test::CliResult r = run("theta.csv", "t,x,y,theta," + taus + "\n0,0,0,0,1,1,1,1,1,1\n0.1,0,0,0,1,1,1,1,1,1\n");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("theta.csv:2: column 'theta'"), std::string::npos) << r.err;
    r = run("u.csv", "t,u1,u2,u3,u4,u5,u6," + taus + "\n0,1,1,1,1,1,1,1,1,1,1,1,1\n0.1,1,1,1,1,1,1,1,1,1,1,1,1\n");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("a spatial robot starts from a pose"), std::string::npos) << r.err;
    r = run("part.csv", "t,x,y,z," + taus + "\n0,0,0,1,1,1,1,1,1,1\n0.1,0,0,1,1,1,1,1,1,1\n");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("the pose needs every column of x,y,z,roll,pitch,yaw"), std::string::npos) << r.err;
    r = run("ok.csv", "t," + taus + "\n0,1,1,1,1,1,1\n0.1,1,1,1,1,1,1\n", " --reactions");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("planar for now"), std::string::npos) << r.err;
}

TEST(SpatialReactions, EveryFreedomPassesItsEffortAndThePlatformBalances) {
    // s_k . W_k = tau_k - phi_k for every freedom k (its actuator's force, less its friction
    // phi_k = damping gd_k + friction sign gd_k; 0 on the U and S joints' freedoms), and
    // sum_j F_j = w_P: on the shipped robots (friction on) and random 6-UPS and 6-RUS
    std::mt19937 rng(31);
    std::vector<SpatialRobotDescription> robots{shipped("delta"), shipped("stewart"), shipped("hexa-6rus")};
    for (const bool rus : {false, true}) robots.push_back(randomHexapod(rng, rus));
    for (const SpatialRobotDescription& description : robots) {
        const Model model(description);
        const int d = model.task_dimension;
        Data data(model);
        Reactions reactions(model);
        for (int trial = 0; trial < 3; ++trial) {
            const TaskVector p = model.home + randomTask(rng, d, 0.03, 0.05);
            ASSERT_TRUE(
                inverseDynamics(model, data, p, randomTask(rng, d, 0.4, 0.6), randomTask(rng, d, 4.0, 6.0)).ok());
            ASSERT_TRUE(jointReactions(model, data, reactions).ok()) << model.name;
            const double scale = data.platform_wrench.cwiseAbs().maxCoeff() + data.tau.cwiseAbs().maxCoeff();
            EXPECT_LT(reactions.balance_residual, 1e-10 * scale) << model.name;
            for (int j = 0; j < model.limbs(); ++j) {
                const Limb& limb = model.limb[static_cast<std::size_t>(j)];
                const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
                for (int k = 0; k < limb.size(); ++k) {
                    const Freedom& f = limb.freedoms[static_cast<std::size_t>(k)];
                    const double gd = ld.gd(k);
                    double expected = -(f.damping * gd + f.friction * (gd > 0.0 ? 1.0 : (gd < 0.0 ? -1.0 : 0.0)));
                    if (f.actuator >= 0) expected += data.tau(f.actuator);
                    const Vector6& W =
                        reactions.joint[static_cast<std::size_t>(j)][static_cast<std::size_t>(f.joint)].wrench;
                    EXPECT_NEAR(ld.J.col(k).dot(W), expected, 1e-10 * scale)
                        << model.name << " limb " << j << " freedom " << k;
                }
                // no moment through an S joint, none about a U's axes; no force along a P
                for (const JointReaction& r : reactions.joint[static_cast<std::size_t>(j)]) {
                    if (r.type == 'S') {
                        EXPECT_LT(r.moment.norm(), 1e-10 * scale) << model.name;
                    }
                    const Eigen::Vector3d raw = r.wrench.head<3>() - r.point.cross(r.wrench.tail<3>());
                    if (r.type == 'S' || r.type == 'U') {
                        EXPECT_LT((raw - r.moment).norm(), 1e-10 * scale) << model.name;
                    }
                }
            }
        }
    }
}

TEST(SpatialReactions, AHexapodWithMasslessLegsPushesAlongEachLegWithItsActuatorsForce) {
    // two-force members: at rest each massless leg's S joint passes a force along the leg, of
    // the cylinder's force (a closed form), and the base U joint the same
    SpatialRobotDescription description = frictionless(shipped("stewart"));
    for (SpatialLimbDescription& limb : description.limbs) {
        for (SpatialBodyDescription& body : limb.bodies) {
            body.mass = 0.0;
            body.inertia.setZero();
        }
    }
    const Model model(description);
    Data data(model);
    Reactions reactions(model);
    const TaskVector p = model.home + TaskVector::Constant(6, 0.02);
    ASSERT_TRUE(inverseDynamics(model, data, p, TaskVector::Zero(6), TaskVector::Zero(6)).ok());
    ASSERT_TRUE(jointReactions(model, data, reactions).ok());
    for (int j = 0; j < 6; ++j) {
        const auto& joints = reactions.joint[static_cast<std::size_t>(j)];
        ASSERT_EQ(joints.size(), 3U);
        EXPECT_EQ(joints[0].type, 'U');
        EXPECT_EQ(joints[1].type, 'P');
        EXPECT_EQ(joints[2].type, 'S');
        const Eigen::Vector3d leg = (joints[2].point - joints[0].point).normalized();
        const double tau = data.tau(j);
        // the base pushes the leg out along +leg with the cylinder's force
        EXPECT_NEAR(joints[2].force.dot(leg), tau, 1e-9 * std::abs(tau)) << j;
        EXPECT_LT((joints[2].force - tau * leg).norm(), 1e-9 * std::abs(tau)) << j;
        EXPECT_LT((joints[0].force - tau * leg).norm(), 1e-9 * std::abs(tau)) << j;
        EXPECT_LT(joints[0].moment.norm(), 1e-9 * std::abs(tau)) << j;
        EXPECT_LT(joints[1].force.norm(), 1e-9 * std::abs(tau)) << j;  // the P passes tau along itself
    }
}

TEST(SpatialControl, ComputedTorqueTracksTheExampleTrajectoriesAndPdLags) {
    // the plant is the controller's model: computed torque leaves only the hold's error; PD,
    // without the model's gravity and dynamics, an error orders of magnitude larger
    for (const auto& [name, file] :
         {std::pair<std::string, std::string>{"stewart", "stewart-sway"}, {"delta", "delta-pick"}}) {
        const Model model(shipped(name));
        const Trajectory trajectory = io::loadSpatialTrajectory(
            std::string(NOCDYN_SOURCE_DIR) + "/trajectories/" + file + ".yaml", model.task_dimension);
        LoopOptions options;
        options.rate = 2000.0;
        options.duration = 0.05;
        const LoopResult ct = runPoseLoop(model, trajectory, options);
        ASSERT_EQ(ct.t.size(), 100U);
        options.controller = ControlLaw::pd;
        const LoopResult pd = runPoseLoop(model, trajectory, options);
        // measured 1.7e-7 m (Stewart) and 1.9e-8 m (Delta); PD 1.0e-4 and 9.6e-5 m
        EXPECT_LT(ct.peak_error.head<3>().maxCoeff(), 1e-6) << name;
        EXPECT_GT(pd.peak_error.head<3>().maxCoeff(), 100.0 * ct.peak_error.head<3>().maxCoeff()) << name;
        EXPECT_EQ(ct.saturated_ticks, 0U);
    }
}

TEST(SpatialControl, TheCommandLineTracksAndRefusesWhatIsPlanarForNow) {
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_control");
    const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/delta.yaml";
    const std::string trajectory = std::string(NOCDYN_SOURCE_DIR) + "/trajectories/delta-pick.yaml";
    const std::string output = (dir / "loop.csv").string();
    const test::CliResult r = test::runCli("control --robot " + robot + " --trajectory " + trajectory +
                                           " --duration 0.05 --rate 2000 -o " + output);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("computed-torque on the nocdyn plant, delta, delta-pick"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("saturated ticks: 0 of 100"), std::string::npos) << r.out;
    const io::Table loop = io::readCsvFile(output);
    ASSERT_EQ(loop.rows.size(), 100U);
    ASSERT_EQ(loop.columns.size(), 1U + 3U + 3U + 3U + 3U);
    EXPECT_EQ(loop.columns[1], "x_d");
    EXPECT_EQ(loop.columns[4], "x");
    // the table's tracking error is the loop's: below a micrometre
    double peak = 0.0;
    for (const std::vector<double>& row : loop.rows) {
        for (std::size_t i = 0; i < 3; ++i) peak = std::max(peak, std::abs(row[1 + i] - row[4 + i]));
    }
    EXPECT_GT(peak, 0.0);
    EXPECT_LT(peak, 1e-6);
    for (const std::string& more : {std::string(" --plant simbody"), std::string(" --payload-mass 1"),
                                    std::string(" --figure ") + (dir / "f").string()}) {
        const test::CliResult bad =
            test::runCli("control --robot " + robot + " --trajectory " + trajectory + " --duration 0.01" + more);
        EXPECT_NE(bad.exit_code, 0) << more;
        EXPECT_NE(bad.err.find("planar for now"), std::string::npos) << more << ": " << bad.err;
    }
}

TEST(SpatialDynamics, TheDeltaKeepsItsOrientationAndAnUnreachablePoseIsNamed) {
    const Model model(shipped("delta"));
    Data data(model);
    TaskVector p = model.home;
    p(2) -= 0.6;  // 1.4 m below the base: beyond the 0.35 + 0.8 m arms
    const Status status = inverseKinematics(model, data, p);
    EXPECT_EQ(status.code, StatusCode::unreachable);
    EXPECT_EQ(describe(status, model).rfind("pose out of reach: limb 1 (arm1) cannot close", 0), 0u)
        << describe(status, model);
    // a reachable pose after the failure closes again (from home)
    p = model.home;
    p(0) += 0.1;
    ASSERT_TRUE(inverseKinematics(model, data, p).ok());
    EXPECT_EQ(model.coordinates(), (std::vector<std::string>{"x", "y", "z"}));
}

TEST(SpatialDynamics, AHexapodHoldsItsTableAsStaticsSays) {
    // at rest the legs carry the weights: the sum of the forces' vertical parts through the
    // legs' directions is the table's weight plus the rods' share (virtual work in z)
    const Model model(frictionless(shipped("stewart")));
    Data data(model);
    const TaskVector zero = TaskVector::Zero(6);
    ASSERT_TRUE(inverseDynamics(model, data, model.home, zero, zero).ok());
    // the platform's vertical virtual displacement dz raises each leg by du = A e_z
    Vector6 twist;
    twist << 0.0, 0.0, 0.0, 0.0, 0.0, 1.0;
    const ActuatorVector du = data.A * twist;
    double weight_power = 9.81 * model.platform_mass;  // the table rises at 1 m/s
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        const FreedomVector gd = ld.J_plus * twist;
        for (std::size_t b = 0; b < limb.bodies.size(); ++b) {
            Vector6 t = Vector6::Zero();
            for (int k = 0; k <= limb.bodies[b].last_freedom; ++k) t += ld.J.col(k) * gd(k);
            const Eigen::Vector3d v_c = t.tail<3>() + t.head<3>().cross(ld.com[b]);
            weight_power += 9.81 * limb.bodies[b].mass * v_c.z();
        }
    }
    EXPECT_NEAR(data.tau.dot(du), weight_power, 1e-9 * weight_power);
    EXPECT_GT(data.tau.minCoeff(), 0.0);  // every leg pushes
}

TEST(SpatialLimits, EachLimitNamesItsJointAndAStatusOfNoJointStillReads) {
    const Model model(shipped("stewart"));
    Data data(model);
    TaskVector p = model.home;
    p(2) += 0.2;  // every leg 0.2 m longer or so: beyond the cylinders' +0.15 m
    ASSERT_TRUE(inverseDynamics(model, data, p, TaskVector::Zero(6), TaskVector::Zero(6)).ok());
    const Status passed = checkLimits(model, data);
    ASSERT_EQ(passed.code, StatusCode::joint_limit_exceeded);
    EXPECT_EQ(passed.limb, 0);
    EXPECT_EQ(passed.joint, 1);  // the P, the second listed joint
    EXPECT_GT(passed.value, 0.15);
    EXPECT_EQ(describe(passed, model).rfind("joint range exceeded: limb 1 (leg1), joint 2: q = 0.1", 0), 0U)
        << describe(passed, model);
    // a status naming no joint of this model reads as one line instead of going round describe()
    const Status stray{StatusCode::effort_exceeded, -1, 2.0, -1};
    EXPECT_EQ(describe(stray, model), "a joint's limit passed (limb 0, joint 0, value 2)");
    ASSERT_TRUE(inverseDynamics(model, data, model.home, TaskVector::Zero(6), TaskVector::Zero(6)).ok());
    EXPECT_TRUE(checkLimits(model, data).ok());
}

}  // namespace
}  // namespace nocdyn::spatial
