// NOC properties (eqs. 15-23): K T = 0 for an independently built constraint matrix,
// I symmetric positive-definite and equal to the bodies' kinetic energy, dT and dI/dt
// against finite differences, and the power balance tau . du = dE/dt along trajectories.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "nocdyn/trajectory.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

constexpr int kPoses = 1000;
using Matrix21x3 = Eigen::Matrix<double, 21, 3>;
using Matrix18x21 = Eigen::Matrix<double, 18, 21>;

Matrix21x3 stacked(const prr3::Data& data) {
    Matrix21x3 T;
    for (int i = 0; i < prr3::kBodies; ++i) T.block<3, 3>(3 * i, 0) = data.T[i];
    return T;
}

/// eq. 15, built from the joints alone (no Jacobian of the paper): per limb, the slider
/// neither turns nor leaves its rail, and the link's velocity field agrees with the slider
/// at A_j and with the platform at M_j. Twists are [omega; v_com] per body (eq. 10).
Matrix18x21 constraintMatrix(const prr3::Model& model, const prr3::Data& data) {
    Matrix18x21 K = Matrix18x21::Zero();
    const Vector2 C = data.p.tail<2>();
    const Eigen::Matrix2d identity = Eigen::Matrix2d::Identity();
    for (int j = 0; j < 3; ++j) {
        const int s = 3 * prr3::sliderBody(j), k = 3 * prr3::linkBody(j), p = 3 * prr3::kPlatformBody;
        const Vector2 G = data.A[j] + (model.l_c / model.l) * (data.Mj[j] - data.A[j]);
        const int row = 6 * j;
        K(row, s) = 1.0;                                         // slider does not turn
        K.block<1, 2>(row + 1, s + 1) = model.n[j].transpose();  // nor leave L_j
        // pin at A_j: v_G + omega_link E (A - G) - v_slider = 0
        K.block<2, 2>(row + 2, k + 1) = identity;
        K.block<2, 1>(row + 2, k) = perp(data.A[j] - G);
        K.block<2, 2>(row + 2, s + 1) = -identity;
        // pin at M_j: v_G + omega_link E (M - G) - v_C - omega_MP E (M - C) = 0
        K.block<2, 2>(row + 4, k + 1) = identity;
        K.block<2, 1>(row + 4, k) = perp(data.Mj[j] - G);
        K.block<2, 2>(row + 4, p + 1) = -identity;
        K.block<2, 1>(row + 4, p) = -perp(data.Mj[j] - C);
    }
    return K;
}

TEST(NaturalOrthogonalComplement, KTimesTIsZero) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data;
    for (int k = 0; k < kPoses; ++k) {
        const Pose p = sampler.next();
        solve(model, data, p, Twist::Zero(), Twist::Zero());
        const Matrix18x21 K = constraintMatrix(model, data);
        const Matrix21x3 T = stacked(data);
        EXPECT_LT((K * T).cwiseAbs().maxCoeff(), 1e-13 * T.cwiseAbs().maxCoeff()) << describePose(p);
        // T spans the whole null space: K has rank 18 and T rank 3.
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd_K(K);
        EXPECT_GT(svd_K.singularValues()(17), 1e-6) << describePose(p);
        const Eigen::JacobiSVD<Eigen::MatrixXd> svd_T(T);
        EXPECT_GT(svd_T.singularValues()(2), 1e-3) << describePose(p);
    }
}

TEST(NaturalOrthogonalComplement, InertiaIsSymmetricPositiveDefinite) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data;
    for (int k = 0; k < kPoses; ++k) {
        const Pose p = sampler.next();
        solve(model, data, p, Twist::Zero(), Twist::Zero());
        EXPECT_LT((data.I - data.I.transpose()).cwiseAbs().maxCoeff(), 1e-14 * data.I.norm()) << describePose(p);
        const Eigen::SelfAdjointEigenSolver<Matrix3> eigen(data.I);
        // Every actuator drives at least its own slider: I >= slider mass in every direction.
        EXPECT_GT(eigen.eigenvalues().minCoeff(), model.parameters.slider_mass * (1 - 1e-12)) << describePose(p);
    }
}

TEST(NaturalOrthogonalComplement, InertiaEqualsKineticEnergyOfBodiesFromFiniteDifferences) {
    // Body velocities from central differences of positions along the motion (no T used).
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data, plus, minus;
    constexpr double h = 1e-7;
    for (int k = 0; k < 200; ++k) {
        const Pose p = sampler.next();
        const Twist t = sampler.twist();
        solve(model, data, p, t, Twist::Zero());
        ASSERT_TRUE(prr3::inverseDisplacement(model, plus, p + h * t).ok());
        ASSERT_TRUE(prr3::inverseDisplacement(model, minus, p - h * t).ok());
        double energy = 0.5 * model.parameters.platform_mass * t.tail<2>().squaredNorm() +
                        0.5 * model.parameters.platform_inertia * t(0) * t(0);
        for (int j = 0; j < 3; ++j) {
            auto com = [&](const prr3::Data& d) { return Vector2(d.A[j] + (model.l_c / model.l) * d.m[j]); };
            const Vector2 v_slider = (plus.A[j] - minus.A[j]) / (2 * h);
            const Vector2 v_link = (com(plus) - com(minus)) / (2 * h);
            const double w_link = (plus.phi_A(j) - minus.phi_A(j)) / (2 * h);  // link angle phi_Aj + phi_j
            energy += 0.5 * model.parameters.slider_mass * v_slider.squaredNorm() +
                      0.5 * model.parameters.link_mass * v_link.squaredNorm() +
                      0.5 * model.parameters.link_inertia * w_link * w_link;
        }
        EXPECT_NEAR(noc::kineticEnergy(data.I, data.du), energy, 1e-7 * energy) << describePose(p);
        EXPECT_NEAR(prr3::kineticEnergy(model, data), energy, 1e-7 * energy) << describePose(p);
    }
}

TEST(NaturalOrthogonalComplement, TwistShapingDerivativeMatchesFiniteDifferences) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data, plus, minus;
    constexpr double h = 1e-6;
    for (int k = 0; k < kPoses; ++k) {
        const Pose p = sampler.next();
        const Twist t = sampler.twist();
        solve(model, data, p, t, Twist::Zero());
        solve(model, plus, p + h * t, t, Twist::Zero());
        solve(model, minus, p - h * t, t, Twist::Zero());
        const Matrix21x3 fd = (stacked(plus) - stacked(minus)) / (2 * h);
        Matrix21x3 exact;
        for (int i = 0; i < prr3::kBodies; ++i) exact.block<3, 3>(3 * i, 0) = data.T_dot[i];
        EXPECT_LT((exact - fd).cwiseAbs().maxCoeff(), 1e-6 * (1 + fd.cwiseAbs().maxCoeff())) << describePose(p);
        // dI/dt = C + C^T (eq. 23 with constant M_i)
        const Matrix3 I_dot = (plus.I - minus.I) / (2 * h);
        EXPECT_LT((I_dot - data.C - data.C.transpose()).cwiseAbs().maxCoeff(), 1e-6 * (1 + I_dot.cwiseAbs().maxCoeff()))
            << describePose(p);
    }
}

/// A random multi-harmonic trajectory that stays well inside the workspace.
PoseTrajectory randomTrajectory(std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0), frequency(1.0, 40.0), phase(-3.0, 3.0);
    auto axis = [&](double scale) {
        AxisMotion motion{0.3 * scale * unit(rng), {}};
        for (int k = 0; k < 3; ++k) motion.harmonics.push_back({0.2 * scale * unit(rng), frequency(rng), phase(rng)});
        return motion;
    };
    PoseTrajectory trajectory;
    trajectory.theta = axis(0.2);
    trajectory.x = axis(0.02);
    trajectory.y = axis(0.02);
    return trajectory;
}

void expectPowerBalance(const prr3::Model& model, const PoseTrajectory& trajectory, const char* name) {
    // tau . du = d/dt (du^T I du / 2), dE/dt by central differences over h = 1e-6 s.
    prr3::Data data, plus, minus;
    constexpr double h = 1e-6;
    double peak_power = 0.0, worst = 0.0;
    for (int k = 0; k < 200; ++k) {
        const double t = 0.001 * k;
        Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        solve(model, data, p, dp, ddp);
        trajectory.evaluate(t + h, p, dp, ddp);
        solve(model, plus, p, dp, ddp);
        trajectory.evaluate(t - h, p, dp, ddp);
        solve(model, minus, p, dp, ddp);
        const double power = data.tau.dot(data.du);
        const double energy_rate =
            (noc::kineticEnergy(plus.I, plus.du) - noc::kineticEnergy(minus.I, minus.du)) / (2 * h);
        // ddu against differences of du, too
        const Vector3 ddu_fd = (plus.du - minus.du) / (2 * h);
        EXPECT_LT((data.ddu - ddu_fd).norm(), 1e-6 * (1 + ddu_fd.norm())) << name << " t = " << t;
        peak_power = std::max(peak_power, std::abs(power));
        worst = std::max(worst, std::abs(power - energy_rate));
    }
    EXPECT_LT(worst, 1e-7 * peak_power) << name << ": peak power " << peak_power << " W";
}

TEST(NaturalOrthogonalComplement, PowerBalanceHoldsAlongPaperTrajectories) {
    const prr3::Model model;
    expectPowerBalance(model, paperTrajectory1(), "paper1");
    expectPowerBalance(model, paperTrajectory2(), "paper2");
}

TEST(NaturalOrthogonalComplement, PowerBalanceHoldsAlongRandomTrajectoriesOfRandomRobots) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> scale(0.5, 2.0);
    for (int k = 0; k < 20; ++k) {
        RobotParameters robot;
        robot.link_com = robot.link_length * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        robot.slider_mass *= scale(rng);
        robot.link_mass *= scale(rng);
        robot.link_inertia *= scale(rng);
        robot.platform_mass *= scale(rng);
        robot.platform_inertia *= scale(rng);
        const prr3::Model model(robot);
        expectPowerBalance(model, randomTrajectory(rng), ("random robot " + std::to_string(k)).c_str());
    }
}

TEST(Accelerations, PlatformAccelerationInvertsActuatorAccelerations) {
    const prr3::Model model;
    WorkspaceSampler sampler(model);
    prr3::Data data;
    for (int k = 0; k < kPoses; ++k) {
        const Pose p = sampler.next();
        const Twist t = sampler.twist();
        const Twist a = 100.0 * sampler.twist();
        solve(model, data, p, t, a);
        const prr3::JointVector ddu = data.ddu;
        prr3::platformAcceleration(data, ddu);
        EXPECT_LT((data.t_M_dot - a).norm(), 1e-10 * (1 + a.norm())) << describePose(p);
    }
}

}  // namespace
}  // namespace nocdyn::test
