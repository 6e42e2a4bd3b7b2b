// NOC properties (eqs. 15-23) on the example robots and on random robots of every limb type:
// K T = 0 for a constraint matrix built from the joints alone, I symmetric positive-definite
// and equal to the bodies' kinetic energy from finite differences of their positions, dT and
// dI/dt against finite differences, the power balance tau . du = d(E + V)/dt + friction power
// along trajectories, and the platform acceleration from the actuator accelerations.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "nocdyn/trajectory.hpp"
#include "random_robots.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

constexpr int kPoses = 300;           // per robot
constexpr int kRandomPerType = 3;     // random robots per limb type
constexpr double kKT = 1e-13;         // K T relative to max |T| (and max |K| when above 1)
constexpr double kSymmetry = 1e-14;   // I - I^T relative to |I|
constexpr double kEnergy = 1e-7;      // kinetic energy from finite differences, relative
constexpr double kDerivative = 1e-6;  // dT, dI/dt, ddu against central differences, relative
constexpr double kPower = 1e-7;       // power balance relative to the peak power
constexpr double kInverse = 1e-10;    // acceleration round trip, relative

/// The example robots and random robots of every limb type.
const std::vector<RobotCase>& cases() {
    static const std::vector<RobotCase> all = exampleAndRandomRobots(kRandomPerType, 17);
    return all;
}

/// Every body's T_i stacked, bodies in the model's order.
Eigen::MatrixXd stacked(const Model& model, const std::array<ShapingMatrix3, kMaxBodies>& T) {
    Eigen::MatrixXd out(3 * model.bodies, 3);
    for (int i = 0; i < model.bodies; ++i) out.block<3, 3>(3 * i, 0) = T[static_cast<std::size_t>(i)];
    return out;
}

/// c.o.m. of body i [m].
Vector2 com(const Model& model, const Data& data, int i) {
    if (i == model.platformBody()) return data.x_P;
    return data.limb[static_cast<std::size_t>(i % model.limbs)].x[static_cast<std::size_t>(i / model.limbs)];
}

/// eq. 15 built from the joints alone (no Jacobian): per joint two rows between its inboard and
/// outboard bodies (the base for the first joint has no twist). Revolute at r: both bodies'
/// velocity fields agree at r. Prismatic along d: the bodies turn together, and their
/// velocities agree across d. Twists are [omega; v_com] per body (eq. 10).
Eigen::MatrixXd constraintMatrix(const Model& model, const Data& data) {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6 * model.limbs, 3 * model.bodies);
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& limb = data.limb[static_cast<std::size_t>(j)];
        for (int k = 0; k < 3; ++k) {
            const int row = 6 * j + 2 * k;
            const int in = k == 0 ? -1 : model.body(j, k - 1);
            const int out = k == 2 ? model.platformBody() : model.body(j, k);
            const Twist& s = limb.s[static_cast<std::size_t>(k)];
            const int col_in = 3 * in, col_out = 3 * out;
            const Vector2 x_out = com(model, data, out);
            if (model.limb[static_cast<std::size_t>(j)].type[static_cast<std::size_t>(k)] == JointType::revolute) {
                const Vector2 r(-s(2), s(1));  // s = [1; r_y; -r_x]
                // v_out + omega_out E (r - x_out) - (the same of the inboard body) = 0
                K.block<2, 1>(row, col_out) = perp(r - x_out);
                K.block<2, 2>(row, col_out + 1) = Eigen::Matrix2d::Identity();
                if (in >= 0) {
                    K.block<2, 1>(row, col_in) = -perp(r - com(model, data, in));
                    K.block<2, 2>(row, col_in + 1) = -Eigen::Matrix2d::Identity();
                }
            } else {
                const Vector2 n = perp(Vector2(s.tail<2>()));  // normal of the current direction
                K(row, col_out) = 1.0;                         // omega_out - omega_in = 0
                // n . (v_out(x_out) - v_in(x_out)) = 0
                K.block<1, 2>(row + 1, col_out + 1) = n.transpose();
                if (in >= 0) {
                    K(row, col_in) = -1.0;
                    K(row + 1, col_in) = -n.dot(perp(x_out - com(model, data, in)));
                    K.block<1, 2>(row + 1, col_in + 1) = -n.transpose();
                }
            }
        }
    }
    return K;
}

/// The independent-coordinate velocity v of the sample: du (three actuators) or dp/dt.
Vector3 independentRates(const Model& model, const Data& data) {
    return model.coordinates == Coordinates::actuators ? Vector3(data.du) : Vector3(data.t_M);
}

TEST(NaturalOrthogonalComplement, KTimesTIsZeroAndTSpansItsNullSpace) {
    const int checked = forEachPose(cases(), kPoses, [](const RobotCase& c, const Pose& p, WorkspaceSampler&) {
        const Model& model = *c.model;
        Data data(model);
        solve(model, data, p, Twist::Zero(), Twist::Zero());
        const Eigen::MatrixXd K = constraintMatrix(model, data);
        const Eigen::MatrixXd T = stacked(model, data.T);
        const double scale = T.cwiseAbs().maxCoeff() * std::max(1.0, K.cwiseAbs().maxCoeff());
        EXPECT_LT((K * T).cwiseAbs().maxCoeff(), kKT * scale) << c.name << ", " << describePose(p);
        // T spans the whole null space: K has full row rank 6 n and T rank 3.
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd_K(K);
        EXPECT_GT(svd_K.singularValues()(6 * model.limbs - 1), 1e-6) << c.name << ", " << describePose(p);
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd_T(T);
        EXPECT_GT(svd_T.singularValues()(2), 1e-3) << c.name << ", " << describePose(p);
        return true;
    });
    EXPECT_GE(checked, kPoses * (5 + 7 * kRandomPerType));
}

/// When each actuator is the first joint of its own limb, that limb's first body moves with that
/// actuator alone (t = s_1 du_a), so I >= min_a of the first body's inertia about the joint in
/// every direction (the slider mass of the paper's robot); otherwise nothing.
std::optional<double> firstBodiesBound(const Model& model) {
    if (model.coordinates != Coordinates::actuators) return std::nullopt;
    double bound = std::numeric_limits<double>::infinity();
    for (int a = 0; a < model.actuators; ++a) {
        if (model.actuator_joint[static_cast<std::size_t>(a)] != 0) return std::nullopt;
        const LimbModel& limb = model.limb[static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)])];
        const InertiaDyad& M = limb.M[0];
        bound = std::min(bound, limb.type[0] == JointType::prismatic
                                    ? M.mass
                                    : M.inertia + M.mass * (limb.com_home[0] - limb.point_home[0]).squaredNorm());
    }
    return bound;
}

TEST(NaturalOrthogonalComplement, InertiaIsSymmetricPositiveDefiniteAndBoundedByTheFirstBodies) {
    const int checked = forEachPose(cases(), kPoses, [](const RobotCase& c, const Pose& p, WorkspaceSampler&) {
        const Model& model = *c.model;
        Data data(model);
        solve(model, data, p, Twist::Zero(), Twist::Zero());
        EXPECT_LT((data.I - data.I.transpose()).cwiseAbs().maxCoeff(), kSymmetry * data.I.norm())
            << c.name << ", " << describePose(p);
        const Eigen::SelfAdjointEigenSolver<Matrix3> eigen(data.I);
        EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0) << c.name << ", " << describePose(p);
        if (const std::optional<double> bound = firstBodiesBound(model)) {
            EXPECT_GT(eigen.eigenvalues().minCoeff(), *bound * (1 - 1e-12)) << c.name << ", " << describePose(p);
        }
        return true;
    });
    EXPECT_GE(checked, kPoses * (5 + 7 * kRandomPerType));
    const auto bounded = std::count_if(cases().begin(), cases().end(),
                                       [](const RobotCase& c) { return firstBodiesBound(*c.model).has_value(); });
    EXPECT_GE(bounded, 2) << "the paper's robot in both forms at least";
}

/// Orientation of body b (0, 1) of limb j relative to home: the sum of its chain's R angles.
double bodyAngle(const Model& model, const Data& data, int j, int b) {
    double angle = 0.0;
    for (int k = 0; k <= b; ++k) {
        if (model.limb[static_cast<std::size_t>(j)].type[static_cast<std::size_t>(k)] == JointType::revolute) {
            angle += data.limb[static_cast<std::size_t>(j)].q(k);
        }
    }
    return angle;
}

TEST(NaturalOrthogonalComplement, InertiaEqualsKineticEnergyOfBodiesFromFiniteDifferences) {
    // Body velocities from central differences of positions along the motion (no T used).
    static constexpr double h = 1e-7;
    const int checked =
        forEachPose(cases(), kPoses / 3, [](const RobotCase& c, const Pose& p, WorkspaceSampler& sampler) {
            const Model& model = *c.model;
            Data data(model), plus(model), minus(model);
            const Twist t = sampler.twist();
            solve(model, data, p, t, Twist::Zero());
            EXPECT_TRUE(inverseDisplacement(model, plus, p + h * t).ok()) << c.name << ", " << describePose(p);
            EXPECT_TRUE(inverseDisplacement(model, minus, p - h * t).ok()) << c.name << ", " << describePose(p);
            const Vector2 v_platform = (plus.x_P - minus.x_P) / (2 * h);
            double energy =
                0.5 * model.platform_M.mass * v_platform.squaredNorm() + 0.5 * model.platform_M.inertia * t(0) * t(0);
            for (int j = 0; j < model.limbs; ++j) {
                for (int b = 0; b < 2; ++b) {
                    const int i = model.body(j, b);
                    const Vector2 v = (com(model, plus, i) - com(model, minus, i)) / (2 * h);
                    const double w = (bodyAngle(model, plus, j, b) - bodyAngle(model, minus, j, b)) / (2 * h);
                    energy += 0.5 * model.inertia(i).mass * v.squaredNorm() + 0.5 * model.inertia(i).inertia * w * w;
                }
            }
            const Vector3 v = independentRates(model, data);
            EXPECT_NEAR(noc::kineticEnergy<3>(data.I, v), energy, kEnergy * energy)
                << c.name << ", " << describePose(p);
            EXPECT_NEAR(kineticEnergy(model, data), energy, kEnergy * energy) << c.name << ", " << describePose(p);
            return true;
        });
    EXPECT_GE(checked, kPoses / 3 * (5 + 7 * kRandomPerType));
}

TEST(NaturalOrthogonalComplement, TwistShapingDerivativeMatchesFiniteDifferences) {
    // fourth-order differences: T_i varies fast near the redundant 4-RRR's singularities
    static constexpr double h = 1e-6;
    const int checked = forEachPose(cases(), kPoses, [](const RobotCase& c, const Pose& p, WorkspaceSampler& sampler) {
        const Model& model = *c.model;
        Data data(model), moved(model);
        const Twist t = sampler.twist();
        solve(model, data, p, t, Twist::Zero());
        const Eigen::MatrixXd fd = centralDifference(
            [&](double s) {
                solve(model, moved, p + s * t, t, Twist::Zero());
                return stacked(model, moved.T);
            },
            h);
        const Eigen::MatrixXd exact = stacked(model, data.T_dot);
        EXPECT_LT((exact - fd).cwiseAbs().maxCoeff(), kDerivative * (1 + fd.cwiseAbs().maxCoeff()))
            << c.name << ", " << describePose(p);
        // dI/dt = C + C^T (eq. 23 with constant M_i)
        const Matrix3 I_dot = centralDifference(
            [&](double s) {
                solve(model, moved, p + s * t, t, Twist::Zero());
                return Matrix3(moved.I);
            },
            h);
        EXPECT_LT((I_dot - data.C - data.C.transpose()).cwiseAbs().maxCoeff(),
                  kDerivative * (1 + I_dot.cwiseAbs().maxCoeff()))
            << c.name << ", " << describePose(p);
        return true;
    });
    EXPECT_GE(checked, kPoses * (5 + 7 * kRandomPerType));
}

/// tau . du = d(E + V)/dt + friction power, with d(E + V)/dt by central differences over
/// h = 1e-6 s; ddu against differences of du, too. Returns the samples checked.
int expectPowerBalance(const Model& model, const PoseTrajectory& trajectory, const std::string& name) {
    Data data(model), plus(model), minus(model);
    static constexpr double h = 1e-6;
    double peak_power = 0.0, worst = 0.0;
    int checked = 0;
    for (int k = 0; k < 200; ++k) {
        const double t = 0.001 * k;
        Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        solve(model, data, p, dp, ddp);
        trajectory.evaluate(t + h, p, dp, ddp);
        solve(model, plus, p, dp, ddp);
        trajectory.evaluate(t - h, p, dp, ddp);
        solve(model, minus, p, dp, ddp);
        if (::testing::Test::HasFatalFailure()) return checked;
        const double power = data.tau.dot(data.du);
        const double energy_rate = (kineticEnergy(model, plus) + potentialEnergy(model, plus) -
                                    kineticEnergy(model, minus) - potentialEnergy(model, minus)) /
                                   (2 * h);
        const Eigen::VectorXd ddu_fd = (plus.du - minus.du) / (2 * h);
        EXPECT_LT((data.ddu - ddu_fd).norm(), kDerivative * (1 + ddu_fd.norm())) << name << " t = " << t;
        peak_power = std::max(peak_power, std::abs(power));
        worst = std::max(worst, std::abs(power - energy_rate - frictionPower(model, data)));
        ++checked;
    }
    EXPECT_LT(worst, kPower * peak_power) << name << ": peak power " << peak_power << " W";
    return checked;
}

TEST(NaturalOrthogonalComplement, PowerBalanceHoldsAlongPaperTrajectoriesOnEveryExampleRobot) {
    int checked = 0;
    for (const std::string& name : io::exampleRobotNames()) {
        const Model model(io::exampleRobot(name));
        checked += expectPowerBalance(model, paperTrajectory1(), name + ", paper1");
        checked += expectPowerBalance(model, paperTrajectory2(), name + ", paper2");
    }
    EXPECT_EQ(checked, 2 * 200 * static_cast<int>(io::exampleRobotNames().size()));
}

TEST(NaturalOrthogonalComplement, PowerBalanceHoldsAlongRandomTrajectoriesOfRandomRobotsWithGravityAndFriction) {
    // every limb type, three limbs and three actuators, then four limbs and four (redundant)
    int checked = 0, robots = 0;
    for (const std::string& type : limbTypes()) {
        for (const RandomRobotSpec& spec : {RandomRobotSpec{{type, type, type}, 3, true, true},
                                            RandomRobotSpec{{type, type, type, type}, 4, true, true}}) {
            std::mt19937 rng(7);
            int kept = 0;
            for (int tried = 0; kept < 2 && tried < 100; ++tried) {
                const auto robot = randomRobot(spec, rng);
                if (!robot) continue;
                const Model model(*robot);
                const PoseTrajectory trajectory = trajectoryAround(robot->home, rng, 0.5);
                // keep robots that stay regular along the whole trajectory
                Data data(model);
                bool regular = true;
                for (int k = 0; k < 200 && regular; ++k) {
                    Pose p, dp, ddp;
                    trajectory.evaluate(0.001 * k, p, dp, ddp);
                    regular = inverseDynamics(model, data, p, dp, ddp).ok() && data.cond_A < 1e3;
                }
                if (!regular) continue;
                ++kept;
                checked += expectPowerBalance(
                    model, trajectory,
                    "random " + type + " x" + std::to_string(spec.limb_types.size()) + " #" + std::to_string(kept));
            }
            robots += kept;
            EXPECT_EQ(kept, 2) << type << " x" << spec.limb_types.size();
        }
    }
    EXPECT_EQ(checked, 200 * robots);
    EXPECT_EQ(robots, 2 * 2 * static_cast<int>(limbTypes().size()));
}

TEST(Accelerations, PlatformAccelerationFromActuatorAccelerationsInvertsTheirComputation) {
    const int checked = forEachPose(cases(), kPoses, [](const RobotCase& c, const Pose& p, WorkspaceSampler& sampler) {
        const Model& model = *c.model;
        if (model.actuators != 3) return false;  // the platform acceleration needs exactly three
        Data data(model);
        const Twist t = sampler.twist();
        const Twist a = 100.0 * sampler.twist();
        solve(model, data, p, t, a);
        const ActuatorVector ddu = data.ddu;
        accelerationFromActuators(model, data, ddu);
        EXPECT_LT((data.t_M_dot - a).norm(), kInverse * (1 + a.norm())) << c.name << ", " << describePose(p);
        return true;
    });
    EXPECT_GE(checked, kPoses * (4 + 7 * kRandomPerType));
}

}  // namespace
}  // namespace nocdyn::test
