// Exact derivatives of the inverse and forward dynamics (derivatives.hpp) on random robots of
// every limb type (the robots of lagrange_test.cpp: gravity, friction, redundant actuation),
// against five-point central finite differences of the values of inverseDynamics and
// forwardDynamics (independent code: the full NOC path with T_i, I and C), and the identities
// A_p^T d tau/d ddp = M_p (the mapped mass matrix) and d ddp/d tau = M_p^-1 A_p^T; and the
// derivatives of the actuator variables u, du, ddu against differences of inverseDynamics'
// values, with d du/d dp = d ddu/d ddp = d u/d p = A S(c).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <optional>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "nocdyn/batch.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "random_robots.hpp"

namespace nocdyn::test {
namespace {

// Five-point stencils at h and h/2, extrapolated: at these steps truncation and rounding are
// both below 1e-9 of the derivatives' size on most samples of these robots (poses over
// centimetres and tenths of a radian, rates of a few rad/s and tens of mm/s).
constexpr double kStep = 2e-5;
// relative, per matrix: |AD - FD| <= kTolerance (|AD| + floor). The worst matrix, on the random
// four-limb PPR robot, is at 8.8e-8 in the release build (-O3) and 1.04e-7 at -O1 (the mutation
// check's build): the differences' rounding moves with the compiled code at that level, while a
// wrong term is off by 1e-3 or more.
constexpr double kTolerance = 2e-7;
constexpr double kConditionLimit = 1e3;

std::vector<RandomRobotSpec> specs() {
    std::vector<RandomRobotSpec> out;
    for (const std::string& type : limbTypes()) {
        out.push_back({{type, type, type}, 3, true, true});
        out.push_back({{type, type, type, type}, 4, true, true});
    }
    out.push_back({{"RRR", "PRR", "RPR"}, 3, true, false});
    out.push_back({{"RRP", "PRP", "RPP", "PPR"}, 5, false, true});
    out.push_back({{"PRR", "RRR", "RPR", "RRR", "PRR"}, 6, true, true});
    out.push_back({{"PRR", "PRR", "PRR"}, 3, true, true, 0});
    out.push_back({{"RRR", "RRR", "RRR"}, 3, true, true, 0});
    out.push_back({{"RPR", "RPR", "RPR"}, 3, true, true, 1});
    return out;
}

std::string label(const RandomRobotSpec& spec) {
    std::string s;
    for (const auto& type : spec.limb_types) s += type + "_";
    if (spec.actuated_joint >= 0) s += "joint" + std::to_string(spec.actuated_joint + 1) + "_";
    return s + std::to_string(spec.actuators) + (spec.gravity ? "_gravity" : "") + (spec.friction ? "_friction" : "");
}

std::string testName(const ::testing::TestParamInfo<RandomRobotSpec>& info) { return label(info.param); }

struct Sample {
    Pose p, dp, ddp;
};

/// Every joint rate of the sample away from zero, so that no Coulomb sign flips within the
/// stencil (the derivative freezes it; a difference across the flip would see the jump).
bool ratesAwayFromZero(const Model& model, const Data& data) {
    for (int j = 0; j < model.limbs; ++j) {
        if (data.limb[static_cast<std::size_t>(j)].gamma_dot.cwiseAbs().minCoeff() < 1e-2) return false;
    }
    return true;
}

/// Five-point derivative of f (a vector) at step h.
template <class F>
Eigen::VectorXd fivePoint(const F& f, double h) {
    return (-f(2.0 * h) + 8.0 * f(h) - 8.0 * f(-h) + f(-2.0 * h)) / (12.0 * h);
}

/// The five-point derivatives at h and h/2 extrapolated (Richardson, truncation O(h^6)), and
/// in `spread` how far the two disagree (an upper bound of the extrapolation's error where the
/// Taylor series converges).
template <class F>
Eigen::VectorXd stencil(const F& f, double h, double& spread) {
    const Eigen::VectorXd coarse = fivePoint(f, h), fine = fivePoint(f, 0.5 * h);
    spread = std::max(spread, (fine - coarse).cwiseAbs().maxCoeff());
    return (16.0 * fine - coarse) / 15.0;
}

/// Where the dynamics vary over lengths near the step (a limb close to the edge of its reach)
/// the differences do not converge, and cannot judge the derivative: such a matrix is skipped
/// when its two stencils differ by more than this, relative.
constexpr double kUnconverged = 1e-4;

double relativeError(const Eigen::MatrixXd& exact, const Eigen::MatrixXd& fd, double floor) {
    return (exact - fd).cwiseAbs().maxCoeff() / (exact.cwiseAbs().maxCoeff() + floor);
}

/// What a test's finite-difference comparisons found: the worst relative error, and how many
/// matrices were compared and skipped as unconverged.
struct Agreement {
    double worst = 0.0;
    int matrices = 0, skipped = 0;

    /// The summary line, and that at most one matrix in ten was skipped.
    void report(const std::string& robot, const char* what) const {
        std::printf("%s: worst relative error of %s %.2e (%d of %d matrices skipped)\n", robot.c_str(), what, worst,
                    skipped, matrices);
        EXPECT_LE(10 * skipped, matrices) << "the finite differences did not converge on too many samples";
    }
};

/// `exact` against the extrapolated central differences of value(i, h) (the value with input
/// coordinate i moved by h), one column per input, at step h: within kTolerance relative to
/// |exact| + error_floor, unless the stencils differ by more than kUnconverged (|exact| + floor).
template <class Value>
void expectFiniteDifferences(const Eigen::MatrixXd& exact, double step, double floor, double error_floor,
                             const Value& value, Agreement& agreement, const std::string& what) {
    Eigen::MatrixXd fd(exact.rows(), exact.cols());
    double spread = 0.0;
    for (Eigen::Index i = 0; i < exact.cols(); ++i) {
        fd.col(i) = stencil([&](double h) -> Eigen::VectorXd { return value(static_cast<int>(i), h); }, step, spread);
    }
    ++agreement.matrices;
    if (spread > kUnconverged * (exact.cwiseAbs().maxCoeff() + floor)) {
        ++agreement.skipped;
        return;
    }
    const double error = relativeError(exact, fd, error_floor);
    agreement.worst = std::max(agreement.worst, error);
    EXPECT_LE(error, kTolerance) << what << "\nexact\n" << exact << "\nfinite differences\n" << fd;
}

class DerivativesRandomRobots : public ::testing::TestWithParam<RandomRobotSpec> {
protected:
    static constexpr int kRobots = 2;
    static constexpr int kSamples = 10;

    /// The first kRobots random robots of the spec that are regular along a random trajectory,
    /// with check run on each sample whose joint rates are away from zero. Returns the count.
    template <class Check>
    void forEachSample(const Check& check) {
        std::mt19937 rng(23);
        int kept = 0, tried = 0, checked = 0;
        while (kept < kRobots && tried < 200) {
            ++tried;
            const auto description = randomRobot(GetParam(), rng);
            if (!description) continue;
            const Model model(*description);
            const PoseTrajectory trajectory = trajectoryAround(description->home, rng, 0.5);
            Data data(model);
            std::vector<Sample> samples;
            bool regular = true;
            for (int k = 0; k < kSamples && regular; ++k) {
                Sample s;
                trajectory.evaluate(0.037 + k * 0.03, s.p, s.dp, s.ddp);
                regular = inverseDynamics(model, data, s.p, s.dp, s.ddp).ok() && data.cond_A < kConditionLimit;
                for (int j = 0; j < model.limbs; ++j)
                    regular = regular && data.limb[static_cast<std::size_t>(j)].cond < kConditionLimit;
                if (regular && ratesAwayFromZero(model, data)) samples.push_back(s);
            }
            if (!regular) continue;
            ++kept;
            for (const Sample& s : samples) {
                check(model, s);
                ++checked;
            }
        }
        EXPECT_EQ(kept, kRobots) << label(GetParam()) << ": only " << kept << " regular robots in " << tried;
        EXPECT_GE(checked, kRobots * kSamples / 2) << label(GetParam()) << ": too few samples checked";
    }
};

std::string where(const Sample& s) {
    std::ostringstream out;
    out << "p = [" << s.p.transpose() << "], dp = [" << s.dp.transpose() << "], ddp = [" << s.ddp.transpose() << "]";
    return out.str();
}

TEST_P(DerivativesRandomRobots, InverseDynamicsDerivativesEqualFiniteDifferences) {
    Agreement agreement;
    forEachSample([&](const Model& model, const Sample& s) {
        Data data(model), probe(model);
        InverseDynamicsDerivatives d;
        ASSERT_TRUE(inverseDynamicsDerivatives(model, data, s.p, s.dp, s.ddp, d).ok()) << where(s);
        ASSERT_TRUE(inverseDynamics(model, probe, s.p, s.dp, s.ddp).ok());
        const Eigen::VectorXd tau = probe.tau;
        EXPECT_LE((Eigen::VectorXd(d.tau) - tau).cwiseAbs().maxCoeff(), 1e-11 * (1.0 + tau.cwiseAbs().maxCoeff()));
        const double floor = 1e-3 * (1.0 + tau.cwiseAbs().maxCoeff());
        const std::array<const char*, 3> names{"p", "dp", "ddp"};
        for (int which = 0; which < 3; ++which) {
            const auto f = [&](int i, double h) -> Eigen::VectorXd {
                Sample t = s;
                (which == 0 ? t.p : which == 1 ? t.dp : t.ddp)(i) += h;
                EXPECT_TRUE(inverseDynamics(model, probe, t.p, t.dp, t.ddp).ok());
                return probe.tau;
            };
            const Eigen::MatrixXd exact =
                which == 0 ? Eigen::MatrixXd(d.d_p) : (which == 1 ? Eigen::MatrixXd(d.d_dp) : Eigen::MatrixXd(d.d_ddp));
            expectFiniteDifferences(exact, kStep, floor, floor, f, agreement,
                                    std::string("d tau/d ") + names[static_cast<std::size_t>(which)] + " of " +
                                        label(GetParam()) + " at " + where(s));
        }
    });
    agreement.report(label(GetParam()), "d tau/d(p, dp, ddp)");
}

TEST_P(DerivativesRandomRobots, AccelerationDerivativeIsTheMappedMassMatrix) {
    forEachSample([&](const Model& model, const Sample& s) {
        Data data(model), platform(model);
        InverseDynamicsDerivatives d;
        ASSERT_TRUE(inverseDynamicsDerivatives(model, data, s.p, s.dp, s.ddp, d).ok());
        ASSERT_TRUE(inverseDisplacement(model, platform, s.p).ok());
        ASSERT_TRUE(velocityFromPlatformTwist(model, platform, s.dp).ok());
        platformDynamics(model, platform);
        // A_p^T d tau/d ddp = M_p (the actuators' resultant supplies M_p ddp), A_p = A S(c)
        const Eigen::MatrixXd A_p = Eigen::MatrixXd(platform.A) * platformTwistMap(s.p.tail<2>());
        const Matrix3 mapped = A_p.transpose() * Eigen::MatrixXd(d.d_ddp);
        EXPECT_LE((mapped - platform.M_p).cwiseAbs().maxCoeff(), 1e-11 * platform.M_p.cwiseAbs().maxCoeff())
            << label(GetParam()) << "\n"
            << mapped << "\nM_p\n"
            << platform.M_p;
        // and the minimum-norm tau lies in the range of A_p: d tau/d ddp = A_p (A_p^T A_p)^-1 M_p
        const Eigen::MatrixXd expected = A_p * (A_p.transpose() * A_p).inverse() * platform.M_p;
        EXPECT_LE((Eigen::MatrixXd(d.d_ddp) - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
    });
}

TEST_P(DerivativesRandomRobots, ForwardDynamicsDerivativesEqualFiniteDifferences) {
    Agreement agreement;
    forEachSample([&](const Model& model, const Sample& s) {
        Data data(model), probe(model);
        // the forces of the sample's own motion
        ASSERT_TRUE(inverseDynamics(model, probe, s.p, s.dp, s.ddp).ok());
        const ActuatorVector tau = probe.tau;
        ForwardDynamicsDerivatives d;
        ASSERT_TRUE(forwardDynamicsDerivatives(model, data, s.p, s.dp, tau, d).ok()) << where(s);
        ASSERT_TRUE(forwardDynamics(model, probe, s.p, s.dp, tau).ok());
        EXPECT_LE((d.ddp - probe.t_M_dot).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + s.ddp.cwiseAbs().maxCoeff()));
        EXPECT_LE((d.M_p - probe.M_p).cwiseAbs().maxCoeff(), 1e-11 * probe.M_p.cwiseAbs().maxCoeff());
        const double floor = 1e-3 * (1.0 + s.ddp.cwiseAbs().maxCoeff());
        const std::array<const char*, 3> names{"p", "dp", "tau"};
        for (int which = 0; which < 3; ++which) {
            const auto f = [&](int i, double h) -> Eigen::VectorXd {
                Pose p = s.p;
                Twist dp = s.dp;
                ActuatorVector t = tau;
                if (which == 0) p(i) += h;
                if (which == 1) dp(i) += h;
                if (which == 2) t(i) += h;
                EXPECT_TRUE(forwardDynamics(model, probe, p, dp, t).ok());
                return probe.t_M_dot;
            };
            const Eigen::MatrixXd exact =
                which == 0 ? Eigen::MatrixXd(d.d_p) : (which == 1 ? Eigen::MatrixXd(d.d_dp) : Eigen::MatrixXd(d.d_tau));
            // forces are tens of newtons: a step of 1e-4 N is as fine as 1e-4 m
            expectFiniteDifferences(exact, which == 2 ? 1e-2 : kStep, floor, which == 2 ? 0.0 : floor, f, agreement,
                                    std::string("d ddp/d ") + names[static_cast<std::size_t>(which)] + " of " +
                                        label(GetParam()) + " at " + where(s));
        }
        // d ddp/d tau = M_p^-1 A_p^T
        const Eigen::MatrixXd A_p = Eigen::MatrixXd(data.A) * platformTwistMap(s.p.tail<2>());
        const Eigen::MatrixXd expected = probe.M_p.inverse() * A_p.transpose();
        EXPECT_LE((Eigen::MatrixXd(d.d_tau) - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
    });
    agreement.report(label(GetParam()), "d ddp/d(p, dp, tau)");
}

/// A random robot of the spec and 20 samples along a trajectory about its home (N x 3 each, the
/// core's pose order), the last one's x not a number.
struct BatchCase {
    std::optional<Model> model;
    Eigen::ArrayXXd p, dp, ddp;
};

BatchCase batchCase(const RandomRobotSpec& spec) {
    BatchCase c;
    std::mt19937 rng(23);
    std::vector<Sample> all;
    for (int tried = 0; tried < 200 && !c.model; ++tried) {
        const auto description = randomRobot(spec, rng);
        if (!description) continue;
        c.model.emplace(*description);
        const PoseTrajectory trajectory = trajectoryAround(description->home, rng, 0.5);
        for (int k = 0; k < 20; ++k) {
            Sample s;
            trajectory.evaluate(0.01 * k, s.p, s.dp, s.ddp);
            all.push_back(s);
        }
    }
    const auto N = static_cast<Eigen::Index>(all.size());
    c.p.resize(N, 3);
    c.dp.resize(N, 3);
    c.ddp.resize(N, 3);
    for (Eigen::Index k = 0; k < N; ++k) {
        c.p.row(k) = all[static_cast<std::size_t>(k)].p.transpose();
        c.dp.row(k) = all[static_cast<std::size_t>(k)].dp.transpose();
        c.ddp.row(k) = all[static_cast<std::size_t>(k)].ddp.transpose();
    }
    if (N > 0) c.p(N - 1, 1) = std::nan("");  // NaN outputs and its Status
    return c;
}

TEST_P(DerivativesRandomRobots, BatchEqualsSampleBySample) {
    const BatchCase c = batchCase(GetParam());
    ASSERT_TRUE(c.model.has_value());
    const Model& model = *c.model;
    const Eigen::ArrayXXd &p = c.p, &dp = c.dp, &ddp = c.ddp;
    const Eigen::Index N = p.rows();
    const int n = model.actuators;
    Eigen::ArrayXXd d_p(N, 3 * n), d_dp(N, 3 * n), d_ddp(N, 3 * n);
    const BatchResult result = inverseDynamicsDerivativesBatch(model, p, dp, ddp, d_p, d_dp, d_ddp, 2);
    Data data(model);
    Eigen::Index failed = 0, first_failed = BatchResult::npos;
    StatusCode first_code = StatusCode::ok;
    for (Eigen::Index k = 0; k < N; ++k) {
        InverseDynamicsDerivatives d;
        const Status status = inverseDynamicsDerivatives(model, data, p.row(k).transpose(), dp.row(k).transpose(),
                                                         ddp.row(k).transpose(), d);
        if (!status && failed++ == 0) {
            first_failed = k;
            first_code = status.code;
        }
        for (int a = 0; a < n; ++a) {
            for (int i = 0; i < 3; ++i) {
                if (!status) {
                    EXPECT_TRUE(std::isnan(d_p(k, 3 * a + i)));
                    continue;
                }
                EXPECT_EQ(d_p(k, 3 * a + i), d.d_p(a, i));
                EXPECT_EQ(d_dp(k, 3 * a + i), d.d_dp(a, i));
                EXPECT_EQ(d_ddp(k, 3 * a + i), d.d_ddp(a, i));
            }
        }
    }
    EXPECT_GE(failed, 1);
    EXPECT_EQ(result.failed, failed);
    EXPECT_EQ(result.first_failure, first_failed);
    EXPECT_EQ(result.status.code, first_code);
}

/// The outputs of actuatorVariableDerivativesBatch, allocated for N samples of n actuators.
struct ActuatorBatchArrays {
    std::array<Eigen::ArrayXXd, 3> values;     // u, du, ddu: N x n
    std::array<Eigen::ArrayXXd, 6> jacobians;  // u_p, du_p, du_dp, ddu_p, ddu_dp, ddu_ddp: N x 3n
    std::vector<Status> status;

    ActuatorBatchArrays(Eigen::Index N, int n) : status(static_cast<std::size_t>(N)) {
        for (auto& v : values) v.resize(N, n);
        for (auto& j : jacobians) j.resize(N, 3 * n);
    }
    BatchResult run(const Model& model, unsigned threads, PoseColumns order, const Eigen::ArrayXXd& p,
                    const Eigen::ArrayXXd& dp, const Eigen::ArrayXXd& ddp) {
        auto& [u, du, ddu] = values;
        auto& [u_p, du_p, du_dp, ddu_p, ddu_dp, ddu_ddp] = jacobians;
        return actuatorVariableDerivativesBatch(
            model, p, dp, ddp, {u, du, ddu, u_p, du_p, du_dp, ddu_p, ddu_dp, ddu_ddp, status}, threads, order);
    }
};

/// Equal to the bit, NaN included.
bool sameBits(const Eigen::ArrayXXd& a, const Eigen::ArrayXXd& b) {
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST_P(DerivativesRandomRobots, ActuatorVariableDerivativesBatchEqualsSampleBySample) {
    const BatchCase c = batchCase(GetParam());
    ASSERT_TRUE(c.model.has_value());
    const Model& model = *c.model;
    const Eigen::Index N = c.p.rows();
    const int n = model.actuators;
    ActuatorBatchArrays one(N, n), two(N, n);
    const BatchResult result = one.run(model, 1, PoseColumns::theta_x_y, c.p, c.dp, c.ddp);
    const BatchResult threaded = two.run(model, 2, PoseColumns::theta_x_y, c.p, c.dp, c.ddp);
    // threads change nothing: every output to the bit, and the outcome
    for (std::size_t v = 0; v < 3; ++v) EXPECT_TRUE(sameBits(one.values[v], two.values[v])) << v;
    for (std::size_t j = 0; j < 6; ++j) EXPECT_TRUE(sameBits(one.jacobians[j], two.jacobians[j])) << j;
    EXPECT_EQ(threaded.failed, result.failed);
    EXPECT_EQ(threaded.first_failure, result.first_failure);
    // each row is actuatorVariableDerivatives' own, each status that sample's
    Data data(model);
    Eigen::Index failed = 0, first_failed = BatchResult::npos;
    for (Eigen::Index k = 0; k < N; ++k) {
        ActuatorVariableDerivatives d;
        const Status status = actuatorVariableDerivatives(model, data, c.p.row(k).transpose(), c.dp.row(k).transpose(),
                                                          c.ddp.row(k).transpose(), d);
        EXPECT_EQ(one.status[static_cast<std::size_t>(k)].code, status.code) << k;
        EXPECT_EQ(two.status[static_cast<std::size_t>(k)].code, status.code) << k;
        if (!status && failed++ == 0) first_failed = k;
        const std::array<const ActuatorVector*, 3> values{&d.u, &d.du, &d.ddu};
        const std::array<const ActuatorPoseJacobian*, 6> jacobians{&d.u_p,   &d.du_p,   &d.du_dp,
                                                                   &d.ddu_p, &d.ddu_dp, &d.ddu_ddp};
        for (int a = 0; a < n; ++a) {
            for (std::size_t v = 0; v < 3; ++v) {
                if (status)
                    EXPECT_EQ(one.values[v](k, a), (*values[v])(a));
                else
                    EXPECT_TRUE(std::isnan(one.values[v](k, a)));
            }
            for (std::size_t j = 0; j < 6; ++j) {
                for (int i = 0; i < 3; ++i) {
                    if (status)
                        EXPECT_EQ(one.jacobians[j](k, 3 * a + i), (*jacobians[j])(a, i));
                    else
                        EXPECT_TRUE(std::isnan(one.jacobians[j](k, 3 * a + i)));
                }
            }
        }
    }
    EXPECT_GE(failed, 1);
    EXPECT_EQ(result.failed, failed);
    EXPECT_EQ(result.first_failure, first_failed);
    // the tables' pose order [x, y, theta]: the inputs' and the derivatives' columns permuted alike
    const auto permuted = [](const Eigen::ArrayXXd& a) {
        Eigen::ArrayXXd b(a.rows(), 3);
        for (int i = 0; i < 3; ++i) b.col(poseColumn(PoseColumns::x_y_theta, i)) = a.col(i);
        return b;
    };
    ActuatorBatchArrays xyt(N, n);
    (void)xyt.run(model, 1, PoseColumns::x_y_theta, permuted(c.p), permuted(c.dp), permuted(c.ddp));
    for (std::size_t v = 0; v < 3; ++v) EXPECT_TRUE(sameBits(xyt.values[v], one.values[v])) << v;
    for (std::size_t j = 0; j < 6; ++j) {
        for (int a = 0; a < n; ++a) {
            for (int i = 0; i < 3; ++i) {
                const Eigen::ArrayXd theirs = one.jacobians[j].col(3 * a + i);
                const Eigen::ArrayXd mine = xyt.jacobians[j].col(3 * a + poseColumn(PoseColumns::x_y_theta, i));
                EXPECT_TRUE(sameBits(mine, theirs)) << j << " " << a << " " << i;
            }
        }
    }
}

TEST(Derivatives, ActuatorVariableBatchNamesAWrongShape) {
    std::mt19937 rng(5);
    std::optional<RobotDescription> description;
    while (!description) description = randomRobot({{"RRR", "RRR", "RRR"}, 3, true, false}, rng);
    const Model model(*description);
    Eigen::ArrayXXd p = Eigen::ArrayXXd::Zero(4, 3), u(4, 3), wrong(4, 8);
    try {
        (void)actuatorVariableDerivativesBatch(model, p, p, p, {u, u, u, wrong, wrong, wrong, wrong, wrong, wrong});
        FAIL() << "a 4 x 8 derivative output was accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "actuatorVariableDerivativesBatch: u_p is 4 x 8, expected 4 x 9");
    }
}

TEST_P(DerivativesRandomRobots, ActuatorVariableDerivativesEqualFiniteDifferences) {
    Agreement agreement;
    forEachSample([&](const Model& model, const Sample& s) {
        Data data(model), probe(model);
        ActuatorVariableDerivatives d;
        ASSERT_TRUE(actuatorVariableDerivatives(model, data, s.p, s.dp, s.ddp, d).ok()) << where(s);
        ASSERT_TRUE(inverseDynamics(model, probe, s.p, s.dp, s.ddp).ok());
        // the values are inverseDynamics' own
        const std::array<std::pair<const ActuatorVector*, const ActuatorVector*>, 3> values{
            {{&d.u, &probe.u}, {&d.du, &probe.du}, {&d.ddu, &probe.ddu}}};
        std::array<double, 3> floor{};
        for (std::size_t v = 0; v < 3; ++v) {
            const Eigen::VectorXd mine = *values[v].first, theirs = *values[v].second;
            EXPECT_LE((mine - theirs).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + theirs.cwiseAbs().maxCoeff()));
            floor[v] = 1e-3 * (1.0 + theirs.cwiseAbs().maxCoeff());
        }
        // (output u/du/ddu, input p/dp/ddp): the six derivatives that are not identically zero
        struct Pair {
            int output, input;
            const ActuatorPoseJacobian* exact;
            const char* name;
        };
        const std::array<Pair, 6> pairs{{{0, 0, &d.u_p, "d u/d p"},
                                         {1, 0, &d.du_p, "d du/d p"},
                                         {1, 1, &d.du_dp, "d du/d dp"},
                                         {2, 0, &d.ddu_p, "d ddu/d p"},
                                         {2, 1, &d.ddu_dp, "d ddu/d dp"},
                                         {2, 2, &d.ddu_ddp, "d ddu/d ddp"}}};
        for (const Pair& pair : pairs) {
            const auto f = [&](int i, double h) -> Eigen::VectorXd {
                Sample t = s;
                (pair.input == 0 ? t.p : pair.input == 1 ? t.dp : t.ddp)(i) += h;
                EXPECT_TRUE(inverseDynamics(model, probe, t.p, t.dp, t.ddp).ok());
                return pair.output == 0 ? probe.u : (pair.output == 1 ? probe.du : probe.ddu);
            };
            const double fl = floor[static_cast<std::size_t>(pair.output)];
            expectFiniteDifferences(Eigen::MatrixXd(*pair.exact), kStep, fl, fl, f, agreement,
                                    std::string(pair.name) + " of " + label(GetParam()) + " at " + where(s));
        }
    });
    EXPECT_GT(agreement.matrices, 0);
    agreement.report(label(GetParam()), "d(u, du, ddu)/d(p, dp, ddp)");
}

TEST_P(DerivativesRandomRobots, ActuatorRateAndAccelerationAreLinearWithTheActuationMap) {
    forEachSample([&](const Model& model, const Sample& s) {
        Data data(model);
        ActuatorVariableDerivatives d;
        ASSERT_TRUE(actuatorVariableDerivatives(model, data, s.p, s.dp, s.ddp, d).ok());
        // d du/d dp = d ddu/d ddp = d u/d p: the dual slots of gamma_dot and gamma_ddot against
        // A S(c) of the velocity stage
        const Eigen::MatrixXd u_p(d.u_p), du_dp(d.du_dp), ddu_ddp(d.ddu_ddp);
        const double scale = u_p.cwiseAbs().maxCoeff();
        EXPECT_LE((du_dp - u_p).cwiseAbs().maxCoeff(), 1e-12 * scale) << label(GetParam()) << "\n" << du_dp;
        EXPECT_LE((ddu_ddp - u_p).cwiseAbs().maxCoeff(), 1e-12 * scale) << label(GetParam()) << "\n" << ddu_ddp;
        // and du = (d u/d p) dp (du is linear in dp)
        EXPECT_LE((Eigen::VectorXd(d.du) - u_p * s.dp).cwiseAbs().maxCoeff(),
                  1e-12 * (1.0 + Eigen::VectorXd(d.du).cwiseAbs().maxCoeff()));
    });
}

INSTANTIATE_TEST_SUITE_P(EveryLimbType, DerivativesRandomRobots, ::testing::ValuesIn(specs()), testName);

TEST(Derivatives, CoulombFrictionAtRestContributesNeitherForceNorDerivative) {
    std::mt19937 rng(5);
    std::optional<RobotDescription> description;
    while (!description) description = randomRobot({{"PRR", "PRR", "PRR"}, 3, false, true}, rng);
    RobotDescription frictionless = *description;
    for (LimbDescription& limb : frictionless.limbs) {
        for (JointDescription& joint : limb.joints) joint.friction = 0.0;
    }
    const Model model(*description), reference(frictionless);
    Data data(model), data_ref(reference);
    const Pose p = description->home;
    const Twist ddp(0.3, 0.1, -0.2);
    InverseDynamicsDerivatives d, d_ref;
    ASSERT_TRUE(inverseDynamicsDerivatives(model, data, p, Twist::Zero(), ddp, d).ok());
    ASSERT_TRUE(inverseDynamicsDerivatives(reference, data_ref, p, Twist::Zero(), ddp, d_ref).ok());
    // at rest, sign 0 = 0: the Coulomb force and its derivative are those of no friction
    EXPECT_LE((Eigen::VectorXd(d.tau) - Eigen::VectorXd(d_ref.tau)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE((Eigen::MatrixXd(d.d_p) - Eigen::MatrixXd(d_ref.d_p)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE((Eigen::MatrixXd(d.d_dp) - Eigen::MatrixXd(d_ref.d_dp)).cwiseAbs().maxCoeff(), 1e-12);
    // while moving, the Coulomb force is there (the robots differ)
    ASSERT_TRUE(inverseDynamicsDerivatives(model, data, p, Twist(0.5, 0.02, -0.01), ddp, d).ok());
    ASSERT_TRUE(inverseDynamicsDerivatives(reference, data_ref, p, Twist(0.5, 0.02, -0.01), ddp, d_ref).ok());
    EXPECT_GT((Eigen::VectorXd(d.tau) - Eigen::VectorXd(d_ref.tau)).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(Derivatives, BadInputGivesTheStatusOfInverseDynamics) {
    std::mt19937 rng(5);
    std::optional<RobotDescription> description;
    while (!description) description = randomRobot({{"RRR", "RRR", "RRR"}, 3, true, false}, rng);
    const Model model(*description);
    Data data(model);
    InverseDynamicsDerivatives d;
    const Pose far(0.0, 5.0, 0.0);
    EXPECT_EQ(inverseDynamicsDerivatives(model, data, far, Twist::Zero(), Twist::Zero(), d).code,
              StatusCode::unreachable);
    const Twist nan(std::nan(""), 0.0, 0.0);
    EXPECT_EQ(inverseDynamicsDerivatives(model, data, description->home, Twist::Zero(), nan, d).code,
              StatusCode::not_finite);
    ForwardDynamicsDerivatives f;
    ActuatorVector tau = ActuatorVector::Zero(model.actuators);
    tau(1) = std::nan("");
    EXPECT_EQ(forwardDynamicsDerivatives(model, data, description->home, Twist::Zero(), tau, f).code,
              StatusCode::not_finite);
    ActuatorVariableDerivatives u;
    EXPECT_EQ(actuatorVariableDerivatives(model, data, far, Twist::Zero(), Twist::Zero(), u).code,
              StatusCode::unreachable);
    EXPECT_EQ(actuatorVariableDerivatives(model, data, description->home, Twist::Zero(), nan, u).code,
              StatusCode::not_finite);
}

}  // namespace
}  // namespace nocdyn::test
