// Two-DOF planar robots (motion: translation, pose [x, y] of a point tool): the five-bar
// (RRRRR) and the biglide (PRRRP) through the planar core with the task map E.
//   - The five-bar's inverse dynamics against Lagrange's equations written in the actuated
//     angles u with a hand-written model of the mechanism (arm angles, the tool point as the
//     intersection of the forearms' circles, every body's pose from them), the energies from the
//     description's masses and inertias and every derivative by finite differences:
//       tau_k = sum_j M_kj ddu_j + sum_jl (dM_kj/du_l - dM_jl/du_k / 2) du_j du_l + dV/du_k.
//   - The power balance tau . du = d/dt (kinetic + potential energy) on random five-bars, biglides
//     and three-armed (redundant) point robots, and the minimum-norm forces of the redundant ones.
//   - Inverse kinematics: every working mode closes every limb on the tool point, the round trip
//     through the hand-written direct kinematics, the actuation and limb Jacobians against finite
//     differences of the inverse kinematics, and both singularity types.
//   - Robot files: the refusals of `motion: translation` and the writer's round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "point_robots.hpp"

namespace nocdyn::test {
namespace {

// Measured on the shipped five-bar: |tau - Lagrange| <= 3e-10 of the scale (largest term).
constexpr double kLagrangeTolerance = 1e-7;
// Measured: |tau . du - dE/dt| <= 1.9e-9 of the largest power term on the random robots.
constexpr double kPowerTolerance = 1e-7;
// Measured: the finite-difference Jacobians agree to 1e-10 relative.
constexpr double kJacobianTolerance = 1e-7;
constexpr double kClosureTolerance = 1e-12;  // [m]
// Samples kept for the power balance: scaled condition numbers of every J_j and of A below this.
constexpr double kConditionLimit = 1e2;

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

RobotDescription shipped(const std::string& name) {
    return io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml");
}

Vector2 rotate(double a, const Vector2& v) {
    return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
}
double cross(const Vector2& a, const Vector2& b) { return a.x() * b.y() - a.y() * b.x(); }
/// The angle that turns a onto b's direction, in (-pi, pi].
double angleBetween(const Vector2& a, const Vector2& b) { return std::atan2(cross(a, b), a.dot(b)); }

/// Five-point central difference of f at x along a unit step h.
template <class F>
auto stencil(F f, double h) {
    using Value = decltype(f(0.0));  // evaluated: no expression of temporaries
    const Value out = (f(-2.0 * h) - 8.0 * f(-h) + 8.0 * f(h) - f(2.0 * h)) / (12.0 * h);
    return out;
}

// ---------------------------------------------------------------------------------------------
// The hand-written five-bar: two arms A_j B_j turned by u_j from home, forearms B_j C with C
// on both forearms' circles, on the side of B_1 B_2 it is at home.
struct FiveBar {
    std::array<Vector2, 2> A, B0, arm_com0, forearm_com0;
    std::array<double, 2> l2{}, arm_mass{}, arm_inertia{}, forearm_mass{}, forearm_inertia{};
    Vector2 C0 = Vector2::Zero();
    double tool_mass = 0.0, side = 0.0;
    Vector2 g = Vector2::Zero();

    explicit FiveBar(const RobotDescription& d) {
        for (std::size_t j = 0; j < 2; ++j) {
            const LimbDescription& limb = d.limbs[j];
            A[j] = limb.joints[0].point;
            B0[j] = limb.joints[1].point;
            C0 = limb.joints[2].point;
            l2[j] = (C0 - B0[j]).norm();
            arm_mass[j] = limb.bodies[0].mass, arm_inertia[j] = limb.bodies[0].inertia;
            forearm_mass[j] = limb.bodies[1].mass, forearm_inertia[j] = limb.bodies[1].inertia;
            arm_com0[j] = limb.bodies[0].com, forearm_com0[j] = limb.bodies[1].com;
        }
        tool_mass = d.platform.mass;
        g = d.gravity;
        side = cross(B0[1] - B0[0], C0 - B0[0]) > 0.0 ? 1.0 : -1.0;
    }

    [[nodiscard]] Vector2 elbow(std::size_t j, double u) const { return A[j] + rotate(u, B0[j] - A[j]); }

    /// Direct kinematics: the tool point for the arm angles u (the home assembly mode).
    [[nodiscard]] Vector2 tool(const Vector2& u) const {
        const Vector2 B1 = elbow(0, u(0)), B2 = elbow(1, u(1));
        const Vector2 d = B2 - B1;
        const double L = d.norm();
        const double a = (l2[0] * l2[0] - l2[1] * l2[1] + L * L) / (2.0 * L);
        const double h = std::sqrt(l2[0] * l2[0] - a * a);
        const Vector2 e = d / L;
        const Vector2 n(-e.y(), e.x());
        return B1 + a * e + side * h * n;
    }

    /// The five bodies' poses [angle, x, y] (arm 1, arm 2, forearm 1, forearm 2, tool) at u.
    [[nodiscard]] std::array<Vector3, 5> poses(const Vector2& u) const {
        const Vector2 C = tool(u);
        std::array<Vector3, 5> out;
        for (std::size_t j = 0; j < 2; ++j) {
            const double uj = u(static_cast<Eigen::Index>(j));
            const Vector2 arm_com = A[j] + rotate(uj, arm_com0[j] - A[j]);
            out[j] = Vector3(uj, arm_com.x(), arm_com.y());
            const Vector2 B = elbow(j, uj);
            const double turn = angleBetween(C0 - B0[j], C - B);
            const Vector2 forearm_com = B + rotate(turn, forearm_com0[j] - B0[j]);
            out[2 + j] = Vector3(turn, forearm_com.x(), forearm_com.y());
        }
        out[4] = Vector3(0.0, C.x(), C.y());
        return out;
    }

    [[nodiscard]] std::array<Vector3, 5> dyads() const {  // [inertia, mass, mass]
        return {Vector3(arm_inertia[0], arm_mass[0], arm_mass[0]), Vector3(arm_inertia[1], arm_mass[1], arm_mass[1]),
                Vector3(forearm_inertia[0], forearm_mass[0], forearm_mass[0]),
                Vector3(forearm_inertia[1], forearm_mass[1], forearm_mass[1]), Vector3(0.0, tool_mass, tool_mass)};
    }

    /// M(u) = sum_i G_i^T diag(I_i, m_i, m_i) G_i, G_i = d pose_i / du.
    [[nodiscard]] Eigen::Matrix2d mass(const Vector2& u) const {
        // 1e-4: the stencil's truncation (h^4) and rounding (eps / h) both below 1e-12
        constexpr double h = 1e-4;
        std::array<Eigen::Matrix<double, 3, 2>, 5> G;
        for (int k = 0; k < 2; ++k) {
            const auto pose_i = [&](double s) {
                Vector2 v = u;
                v(k) += s;
                const auto p = poses(v);
                Eigen::Matrix<double, 15, 1> all;
                for (std::size_t i = 0; i < 5; ++i) all.segment<3>(3 * static_cast<Eigen::Index>(i)) = p[i];
                return all;
            };
            const Eigen::Matrix<double, 15, 1> d = stencil(pose_i, h);
            for (std::size_t i = 0; i < 5; ++i) G[i].col(k) = d.segment<3>(3 * static_cast<Eigen::Index>(i));
        }
        Eigen::Matrix2d M = Eigen::Matrix2d::Zero();
        const auto D = dyads();
        for (std::size_t i = 0; i < 5; ++i) M += G[i].transpose() * D[i].asDiagonal() * G[i];
        return M;
    }

    [[nodiscard]] double potential(const Vector2& u) const {
        const auto p = poses(u);
        const auto D = dyads();
        double V = 0.0;
        for (std::size_t i = 0; i < 5; ++i) V -= D[i](1) * g.dot(p[i].tail<2>());
        return V;
    }

    /// Lagrange's equations in u: the actuator torques for u, du, ddu.
    [[nodiscard]] Vector2 torques(const Vector2& u, const Vector2& du, const Vector2& ddu, double& scale) const {
        // dM/du, a stencil of stencils: 1e-3 keeps the rounding of G (~1e-13) over h_M below 1e-9
        constexpr double h_M = 1e-3, h_V = 1e-4;
        const Eigen::Matrix2d M = mass(u);
        std::array<Eigen::Matrix2d, 2> dM;
        Vector2 dV;
        for (int l = 0; l < 2; ++l) {
            dM[static_cast<std::size_t>(l)] = stencil(
                [&](double s) {
                    Vector2 v = u;
                    v(l) += s;
                    return Eigen::Matrix2d(mass(v));
                },
                h_M);
            dV(l) = stencil(
                [&](double s) {
                    Vector2 v = u;
                    v(l) += s;
                    return potential(v);
                },
                h_V);
        }
        Vector2 tau = M * ddu + dV;
        scale = (M * ddu).cwiseAbs().maxCoeff() + dV.cwiseAbs().maxCoeff();
        for (int k = 0; k < 2; ++k) {
            double c = 0.0;
            for (int j = 0; j < 2; ++j) {
                for (int l = 0; l < 2; ++l) {
                    c += (dM[static_cast<std::size_t>(l)](k, j) - 0.5 * dM[static_cast<std::size_t>(k)](j, l)) * du(j) *
                         du(l);
                }
            }
            tau(k) += c;
            scale = std::max(scale, std::abs(c));
        }
        return tau;
    }
};

TaskVector task(double x, double y) {
    TaskVector p(2);
    p << x, y;
    return p;
}

/// A smooth tool motion about c: p(t), dp/dt, d2p/dt2.
struct Motion2 {
    Vector2 c, a, w, phase;
    void at(double t, TaskVector& p, TaskVector& dp, TaskVector& ddp) const {
        p.resize(2), dp.resize(2), ddp.resize(2);
        for (int i = 0; i < 2; ++i) {
            const double arg = w(i) * t + phase(i);
            p(i) = c(i) + a(i) * std::sin(arg);
            dp(i) = a(i) * w(i) * std::cos(arg);
            ddp(i) = -a(i) * w(i) * w(i) * std::sin(arg);
        }
    }
};

/// The core's pose [home(0), x, y] and rates [0, dx, dy] of task samples (poseOfTask and
/// rateOfTask for two task coordinates, written out).
Pose lift(const Model& model, const TaskVector& p) { return {model.home(0), p(0), p(1)}; }
Twist liftRate(const TaskVector& dp) { return {0.0, dp(0), dp(1)}; }

Status solve(const Model& model, Data& data, const TaskVector& p, const TaskVector& dp, const TaskVector& ddp) {
    return inverseDynamics(model, data, lift(model, p), liftRate(dp), liftRate(ddp));
}

// ---------------------------------------------------------------------------------------------

TEST(TwoDofModel, ShippedRobotsAreTranslatingPointTools) {
    for (const char* name : {"five-bar", "biglide"}) {
        const Model model(shipped(name));
        EXPECT_EQ(model.task_dimension, 2) << name;
        EXPECT_EQ(model.actuators, 2) << name;
        EXPECT_EQ(model.coordinates, Coordinates::platform) << name;
        const TaskMap E = taskMap(model);
        EXPECT_EQ(E.rows(), 3);
        EXPECT_EQ(E.cols(), 2);
        EXPECT_EQ(E(1, 0), 1.0);
        EXPECT_EQ(E(2, 1), 1.0);
        EXPECT_EQ(E.row(0).cwiseAbs().sum(), 0.0);
    }
}

TEST(TwoDofModel, FiveBarInverseDynamicsMatchesHandWrittenLagrangian) {
    for (const double gy : {0.0, -9.81}) {
        RobotDescription d = shipped("five-bar");
        d.gravity = Vector2(0.0, gy);  // the horizontal DexTAR, and standing in a vertical plane
        const Model model(d);
        const FiveBar hand(d);
        Data data(model);
        const Motion2 motion{Vector2(0.01, 0.32), Vector2(0.04, 0.05), Vector2(9.0, 13.0), Vector2(0.3, -0.7)};
        double worst = 0.0;
        for (int k = 0; k < 25; ++k) {
            TaskVector p, dp, ddp;
            motion.at(0.037 * k, p, dp, ddp);
            ASSERT_TRUE(solve(model, data, p, dp, ddp).ok()) << "sample " << k;
            const Vector2 u = data.u.head<2>(), du = data.du.head<2>(), ddu = data.ddu.head<2>();
            // the hand model's direct kinematics puts the tool where the model's inverse did
            ASSERT_LT((hand.tool(u) - Vector2(p(0), p(1))).norm(), kClosureTolerance) << "sample " << k;
            double scale = 0.0;
            const Vector2 tau = hand.torques(u, du, ddu, scale);
            ASSERT_GT(scale, 0.1) << "the motion must load the actuators";
            const double error = (tau - data.tau.head<2>()).cwiseAbs().maxCoeff() / scale;
            worst = std::max(worst, error);
            EXPECT_LT(error, kLagrangeTolerance) << "sample " << k << ", g_y " << gy << ": Lagrange " << tau.transpose()
                                                 << ", NOC " << data.tau.transpose();
        }
        std::printf("five-bar (g_y = %g) against Lagrange: worst %.3g of the scale\n", gy, worst);
    }
}

TEST(TwoDofModel, PowerBalanceHoldsOnRandomPointRobots) {
    std::mt19937 rng(53);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    int checked = 0, robots = 0;
    double worst = 0.0;
    for (int r = 0; r < 60; ++r) {
        const int limbs = r % 3 == 2 ? 3 : 2;
        const bool prismatic = r % 2 == 1;
        RobotDescription d = randomPointRobot(rng, limbs, prismatic);
        std::unique_ptr<Model> model;
        try {
            model = std::make_unique<Model>(d);
        } catch (const Error&) {
            continue;  // singular at home: another draw
        }
        ++robots;
        Data data(*model), other(*model);
        const Motion2 motion{d.home.tail<2>(), Vector2(0.01 + 0.01 * U(rng), 0.01 + 0.01 * U(rng)),
                             Vector2(8.0 + 4.0 * U(rng), 8.0 + 4.0 * U(rng)), Vector2(U(rng), U(rng))};
        const auto energy = [&](double t) {
            TaskVector p, dp, ddp;
            motion.at(t, p, dp, ddp);
            if (!solve(*model, other, p, dp, ddp)) return std::numeric_limits<double>::quiet_NaN();
            return kineticEnergy(*model, other) + potentialEnergy(*model, other);
        };
        for (int k = 0; k < 8; ++k) {
            const double t = 0.05 * k;
            TaskVector p, dp, ddp;
            motion.at(t, p, dp, ddp);
            if (!solve(*model, data, p, dp, ddp)) continue;
            // near a singularity the energy changes too fast for the time stencil: regular samples only
            bool regular = data.cond_A < kConditionLimit;
            for (int j = 0; j < model->limbs; ++j)
                regular = regular && data.limb[static_cast<std::size_t>(j)].cond < kConditionLimit;
            if (!regular) continue;
            const double power = data.tau.head(model->actuators).dot(data.du.head(model->actuators));
            const double rate = stencil([&](double s) { return energy(t + s); }, 2e-5);
            if (!std::isfinite(rate)) continue;
            double scale = 0.0;
            for (int a = 0; a < model->actuators; ++a) scale = std::max(scale, std::abs(data.tau(a) * data.du(a)));
            scale = std::max(scale, 1e-3);
            worst = std::max(worst, std::abs(power - rate) / scale);
            EXPECT_NEAR(power, rate, kPowerTolerance * scale)
                << d.name << " " << r << " sample " << k << ": tau . du " << power << ", dE/dt " << rate;
            // the lean path (and so the batch's kernel) gives the same forces
            Data lean(*model);
            ASSERT_TRUE(inverseDynamicsFast(*model, lean, lift(*model, p), liftRate(dp), liftRate(ddp)).ok());
            for (int a = 0; a < model->actuators; ++a) {
                EXPECT_NEAR(lean.tau(a), data.tau(a), 1e-10 * (1.0 + data.tau.cwiseAbs().maxCoeff()))
                    << d.name << " " << r << " actuator " << a;
            }
            if (model->actuators == 3) {
                // minimum norm: tau in the range of A_E (the x, y columns of A), i.e. normal to
                // the null space of A_E^T, n = column x cross column y
                const Vector3 cx = data.A.col(1), cy = data.A.col(2);
                const Vector3 n = cx.cross(cy).normalized();
                EXPECT_LT(std::abs(n.dot(data.tau.head<3>())), 1e-10 * (1.0 + data.tau.cwiseAbs().maxCoeff()))
                    << "redundant robot " << r;
            }
            ++checked;
        }
    }
    std::printf("power balance: %d robots, %d samples, worst |tau . du - dE/dt| %.3g of the largest power\n", robots,
                checked, worst);
    EXPECT_GT(robots, 30);
    EXPECT_GT(checked, 150);
}

TEST(TwoDofModel, EveryWorkingModeClosesOnTheToolPoint) {
    const RobotDescription d = shipped("five-bar");
    const Model model(d);
    Data data(model);
    const Pose p = lift(model, task(0.02, 0.3));
    std::vector<Vector2> modes;
    for (const int b0 : {1, -1}) {
        for (const int b1 : {1, -1}) {
            LimbBranches branches{};
            branches[0] = b0, branches[1] = b1;
            ASSERT_TRUE(inverseDisplacement(model, data, p, branches).ok()) << b0 << " " << b1;
            for (std::size_t j = 0; j < 2; ++j) {
                // forward along the limb from its joint variables: the tool point
                const LimbDescription& limb = d.limbs[j];
                const Vector3& q = data.limb[j].q;
                const Vector2 A = limb.joints[0].point;
                const Vector2 B = A + rotate(q(0), limb.joints[1].point - A);
                const Vector2 C = B + rotate(q(0) + q(1), limb.joints[2].point - limb.joints[1].point);
                EXPECT_LT((C - p.tail<2>()).norm(), kClosureTolerance) << "mode " << b0 << b1 << " limb " << j;
            }
            modes.emplace_back(data.u(0), data.u(1));
        }
    }
    // four distinct working modes, the default being the home branches
    for (std::size_t a = 0; a < modes.size(); ++a) {
        for (std::size_t b = a + 1; b < modes.size(); ++b) EXPECT_GT((modes[a] - modes[b]).norm(), 0.1);
    }
    ASSERT_TRUE(inverseDisplacement(model, data, p).ok());
    const Vector2 home_mode(data.u(0), data.u(1));
    int same = 0;
    for (const Vector2& m : modes) same += (m - home_mode).norm() < 1e-15 ? 1 : 0;
    EXPECT_EQ(same, 1);
}

TEST(TwoDofModel, InverseKinematicsRoundTripsThroughHandDirectKinematics) {
    const RobotDescription d = shipped("five-bar");
    const Model model(d);
    const FiveBar hand(d);
    Data data(model);
    double worst = 0.0;
    for (double x = -0.08; x <= 0.08; x += 0.04) {
        for (double y = 0.22; y <= 0.42; y += 0.05) {
            ASSERT_TRUE(inverseDisplacement(model, data, lift(model, task(x, y))).ok()) << x << ", " << y;
            worst = std::max(worst, (hand.tool(Vector2(data.u(0), data.u(1))) - Vector2(x, y)).norm());
        }
    }
    EXPECT_LT(worst, kClosureTolerance);
}

/// Both tool points of a two-limb point robot with its actuators at u, in closed form: each
/// limb's locked first joint puts its elbow (or slider pivot) at B_j = A_j + Rot(u_j) (B_j0 -
/// A_j) (R) or B_j0 + u_j d_j (P); the tool is on the circle of radius |C_0 - B_j0| about B_j,
/// and the two circles meet at B_1 + a e +- h n (e along B_1 B_2, n normal to it).
std::vector<Vector2> circleIntersections(const RobotDescription& d, const ActuatorVector& u) {
    std::array<Vector2, 2> B;
    std::array<double, 2> r{};
    const Vector2 C0 = d.home.tail<2>();
    for (std::size_t j = 0; j < 2; ++j) {
        const JointDescription& base = d.limbs[j].joints[0];
        const Vector2 B0 = d.limbs[j].joints[1].point;
        const double uj = u(static_cast<Eigen::Index>(j));
        if (base.type == JointType::revolute) {
            B[j] = base.point + rotate(uj, B0 - base.point);
        } else {
            B[j] = B0 + uj * base.direction.normalized();
        }
        r[j] = (C0 - B0).norm();
    }
    const Vector2 e = (B[1] - B[0]).normalized();
    const double D = (B[1] - B[0]).norm();
    const double a = (r[0] * r[0] - r[1] * r[1] + D * D) / (2.0 * D);
    const double h2 = r[0] * r[0] - a * a;
    if (h2 < 0.0) return {};
    const Vector2 n(-e.y(), e.x());
    const double h = std::sqrt(h2);
    return {B[0] + a * e + h * n, B[0] + a * e - h * n};
}

// Direct kinematics of random five-bars and biglides (and the shipped ones): from the actuator
// values of a tool point near home, exactly the two closed-form circle intersections, each at
// theta = home, verified by inverse displacement (u back to round-off); the pose that gave u is
// among them, on the home branches (the working mode); and stateFromActuators picks it.
TEST(TwoDofModel, DirectKinematicsGivesBothCircleIntersections) {
    std::mt19937 rng(61);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    int checked = 0, robots = 0;
    double worst = 0.0, worst_u = 0.0;
    for (int r = 0; r < 40; ++r) {
        RobotDescription d =
            r == 0 ? shipped("five-bar") : (r == 1 ? shipped("biglide") : randomPointRobot(rng, 2, r % 2 == 1));
        std::unique_ptr<Model> model;
        try {
            model = std::make_unique<Model>(d);
        } catch (const Error&) {
            continue;
        }
        ++robots;
        Data data(*model);
        for (int k = 0; k < 6; ++k) {
            const TaskVector p = task(d.home(1) + 0.02 * U(rng), d.home(2) + 0.02 * U(rng));
            if (!inverseDisplacement(*model, data, lift(*model, p)).ok()) continue;
            const ActuatorVector u = data.u.head(model->actuators);
            const std::vector<Vector2> closed = circleIntersections(d, u);
            ASSERT_EQ(closed.size(), 2U) << d.name << " " << r;
            AssemblyModes modes;
            ASSERT_TRUE(directKinematics(*model, data, u, modes).ok());
            ASSERT_EQ(modes.count, 2) << d.name << " " << r << " sample " << k;
            EXPECT_FALSE(modes.degenerate);
            const Pose& first = modes.mode[0].p;
            const Pose& second = modes.mode[1].p;
            EXPECT_TRUE(first(1) < second(1) || (first(1) == second(1) && first(2) < second(2)))
                << "listed by x, then y";
            std::array<bool, 2> found{};
            for (const AssemblyMode& mode : modes) {
                EXPECT_EQ(mode.p(0), d.home(0));
                worst_u = std::max(worst_u, mode.u_error);
                EXPECT_LT(mode.u_error, 1e-12);
                for (std::size_t c = 0; c < 2; ++c) {
                    const double distance = (mode.p.tail<2>() - closed[c]).norm();
                    if (distance < kClosureTolerance) {
                        found[c] = true;
                        worst = std::max(worst, distance);
                    }
                }
                if ((mode.p.tail<2>() - Vector2(p(0), p(1))).norm() < kClosureTolerance) {
                    EXPECT_TRUE(mode.working) << d.name << " " << r << ": the pose that gave u is on the home branches";
                }
            }
            EXPECT_TRUE(found[0] && found[1]) << d.name << " " << r << " sample " << k << ": closed form "
                                              << closed[0].transpose() << " and " << closed[1].transpose() << "; modes "
                                              << modes.mode[0].p.transpose() << " and " << modes.mode[1].p.transpose();
            const bool has_start = std::any_of(modes.begin(), modes.end(), [&](const AssemblyMode& mode) {
                return (mode.p.tail<2>() - Vector2(p(0), p(1))).norm() < kClosureTolerance;
            });
            EXPECT_TRUE(has_start) << d.name << " " << r;
            ActuatorStart start;
            ASSERT_TRUE(stateFromActuators(*model, data, u, ActuatorVector(), 0, start).ok());
            EXPECT_LT((start.p.tail<2>() - Vector2(p(0), p(1))).norm(), kClosureTolerance) << d.name << " " << r;
            ++checked;
        }
    }
    std::printf("direct kinematics: %d robots, %d samples, worst |C - closed form| %.3g m, worst u error %.3g\n",
                robots, checked, worst, worst_u);
    EXPECT_GT(robots, 20);
    EXPECT_GT(checked, 100);
}

TEST(TwoDofModel, JacobiansMatchFiniteDifferencesOfInverseKinematics) {
    for (const char* name : {"five-bar", "biglide"}) {
        const Model model(shipped(name));
        Data data(model), moved(model);
        const TaskVector p = task(0.03, model.home(2) - 0.04);
        for (int k = 0; k < 2; ++k) {
            TaskVector e = TaskVector::Zero(2);
            e(k) = 1.0;
            const Pose pose = lift(model, p);
            ASSERT_TRUE(inverseDisplacement(model, data, pose).ok());
            ASSERT_TRUE(velocityFromPlatformTwist(model, data, liftRate(e)).ok());
            const auto joints = [&](double s) {
                const TaskVector ps = p + s * e;
                EXPECT_TRUE(inverseDisplacement(model, moved, lift(model, ps)).ok());
                Eigen::Matrix<double, 8, 1> out;
                out << moved.u(0), moved.u(1), moved.limb[0].q, moved.limb[1].q;
                return out;
            };
            const Eigen::Matrix<double, 8, 1> fd = stencil(joints, 1e-5);
            Eigen::Matrix<double, 8, 1> model_rates;
            model_rates << data.du(0), data.du(1), data.limb[0].gamma_dot, data.limb[1].gamma_dot;
            EXPECT_LT((fd - model_rates).cwiseAbs().maxCoeff(),
                      kJacobianTolerance * (1.0 + model_rates.cwiseAbs().maxCoeff()))
                << name << " direction " << k << ": finite differences " << fd.transpose() << ", model "
                << model_rates.transpose();
        }
    }
}

TEST(TwoDofModel, BothSingularityTypesAreNamed) {
    const RobotDescription d = shipped("five-bar");
    const Model model(d);
    Data data(model);
    // forearms aligned: with the symmetric five-bar, the tool on the line of the elbows,
    // forearms horizontal: B_1 = (-l_2, y), |B_1 - A_1| = l_1
    const double l1 = (d.limbs[0].joints[1].point - d.limbs[0].joints[0].point).norm();
    const double l2 = (d.limbs[0].joints[2].point - d.limbs[0].joints[1].point).norm();
    const double ax = d.limbs[0].joints[0].point.x();
    const double y_aligned = std::sqrt(l1 * l1 - (l2 + ax) * (l2 + ax));
    Status status = inverseDynamics(model, data, lift(model, task(0.0, y_aligned)), Twist::Zero(), Twist::Zero());
    EXPECT_EQ(status.code, StatusCode::singular_actuation);
    EXPECT_NE(describe(status, model).find("actuation singularity"), std::string::npos);
    // a limb stretched: the tool at l_1 + l_2 from the left motor, just inside
    const Vector2 A1 = d.limbs[0].joints[0].point;
    const Vector2 dir(std::cos(1.1), std::sin(1.1));
    const Vector2 stretched = A1 + (l1 + l2) * (1.0 - 1e-10) * dir;
    status =
        inverseDynamics(model, data, lift(model, task(stretched.x(), stretched.y())), Twist::Zero(), Twist::Zero());
    EXPECT_EQ(status.code, StatusCode::singular_limb);
    EXPECT_EQ(status.limb, 0);
    // and beyond its reach
    const Vector2 beyond = A1 + (l1 + l2) * (1.0 + 1e-6) * dir;
    status = inverseDynamics(model, data, lift(model, task(beyond.x(), beyond.y())), Twist::Zero(), Twist::Zero());
    EXPECT_EQ(status.code, StatusCode::unreachable);
    EXPECT_EQ(status.limb, 0);
}

TEST(TwoDofModel, BiglideHoldsItsWeightAsVirtualWorkSays) {
    // at rest at the symmetric home: moving both sliders in by delta raises the tool by
    // (s / y) delta and each link's c.o.m. by half that; tau_1 = -tau_2 = g (m_t + m_l) s / (2 y)
    const Model model(shipped("biglide"));
    Data data(model);
    ASSERT_TRUE(inverseDynamics(model, data, model.home, Twist::Zero(), Twist::Zero()).ok());
    const double s = 0.15, y = 0.2, m_tool = 0.5, m_link = 0.2, g = 9.81;
    const double expected = g * (m_tool + m_link) * s / (2.0 * y);
    EXPECT_NEAR(data.tau(0), expected, 1e-12 * expected);
    EXPECT_NEAR(data.tau(1), -expected, 1e-12 * expected);
}

// ---------------------------------------------------------------------------------------------

std::string refusal(const std::string& text) {
    try {
        (void)io::parseRobotDescription(text, "bad.yaml");
    } catch (const Error& e) {
        return e.what();
    }
    return "accepted";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

TEST(TwoDofFiles, BadTranslatingRobotsAreRefusedWithTheirReason) {
    const std::string good = readText(std::string(NOCDYN_SOURCE_DIR) + "/robots/five-bar.yaml");
    ASSERT_EQ(refusal(good), "accepted");
    // the right forearm's last joint elsewhere: the limbs do not meet at one point
    std::string e = refusal(replaced(good,
                                     "- {type: R, point: [0.0, 0.35]}   # tool point\n    bodies:\n      - {mass: "
                                     "0.25, inertia: 2.0e-3, com: [0.15",
                                     "- {type: R, point: [0.01, 0.35]}   # tool point\n    bodies:\n      - {mass: "
                                     "0.25, inertia: 2.0e-3, com: [0.15"));
    EXPECT_NE(e.find("bad.yaml:"), std::string::npos) << e;
    EXPECT_NE(e.find("limbs[1] (right).joints[2]"), std::string::npos) << e;
    EXPECT_NE(e.find("meet at one point"), std::string::npos) << e;
    // a last joint P
    e = refusal(replaced(good, "{type: R, point: [0.0, 0.35]}", "{type: P, direction: [0.0, 1.0]}"));
    EXPECT_NE(e.find("limbs[0] (left).joints[2]"), std::string::npos) << e;
    EXPECT_NE(e.find("ends in an R joint"), std::string::npos) << e;
    // a last joint actuated
    e = refusal(replaced(good, "{type: R, point: [0.0, 0.35]}", "{type: R, point: [0.0, 0.35], actuated: true}"));
    EXPECT_NE(e.find("cannot be actuated"), std::string::npos) << e;
    // a platform with an inertia, a home with an angle
    e = refusal(replaced(good, "platform: {mass: 0.3}", "platform: {mass: 0.3, inertia: 1.0e-3}"));
    EXPECT_NE(e.find("platform.inertia"), std::string::npos) << e;
    e = refusal(replaced(good, "home: [0.0, 0.35]", "home: [0.0, 0.35, 0.1]"));
    EXPECT_NE(e.find("expected [x, y]"), std::string::npos) << e;
    e = refusal(replaced(good, "motion: translation", "motion: rotation"));
    EXPECT_NE(e.find("expected full or translation"), std::string::npos) << e;
    // a home the limbs do not meet at
    e = refusal(replaced(good, "home: [0.0, 0.35]", "home: [0.0, 0.3]"));
    EXPECT_NE(e.find("meet at one point"), std::string::npos) << e;
}

TEST(TwoDofFiles, WriterRoundTripsTranslatingRobots) {
    for (const char* name : {"five-bar", "biglide"}) {
        const RobotDescription d = shipped(name);
        const std::string text = io::descriptionToYaml(d);
        EXPECT_NE(text.find("motion: translation"), std::string::npos) << text;
        const RobotDescription back = io::parseRobotDescription(text, "written.yaml");
        EXPECT_EQ(io::descriptionToYaml(back), text);
        const Model a(d), b(back);
        Data da(a), db(b);
        const Motion2 motion{d.home.tail<2>(), Vector2(0.02, 0.02), Vector2(7.0, 9.0), Vector2(0.1, 0.2)};
        TaskVector p, dp, ddp;
        motion.at(0.1, p, dp, ddp);
        ASSERT_TRUE(solve(a, da, p, dp, ddp).ok());
        ASSERT_TRUE(solve(b, db, p, dp, ddp).ok());
        EXPECT_EQ(da.tau(0), db.tau(0)) << name;
        EXPECT_EQ(da.tau(1), db.tau(1)) << name;
    }
}

}  // namespace
}  // namespace nocdyn::test
