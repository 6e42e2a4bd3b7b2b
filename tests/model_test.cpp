// The general model on the paper's robot (against the hand-derived 3-PRR model) and on random
// robots of every limb type and actuation choice: inverse displacement against the product
// of exponentials, rates and T_i against finite differences, I SPD, dI/dt = C + C^T, the
// power balance with gravity and friction, the lean path against the full path, and the
// minimum-norm forces of redundantly actuated robots.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "nocdyn/batch.hpp"
#include "nocdyn/dynamics.hpp"
#include "limb_ik_impl.hpp"
#include "nocdyn/detail/fast_math.hpp"
#include "nocdyn/limb_ik.hpp"
#include "random_robots.hpp"
#include "support.hpp"

// Packets are inlined locals here: the note that a 32-byte vector's ABI depends on AVX does
// not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace nocdyn::test {
namespace {

constexpr double kFiniteDifferenceStep = 1e-6;       // [s]
constexpr double kFiniteDifferenceTolerance = 1e-6;  // relative to the quantity's scale
constexpr double kRoundOff = 1e-10;                  // relative

/// Platform pose from one limb's joint variables by the product of exponentials
/// exp(s_1 q_1) exp(s_2 q_2) exp(s_3 q_3) applied to the home pose (independent of the model).
Pose productOfExponentials(const RobotDescription& robot, int j, const Vector3& q) {
    double angle = 0.0;
    Vector2 t = Vector2::Zero();
    const auto rotate = [](double a, const Vector2& v) {
        return Vector2(std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y());
    };
    for (int k = 0; k < 3; ++k) {
        const JointDescription& joint = robot.limbs[static_cast<std::size_t>(j)].joints[static_cast<std::size_t>(k)];
        double a = 0.0;
        Vector2 d = Vector2::Zero();
        if (joint.type == JointType::revolute) {
            a = q(k);
            d = joint.point - rotate(a, joint.point);
        } else {
            d = q(k) * joint.direction;
        }
        t = rotate(angle, d) + t;  // g o e
        angle += a;
    }
    const Vector2 c = rotate(angle, robot.home.tail<2>()) + t;
    return {robot.home(0) + angle, c.x(), c.y()};
}

struct Sample {
    Pose p, dp, ddp;
};

Sample at(const PoseTrajectory& trajectory, double t) {
    Sample s;
    trajectory.evaluate(t, s.p, s.dp, s.ddp);
    return s;
}

/// The full path at t - h, t and t + h, for central differences; false when a sample fails.
bool solveAround(const Model& model, const PoseTrajectory& trajectory, double t, double h, Data& minus, Data& data,
                 Data& plus) {
    bool ok = true;
    for (auto [time, out] : {std::pair{t - h, &minus}, std::pair{t, &data}, std::pair{t + h, &plus}}) {
        const Sample s = at(trajectory, time);
        ok = ok && inverseDynamics(model, *out, s.p, s.dp, s.ddp).ok();
    }
    return ok;
}

/// Random robots of every limb type (all limbs alike, then mixed), with and without gravity
/// and friction, three actuators or more.
std::vector<RandomRobotSpec> specs() {
    std::vector<RandomRobotSpec> out;
    for (const std::string& type : limbTypes()) {
        out.push_back({{type, type, type}, 3, false, false});
        out.push_back({{type, type, type}, 3, true, true});
        out.push_back({{type, type, type, type}, 4, true, true});
    }
    out.push_back({{"RRR", "PRR", "RPR"}, 3, true, false});
    out.push_back({{"RRP", "PRP", "RPP", "PPR"}, 5, false, true});
    out.push_back({{"PRR", "RRR", "RPR", "RRR", "PRR"}, 6, true, true});
    return out;
}

std::string label(const RandomRobotSpec& spec) {
    std::string s;
    for (const auto& type : spec.limb_types) s += type + "-";
    if (spec.actuated_joint >= 0) s += "joint" + std::to_string(spec.actuated_joint + 1) + "-";
    return s + std::to_string(spec.actuators) + (spec.gravity ? "-gravity" : "") + (spec.friction ? "-friction" : "");
}

/// Robots whose limbs are alike and actuated at the same joint, which the lean path runs
/// side by side in the lanes of a packet: every limb type and actuated joint, three limbs,
/// and four with gravity and friction. A limb with one R joint, actuated there, only measures
/// the platform's angle (three of them cannot actuate it): left out.
std::vector<RandomRobotSpec> uniformSpecs() {
    std::vector<RandomRobotSpec> out;
    for (const std::string& type : limbTypes()) {
        for (int k = 0; k < 3; ++k) {
            if (type[static_cast<std::size_t>(k)] == 'R' && std::count(type.begin(), type.end(), 'R') == 1) continue;
            out.push_back({{type, type, type}, 3, false, false, k});
            out.push_back({{type, type, type, type}, 4, true, true, k});
        }
    }
    return out;
}

class RandomRobots : public ::testing::TestWithParam<RandomRobotSpec> {
protected:
    /// The first few random robots of the spec that are regular along a random trajectory.
    void forEachRobot(const std::function<void(const Model&, const PoseTrajectory&)>& check) {
        std::mt19937 rng(7);
        int kept = 0, tried = 0;
        while (kept < kRobots && tried < 200) {
            ++tried;
            const auto description = randomRobot(GetParam(), rng);
            if (!description) continue;
            const Model model(*description);
            const PoseTrajectory trajectory = trajectoryAround(description->home, rng, 0.5);
            Data data(model);
            bool regular = true;
            for (int k = 0; k <= kSamples && regular; ++k) {
                const Sample s = at(trajectory, k * kDuration / kSamples);
                regular = inverseDynamics(model, data, s.p, s.dp, s.ddp).ok() && data.cond_A < 1e3;
                for (int j = 0; j < model.limbs; ++j)
                    regular = regular && data.limb[static_cast<std::size_t>(j)].cond < 1e3;
            }
            if (!regular) continue;
            ++kept;
            check(model, trajectory);
        }
        EXPECT_EQ(kept, kRobots) << label(GetParam()) << ": only " << kept << " regular robots in " << tried;
    }

    static constexpr int kRobots = 3;
    static constexpr int kSamples = 12;
    static constexpr double kDuration = 0.3;
};

TEST_P(RandomRobots, InverseDisplacementInvertsTheProductOfExponentials) {
    forEachRobot([](const Model& model, const PoseTrajectory& trajectory) {
        Data data(model);
        for (int k = 0; k <= kSamples; ++k) {
            const Sample s = at(trajectory, k * kDuration / kSamples);
            ASSERT_TRUE(inverseDisplacement(model, data, s.p).ok());
            for (int j = 0; j < model.limbs; ++j) {
                const Pose back = productOfExponentials(model.description, j, data.limb[static_cast<std::size_t>(j)].q);
                EXPECT_NEAR(back(0), s.p(0), 1e-13) << model.limbName(j);
                EXPECT_NEAR(back(1), s.p(1), 1e-13) << model.limbName(j);
                EXPECT_NEAR(back(2), s.p(2), 1e-13) << model.limbName(j);
            }
        }
    });
}

TEST_P(RandomRobots, RatesAndAccelerationsMatchFiniteDifferences) {
    forEachRobot([](const Model& model, const PoseTrajectory& trajectory) {
        Data data(model), minus(model), plus(model);
        const double h = kFiniteDifferenceStep;
        for (int k = 1; k < kSamples; ++k) {
            const double t = k * kDuration / kSamples;
            ASSERT_TRUE(solveAround(model, trajectory, t, h, minus, data, plus)) << "t = " << t;
            for (int j = 0; j < model.limbs; ++j) {
                const auto jj = static_cast<std::size_t>(j);
                for (int q = 0; q < 3; ++q) {
                    double dq = plus.limb[jj].q(q) - minus.limb[jj].q(q);
                    dq = std::remainder(dq, 2.0 * std::numbers::pi);  // angles wrap
                    const double fd = dq / (2 * h);
                    const double fd2 = (plus.limb[jj].gamma_dot(q) - minus.limb[jj].gamma_dot(q)) / (2 * h);
                    const double scale_v = 1.0 + data.limb[jj].gamma_dot.cwiseAbs().maxCoeff();
                    const double scale_a = 1.0 + data.limb[jj].gamma_ddot.cwiseAbs().maxCoeff();
                    EXPECT_NEAR(data.limb[jj].gamma_dot(q), fd, kFiniteDifferenceTolerance * scale_v)
                        << model.limbName(j) << " joint " << q + 1;
                    EXPECT_NEAR(data.limb[jj].gamma_ddot(q), fd2, 1e-5 * scale_a)
                        << model.limbName(j) << " joint " << q + 1;
                }
            }
            // T_i v is the body twist: its c.o.m. velocity against finite differences of x_i
            for (int j = 0; j < model.limbs; ++j) {
                const auto jj = static_cast<std::size_t>(j);
                for (int b = 0; b < 2; ++b) {
                    const auto bb = static_cast<std::size_t>(b);
                    const Vector2 fd = (plus.limb[jj].x[bb] - minus.limb[jj].x[bb]) / (2 * h);
                    const Vector3 v =
                        model.coordinates == Coordinates::actuators ? Vector3(data.du) : Vector3(data.t_M);
                    const Twist t_i = data.T[static_cast<std::size_t>(model.body(j, b))] * v;
                    EXPECT_NEAR(t_i(1), fd.x(), kFiniteDifferenceTolerance * (1.0 + fd.norm()));
                    EXPECT_NEAR(t_i(2), fd.y(), kFiniteDifferenceTolerance * (1.0 + fd.norm()));
                }
            }
            // dT_i against finite differences of T_i
            for (int i = 0; i < model.bodies; ++i) {
                const auto ii = static_cast<std::size_t>(i);
                const Matrix3 fd = (plus.T[ii] - minus.T[ii]) / (2 * h);
                const double scale = 1.0 + data.T_dot[ii].cwiseAbs().maxCoeff() + data.T[ii].cwiseAbs().maxCoeff();
                EXPECT_LT((fd - data.T_dot[ii]).cwiseAbs().maxCoeff(), 1e-5 * scale) << "body " << i;
            }
        }
    });
}

TEST_P(RandomRobots, InertiaIsSymmetricPositiveDefiniteAndItsRateIsCPlusCTranspose) {
    forEachRobot([](const Model& model, const PoseTrajectory& trajectory) {
        Data data(model), minus(model), plus(model);
        const double h = kFiniteDifferenceStep;
        for (int k = 1; k < kSamples; ++k) {
            const double t = k * kDuration / kSamples;
            ASSERT_TRUE(solveAround(model, trajectory, t, h, minus, data, plus)) << "t = " << t;
            const double scale = data.I.cwiseAbs().maxCoeff();
            EXPECT_LT((data.I - data.I.transpose()).cwiseAbs().maxCoeff(), kRoundOff * scale);
            const Eigen::SelfAdjointEigenSolver<Matrix3> eig(data.I);
            EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
            const Matrix3 I_dot = (plus.I - minus.I) / (2 * h);
            const Matrix3 CC = data.C + data.C.transpose();
            EXPECT_LT((I_dot - CC).cwiseAbs().maxCoeff(), 1e-5 * (1.0 + CC.cwiseAbs().maxCoeff() + scale));
        }
    });
}

TEST_P(RandomRobots, PowerBalanceHoldsWithGravityAndFriction) {
    forEachRobot([](const Model& model, const PoseTrajectory& trajectory) {
        Data data(model), minus(model), plus(model);
        const double h = kFiniteDifferenceStep;
        for (int k = 1; k < kSamples; ++k) {
            const double t = k * kDuration / kSamples;
            ASSERT_TRUE(solveAround(model, trajectory, t, h, minus, data, plus)) << "t = " << t;
            const double energy_rate = (kineticEnergy(model, plus) + potentialEnergy(model, plus) -
                                        kineticEnergy(model, minus) - potentialEnergy(model, minus)) /
                                       (2 * h);
            const double power = data.tau.dot(data.du);
            const double scale = 1.0 + (data.tau.cwiseAbs().array() * data.du.cwiseAbs().array()).sum();
            EXPECT_NEAR(power, energy_rate + frictionPower(model, data), 1e-6 * scale) << "t = " << t;
        }
    });
}

TEST_P(RandomRobots, LeanPathEqualsFullPath) {
    forEachRobot([](const Model& model, const PoseTrajectory& trajectory) {
        Data full(model), lean(model);
        for (int k = 0; k <= kSamples; ++k) {
            const Sample s = at(trajectory, k * kDuration / kSamples);
            ASSERT_TRUE(inverseDynamics(model, full, s.p, s.dp, s.ddp).ok());
            ASSERT_TRUE(inverseDynamicsFast(model, lean, s.p, s.dp, s.ddp).ok());
            const double scale = 1.0 + full.tau.cwiseAbs().maxCoeff();
            for (int a = 0; a < model.actuators; ++a) {
                EXPECT_NEAR(lean.u(a), full.u(a), 1e-14);
                EXPECT_NEAR(lean.du(a), full.du(a), 1e-12 * (1.0 + std::abs(full.du(a))));
                EXPECT_NEAR(lean.ddu(a), full.ddu(a), 1e-11 * (1.0 + std::abs(full.ddu(a))));
                EXPECT_NEAR(lean.tau(a), full.tau(a), kRoundOff * scale) << "actuator " << a + 1;
            }
        }
    });
}

TEST_P(RandomRobots, BatchEqualsThePerSamplePath) {
    forEachRobot([](const Model& model, const PoseTrajectory& trajectory) {
        // the trajectory's samples, and one pose out of reach in the middle
        const Eigen::Index N = kSamples + 2;
        Eigen::ArrayX3d p(N, 3), dp(N, 3), ddp(N, 3);
        for (Eigen::Index k = 0; k < N; ++k) {
            const Sample s = at(trajectory, static_cast<double>(k) * kDuration / kSamples);
            p.row(k) = s.p.transpose();
            dp.row(k) = s.dp.transpose();
            ddp.row(k) = s.ddp.transpose();
        }
        p(N / 2, 1) += 100.0;  // out of reach unless the limbs' P joints can follow
        // beyond the branch-free sinCos's range, and a non-finite rate: each lane the packet
        // kernel hands to the full path
        p(1, 0) += 4.0e6 * M_PI;
        dp(N - 2, 2) = std::numeric_limits<double>::quiet_NaN();
        const int n = model.actuators;
        for (const unsigned threads : {1u, 3u}) {
            Eigen::ArrayXXd u(N, n), du(N, n), ddu(N, n), tau(N, n);
            const BatchResult result = inverseDynamicsBatch(model, p, dp, ddp, u, du, ddu, tau, threads);
            Data data(model);
            Eigen::Index failed = 0;
            for (Eigen::Index k = 0; k < N; ++k) {
                const Status status = inverseDynamicsFast(model, data, p.row(k).transpose(), dp.row(k).transpose(),
                                                          ddp.row(k).transpose());
                if (!status) {
                    if (failed++ == 0) {
                        EXPECT_EQ(result.first_failure, k);
                        EXPECT_EQ(result.status.code, status.code);
                        EXPECT_EQ(result.status.limb, status.limb);
                        // the same number, or both NaN (a non-finite input's)
                        EXPECT_TRUE(result.status.value == status.value ||
                                    (std::isnan(result.status.value) && std::isnan(status.value)))
                            << result.status.value << " vs " << status.value;
                    }
                    for (int a = 0; a < n; ++a) EXPECT_TRUE(std::isnan(tau(k, a)));
                    continue;
                }
                const double scale = 1.0 + data.tau.cwiseAbs().maxCoeff();
                for (int a = 0; a < n; ++a) {
                    // the same kernel, inlined elsewhere: equal to rounding
                    EXPECT_NEAR(u(k, a), data.u(a), 1e-14 * (1.0 + std::abs(data.u(a))));
                    EXPECT_NEAR(du(k, a), data.du(a), 1e-12 * (1.0 + std::abs(data.du(a))));
                    EXPECT_NEAR(ddu(k, a), data.ddu(a), 1e-12 * (1.0 + std::abs(data.ddu(a))));
                    EXPECT_NEAR(tau(k, a), data.tau(a), kRoundOff * scale) << "sample " << k << ", actuator " << a + 1;
                }
            }
            EXPECT_EQ(result.failed, failed);
        }
    });
}

TEST_P(RandomRobots, RedundantForcesAreTheMinimumNormSolution) {
    forEachRobot([](const Model& model, const PoseTrajectory& trajectory) {
        Data data(model);
        for (int k = 0; k <= kSamples; ++k) {
            const Sample s = at(trajectory, k * kDuration / kSamples);
            ASSERT_TRUE(inverseDynamics(model, data, s.p, s.dp, s.ddp).ok());
            // A_p^T tau = Q, and tau lies in the range of A_p (no component in its null space)
            const Eigen::MatrixXd A_p = Eigen::MatrixXd(data.A) * data.Xi;
            const Eigen::VectorXd tau = data.tau;
            const double scale = 1.0 + tau.cwiseAbs().maxCoeff() * A_p.cwiseAbs().maxCoeff();
            EXPECT_LT((A_p.transpose() * tau - data.Q).cwiseAbs().maxCoeff(), kRoundOff * scale);
            const Eigen::VectorXd projected = A_p * A_p.colPivHouseholderQr().solve(tau);
            EXPECT_LT((projected - tau).cwiseAbs().maxCoeff(), kRoundOff * (1.0 + tau.cwiseAbs().maxCoeff()));
        }
    });
}

/// A test name from a robot's label (gtest names take no '-').
std::string testName(const ::testing::TestParamInfo<RandomRobotSpec>& info) {
    std::string name = label(info.param);
    for (char& c : name) c = c == '-' ? '_' : c;
    return name;
}

INSTANTIATE_TEST_SUITE_P(EveryLimbType, RandomRobots, ::testing::ValuesIn(specs()), testName);

using UniformRobots = RandomRobots;

// The limbs in the lanes of one packet give what the full path gives, sample by sample, and
// hand it every sample it must refuse (a pose out of reach) with the full path's Status.
TEST_P(UniformRobots, LimbsInLanesEqualTheFullPath) {
    forEachRobot([](const Model& model, const PoseTrajectory& trajectory) {
        EXPECT_TRUE(model.limbsInLanes());
        Data full(model), lean(model);
        for (int k = 0; k <= kSamples; ++k) {
            Sample s = at(trajectory, k * kDuration / kSamples);
            if (k == kSamples / 2) s.p(1) += 100.0;  // out of reach unless every limb's P joints can follow
            const Status expected = inverseDynamics(model, full, s.p, s.dp, s.ddp);
            const Status status = inverseDynamicsFast(model, lean, s.p, s.dp, s.ddp);
            ASSERT_EQ(status.code, expected.code) << "sample " << k;
            EXPECT_EQ(status.limb, expected.limb);
            if (!expected) {
                EXPECT_EQ(status.value, expected.value);
                continue;
            }
            const double scale = 1.0 + full.tau.cwiseAbs().maxCoeff();
            for (int a = 0; a < model.actuators; ++a) {
                EXPECT_NEAR(lean.u(a), full.u(a), 1e-14 * (1.0 + std::abs(full.u(a))))
                    << "sample " << k << ", actuator " << a + 1;
                EXPECT_NEAR(lean.du(a), full.du(a), 1e-12 * (1.0 + std::abs(full.du(a))));
                EXPECT_NEAR(lean.ddu(a), full.ddu(a), 1e-11 * (1.0 + std::abs(full.ddu(a))));
                EXPECT_NEAR(lean.tau(a), full.tau(a), kRoundOff * scale) << "sample " << k << ", actuator " << a + 1;
            }
            // W_P = A^T tau, to the round-off of that product
            const Wrench W_P = full.A.transpose() * full.tau;
            EXPECT_LT((lean.W_P - W_P).cwiseAbs().maxCoeff(),
                      kRoundOff * (1.0 + full.A.cwiseAbs().maxCoeff() * full.tau.cwiseAbs().maxCoeff()));
        }
    });
}

INSTANTIATE_TEST_SUITE_P(EveryLimbTypeAndActuatedJoint, UniformRobots, ::testing::ValuesIn(uniformSpecs()), testName);

// The branch-free atan2 of the actuated angles against libm's, over every octant, near
// the breakpoints of its reduction, tiny and large angles, and unnormalised (c, s).
TEST(FastMath, APacketGivesEachLaneTheValueOfTheScalarFunctions) {
    using nocdyn::fastmath::Pack;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> angle(-40.0, 40.0), unit(-1.0, 1.0);
    for (int trial = 0; trial < 200; ++trial) {
        Pack x, y, c;
        for (int l = 0; l < 4; ++l) x[l] = angle(rng), y[l] = unit(rng), c[l] = unit(rng);
        if (trial == 0) y[1] = 0.0, c[1] = -1.0, y[2] = -0.0, c[2] = -1.0, y[3] = 1.0, c[3] = 0.0;
        Pack s_p, c_p;
        nocdyn::fastmath::sinCos(x, s_p, c_p);
        const Pack a_p = nocdyn::fastmath::atan2Of(y, c);
        for (int l = 0; l < 4; ++l) {
            double s_d, c_d;
            nocdyn::fastmath::sinCos(x[l], s_d, c_d);
            EXPECT_EQ(s_p[l], s_d);
            EXPECT_EQ(c_p[l], c_d);
            EXPECT_EQ(a_p[l], nocdyn::fastmath::atan2Of(y[l], c[l])) << y[l] << ", " << c[l];
            EXPECT_NEAR(s_d, std::sin(x[l]), 4e-16);
            EXPECT_NEAR(c_d, std::cos(x[l]), 4e-16);
        }
    }
}

TEST(Atan2Of, IsWithinTwoUlpOfLibm) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> angle(-M_PI, M_PI), scale(0.25, 4.0);
    const double breakpoints[] = {std::atan(0.4375), std::atan(0.6875), std::atan(1.1875), std::atan(2.4375)};
    double worst = 0.0;
    for (int i = 0; i < 400000; ++i) {
        double a = angle(rng);
        if (i % 5 == 1) a = std::ldexp(a, -(i % 64));  // tiny
        if (i % 5 == 2) a = breakpoints[i % 4] * (1.0 + std::ldexp(a, -40)) * ((i & 8) ? -1.0 : 1.0);
        if (i % 5 == 3) a = std::copysign(M_PI, a) - std::ldexp(a, -(i % 50));  // next to +-pi
        const double k = i % 3 == 0 ? scale(rng) : 1.0;
        const double y = k * std::sin(a), x = k * std::cos(a);
        const double expected = std::atan2(y, x);
        const double ulp = std::nextafter(std::abs(expected), INFINITY) - std::abs(expected);
        worst = std::max(worst, std::abs(nocdyn::detail::ik::atan2Of(y, x) - expected) / ulp);
    }
    EXPECT_LE(worst, 2.0);
    EXPECT_GT(worst, 0.0);  // not libm itself
    EXPECT_EQ(nocdyn::detail::ik::atan2Of(0.0, 1.0), 0.0);
    EXPECT_EQ(nocdyn::detail::ik::atan2Of(0.0, -1.0), M_PI);
    EXPECT_EQ(nocdyn::detail::ik::atan2Of(-0.0, -1.0), -M_PI);
    EXPECT_EQ(nocdyn::detail::ik::atan2Of(1.0, 0.0), M_PI / 2);
    EXPECT_EQ(nocdyn::detail::ik::atan2Of(-1.0, 0.0), -M_PI / 2);
}

TEST(PaperRobot, PoseOutOfReachNamesTheLimbAndTheDistance) {
    const Model model{io::expand(io::RobotParameters{})};
    Data data(model);
    // far to the right: limb 2 (rail along 120 degrees) cannot reach
    const Status status = inverseDisplacement(model, data, Pose(0.0, 0.3, 0.0));
    ASSERT_EQ(status.code, StatusCode::unreachable);
    EXPECT_GE(status.limb, 0);
    EXPECT_GT(status.value, 0.0);
    const std::string message = describe(status, model);
    EXPECT_NE(message.find("limb " + std::to_string(status.limb + 1)), std::string::npos) << message;
}

TEST(PaperRobot, NonFiniteInputIsAStatusNotANaN) {
    const Model model{io::expand(io::RobotParameters{})};
    Data data(model);
    EXPECT_EQ(inverseDynamics(model, data, Pose(std::nan(""), 0, 0), Twist::Zero(), Twist::Zero()).code,
              StatusCode::not_finite);
    EXPECT_EQ(inverseDynamicsFast(model, data, Pose::Zero(), Twist(0, INFINITY, 0), Twist::Zero()).code,
              StatusCode::not_finite);
}

}  // namespace
}  // namespace nocdyn::test
