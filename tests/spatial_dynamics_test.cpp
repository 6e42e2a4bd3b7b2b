// The spatial NOC (nocdyn/spatial.hpp) against identities that need no engine: every limb closes
// on the platform's displacement; Lagrange's equations by finite differences of the kinetic and
// potential energies (the generalised forces (du/dp)^T tau, friction off); the power balance with
// friction; on the shipped Delta, 6-UPS and 6-RUS and on random 6-UPS and 6-RUS hexapods.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/spatial_simulator.hpp"
#include "nocdyn/spatial.hpp"

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
    for (const std::string name : {"delta", "stewart", "6-rus"}) {
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
    for (const std::string name : {"delta", "stewart", "6-rus"}) {
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

TEST(SpatialDynamics, ShippedRobotsSatisfyLagrangesEquations) {
    std::mt19937 rng(11);
    for (const std::string name : {"delta", "stewart", "6-rus"}) {
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
    for (const std::string name : {"delta", "stewart", "6-rus"}) {
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
    std::vector<SpatialRobotDescription> robots{shipped("delta"), shipped("stewart"), shipped("6-rus")};
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
    for (const std::string name : {"delta", "stewart", "6-rus"}) {
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

}  // namespace
}  // namespace nocdyn::spatial
