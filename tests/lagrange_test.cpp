// The dynamics of random robots of every limb type against Lagrange's equations, with every
// quantity on the right-hand side computed independently of the NOC:
//   - each body's pose (angle, c.o.m.) from the limb's joint variables by the product of
//     exponentials of the robot description (the platform's from p and its c.o.m. in the
//     platform frame), its velocity from finite differences of that pose;
//   - the kinetic energy sum_i (m_i |dx_i/dt|^2 + I_i w_i^2) / 2 and the potential energy
//     -sum_i m_i g . x_i from the description's masses and inertias;
//   - joint friction damping q' + friction sign q' from the description's coefficients, with
//     q' from finite differences of the joint variables.
// Lagrange's equations are written in the platform pose p (every robot, redundant or not):
//   d/dt(dL/d(dp)) - dL/dp + Q_friction = A_p^T tau,
// the right-hand side being the generalized force of the actuators (virtual power
// tau . du = (A_p^T tau) . dp, A_p = du/dp by finite differences). With L = dp^T M(p) dp / 2 - V(p)
// and M(p) = sum_i G_i^T diag(I_i, m_i, m_i) G_i, G_i = d(pose_i)/dp:
//   M ddp + sum_k (dM/dp_k dp_k) dp - [dp^T dM/dp_k dp / 2]_k + dV/dp + Q_friction = A_p^T tau.
// Unlike the power balance (which sees only du^T C du, the same for C and C^T) this sees every
// component of tau, so it catches C in place of C^T and every mass, c.o.m. and inertia error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

#include "nocdyn/dynamics.hpp"
#include "random_robots.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

// Derivatives by the five-point central stencil (truncation O(h^4)). The robots' poses change
// over a few centimetres and a few tenths of a radian: a pose's derivative is exact to about
// 1e-11 at 1e-5 (rounding); dM/dp, one stencil over another, to about 1e-8 at 5e-5 (larger steps
// lose to truncation, smaller ones to rounding).
constexpr double kPoseStep = 1e-5;     // [rad or m] for d(pose)/dp
constexpr double kInertiaStep = 5e-5;  // [rad or m] for dM/dp
// Measured: |A_p^T tau - Lagrange| <= 1.4e-8 of the scale (the sum of the terms' largest
// components) on every robot below, on both paths (release and -O1 builds).
constexpr double kLagrangeTolerance = 1e-7;
// Measured: the model's energies and friction power agree with the independent sums to 7.7e-11
// of their magnitude.
constexpr double kEnergyTolerance = 1e-9;
// Joint rates closer to zero than this leave the sign of Coulomb friction to rounding: such
// a sample is not checked (counted, and few are allowed).
constexpr double kSmallestRate = 1e-6;
// Robots kept: regular along their trajectory (scaled condition numbers of every J_j and of A
// below this), as in model_test.
constexpr double kConditionLimit = 1e3;

Vector2 rotate(double a, const Vector2& v) {
    return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
}

/// Body poses and joint variables of a robot at one platform pose, from the model's inverse
/// displacement (the joint variables only) and the description (everything else).
struct Configuration {
    /// [angle, x, y] of every body: limb j's bodies at 6 j and 6 j + 3, the platform last.
    Eigen::VectorXd bodies;
    /// The joint variables, three per limb.
    Eigen::VectorXd joints;
};

class IndependentMechanics {
public:
    IndependentMechanics(const RobotDescription& robot, const Model& model)
        : robot_(robot), model_(model), data_(model) {
        limbs_ = static_cast<int>(robot.limbs.size());
        for (int j = 0; j < limbs_; ++j) {
            for (int k = 0; k < 3; ++k) {
                if (joint(j, k).actuated) actuated_.push_back(3 * j + k);
            }
        }
    }

    [[nodiscard]] int bodies() const { return 2 * limbs_ + 1; }
    [[nodiscard]] const std::vector<int>& actuated() const { return actuated_; }

    /// false when the model cannot place the robot at p.
    bool configuration(const Pose& p, Configuration& out) {
        if (!inverseDisplacement(model_, data_, p).ok()) return false;
        out.bodies.resize(3 * bodies());
        out.joints.resize(3 * limbs_);
        for (int j = 0; j < limbs_; ++j) {
            const Vector3 q = data_.limb[static_cast<std::size_t>(j)].q;
            out.joints.segment<3>(3 * j) = q;
            // product of exponentials: body 1 moves by exp(s_1 q_1), body 2 by exp(s_1 q_1) exp(s_2 q_2)
            double angle = 0.0;
            for (int b = 0; b < 2; ++b) {
                Vector2 x = body(j, b).com;
                for (int k = b; k >= 0; --k) x = displace(joint(j, k), q(k), x);
                if (joint(j, b).type == JointType::revolute) angle += q(b);
                out.bodies.segment<3>(6 * j + 3 * b) = Vector3(angle, x.x(), x.y());
            }
        }
        const Vector2 x_P = p.tail<2>() + rotate(p(0), robot_.platform.com);
        out.bodies.tail<3>() = Vector3(p(0), x_P.x(), x_P.y());
        return true;
    }

    /// d(bodies, joints)/dp by the five-point stencil; false when a pose fails.
    bool jacobian(const Pose& p, Eigen::MatrixXd& G_bodies, Eigen::MatrixXd& G_joints) {
        G_bodies.resize(3 * bodies(), 3);
        G_joints.resize(3 * limbs_, 3);
        Configuration c[4];
        const double steps[4] = {2.0, 1.0, -1.0, -2.0};
        for (int axis = 0; axis < 3; ++axis) {
            for (int s = 0; s < 4; ++s) {
                if (!configuration(p + steps[s] * kPoseStep * Pose::Unit(axis), c[s])) return false;
            }
            const auto derivative = [&](const Eigen::VectorXd Configuration::*field, bool angle) {
                Eigen::VectorXd d(c[0].*field - c[3].*field);
                Eigen::VectorXd e(c[1].*field - c[2].*field);
                if (angle) {
                    // angles may wrap between the samples: their differences are taken mod 2 pi
                    for (Eigen::Index i = 0; i < d.size(); ++i) {
                        d(i) = std::remainder(d(i), 2.0 * std::numbers::pi);
                        e(i) = std::remainder(e(i), 2.0 * std::numbers::pi);
                    }
                }
                return Eigen::VectorXd((8.0 * e - d) / (12.0 * kPoseStep));
            };
            const Eigen::VectorXd body_rows = derivative(&Configuration::bodies, false);
            const Eigen::VectorXd body_angles = derivative(&Configuration::bodies, true);
            const Eigen::VectorXd joint_rows = derivative(&Configuration::joints, false);
            const Eigen::VectorXd joint_angles = derivative(&Configuration::joints, true);
            for (int i = 0; i < bodies(); ++i) {
                G_bodies.col(axis).segment<3>(3 * i) = body_rows.segment<3>(3 * i);
                G_bodies(3 * i, axis) = body_angles(3 * i);
            }
            for (int i = 0; i < 3 * limbs_; ++i) {
                const bool revolute = joint(i / 3, i % 3).type == JointType::revolute;
                G_joints(i, axis) = revolute ? joint_angles(i) : joint_rows(i);
            }
        }
        return true;
    }

    /// M(p) = sum_i G_i^T diag(I_i, m_i, m_i) G_i.
    bool inertia(const Pose& p, Matrix3& M) {
        Eigen::MatrixXd G, G_joints;
        if (!jacobian(p, G, G_joints)) return false;
        M.setZero();
        for (int i = 0; i < bodies(); ++i) {
            const Eigen::Matrix<double, 3, 3> G_i = G.middleRows<3>(3 * i);
            M.noalias() += G_i.transpose() * dyad(i).asDiagonal() * G_i;
        }
        return true;
    }

    /// V(p) = -sum_i m_i g . x_i.
    bool potential(const Pose& p, double& V) {
        Configuration c;
        if (!configuration(p, c)) return false;
        V = 0.0;
        for (int i = 0; i < bodies(); ++i) V -= dyad(i)(1) * robot_.gravity.dot(c.bodies.segment<2>(3 * i + 1));
        return true;
    }

    /// The effort of joint k of limb j against its friction at rate q', from the file's
    /// coefficients: damping q' + friction sign q'.
    [[nodiscard]] double friction(int i, double rate) const {
        const JointDescription& jd = joint(i / 3, i % 3);
        return jd.damping * rate + jd.friction * (rate > 0.0 ? 1.0 : -1.0);
    }
    [[nodiscard]] bool hasCoulomb(int i) const { return joint(i / 3, i % 3).friction != 0.0; }

    /// [I_i, m_i, m_i] of body i.
    [[nodiscard]] Vector3 dyad(int i) const {
        if (i == bodies() - 1) return {robot_.platform.inertia, robot_.platform.mass, robot_.platform.mass};
        const BodyDescription& bd = body(i / 2, i % 2);
        return {bd.inertia, bd.mass, bd.mass};
    }

private:
    [[nodiscard]] const JointDescription& joint(int j, int k) const {
        return robot_.limbs[static_cast<std::size_t>(j)].joints[static_cast<std::size_t>(k)];
    }
    [[nodiscard]] const BodyDescription& body(int j, int b) const {
        return robot_.limbs[static_cast<std::size_t>(j)].bodies[static_cast<std::size_t>(b)];
    }
    /// A point carried by joint k's outboard body, moved by the joint: a turn about its axis
    /// or a slide along its direction (both given at home).
    static Vector2 displace(const JointDescription& jd, double q, const Vector2& x) {
        return jd.type == JointType::revolute ? Vector2(jd.point + rotate(q, x - jd.point))
                                              : Vector2(x + q * jd.direction);
    }

    const RobotDescription& robot_;
    const Model& model_;
    Data data_;
    int limbs_ = 0;
    std::vector<int> actuated_;  ///< 3 j + k of each actuator, in the model's order
};

/// Random robots of every limb type, with gravity, friction and off-axis c.o.m.s
/// (random_robots.hpp), three actuators and redundant ones.
std::vector<RandomRobotSpec> specs() {
    std::vector<RandomRobotSpec> out;
    for (const std::string& type : limbTypes()) {
        out.push_back({{type, type, type}, 3, true, true});
        out.push_back({{type, type, type, type}, 4, true, true});
    }
    out.push_back({{"RRR", "PRR", "RPR"}, 3, true, false});
    out.push_back({{"RRP", "PRP", "RPP", "PPR"}, 5, false, true});
    out.push_back({{"PRR", "RRR", "RPR", "RRR", "PRR"}, 6, true, true});
    // uniform limbs actuated at one joint: the lean kernel runs them in the lanes of a packet
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

class LagrangeRandomRobots : public ::testing::TestWithParam<RandomRobotSpec> {
protected:
    static constexpr int kRobots = 2;
    static constexpr int kSamples = 8;
    static constexpr double kDuration = 0.3;

    /// The first kRobots random robots of the spec that are regular along a random trajectory;
    /// check returns how many samples it checked, of which every robot needs kSamples - 1.
    void forEachRobot(
        const std::function<int(const RobotDescription&, const Model&, const std::vector<Sample>&)>& check) {
        std::mt19937 rng(11);
        int kept = 0, tried = 0;
        while (kept < kRobots && tried < 200) {
            ++tried;
            const auto description = randomRobot(GetParam(), rng);
            if (!description) continue;
            const Model model(*description);
            const PoseTrajectory trajectory = trajectoryAround(description->home, rng, 0.5);
            Data data(model);
            std::vector<Sample> samples;
            bool regular = true;
            for (int k = 0; k <= kSamples && regular; ++k) {
                Sample s;
                trajectory.evaluate(k * kDuration / kSamples, s.p, s.dp, s.ddp);
                regular = inverseDynamics(model, data, s.p, s.dp, s.ddp).ok() && data.cond_A < kConditionLimit;
                for (int j = 0; j < model.limbs; ++j)
                    regular = regular && data.limb[static_cast<std::size_t>(j)].cond < kConditionLimit;
                samples.push_back(s);
            }
            if (!regular) continue;
            ++kept;
            const int checked = check(*description, model, samples);
            EXPECT_GE(checked, kSamples) << label(GetParam()) << ", robot " << kept << ": only " << checked << " of "
                                         << samples.size() << " samples checked";
        }
        EXPECT_EQ(kept, kRobots) << label(GetParam()) << ": only " << kept << " regular robots in " << tried;
    }
};

std::string where(const RandomRobotSpec& spec, const Sample& s) {
    std::ostringstream out;
    out << label(spec) << ", " << describePose(s.p) << ", dp = [" << s.dp.transpose() << "], ddp = ["
        << s.ddp.transpose() << "]";
    return out.str();
}

TEST_P(LagrangeRandomRobots, LagrangeEquationsHoldByFiniteDifferences) {
    forEachRobot([](const RobotDescription& robot, const Model& model, const std::vector<Sample>& samples) {
        IndependentMechanics mechanics(robot, model);
        Data full(model), lean(model);
        int checked = 0;
        double worst = 0.0;
        for (const Sample& s : samples) {
            Eigen::MatrixXd G, G_joints;
            Matrix3 M;
            if (!mechanics.jacobian(s.p, G, G_joints) || !mechanics.inertia(s.p, M)) {
                ADD_FAILURE() << "the poses around the sample fail: " << where(GetParam(), s);
                continue;
            }
            // dM/dp_k and dV/dp by the five-point stencil
            std::array<Matrix3, 3> dM;
            Vector3 dV;
            const double steps[4] = {2.0, 1.0, -1.0, -2.0};
            bool ok = true;
            for (int axis = 0; axis < 3; ++axis) {
                Matrix3 M_s[4];
                double V_s[4];
                for (int k = 0; k < 4; ++k) {
                    const Pose p = s.p + steps[k] * kInertiaStep * Pose::Unit(axis);
                    ok = ok && mechanics.inertia(p, M_s[k]) && mechanics.potential(p, V_s[k]);
                }
                dM[static_cast<std::size_t>(axis)] =
                    (8.0 * (M_s[1] - M_s[2]) - (M_s[0] - M_s[3])) / (12.0 * kInertiaStep);
                dV(axis) = (8.0 * (V_s[1] - V_s[2]) - (V_s[0] - V_s[3])) / (12.0 * kInertiaStep);
            }
            if (!ok) {
                ADD_FAILURE() << "the poses around the sample fail: " << where(GetParam(), s);
                continue;
            }
            // joint rates and friction from the file's coefficients; a rate at zero leaves the
            // Coulomb sign to rounding
            const Eigen::VectorXd rates = G_joints * s.dp;
            bool ambiguous = false;
            Vector3 friction = Vector3::Zero();
            for (Eigen::Index i = 0; i < rates.size(); ++i) {
                const int ii = static_cast<int>(i);
                if (mechanics.hasCoulomb(ii) && std::abs(rates(i)) < kSmallestRate) ambiguous = true;
                friction += mechanics.friction(ii, rates(i)) * G_joints.row(i).transpose();
            }
            if (ambiguous) continue;
            Matrix3 M_dot = Matrix3::Zero();
            Vector3 centrifugal;
            for (int axis = 0; axis < 3; ++axis) {
                M_dot += dM[static_cast<std::size_t>(axis)] * s.dp(axis);
                centrifugal(axis) = 0.5 * s.dp.dot(dM[static_cast<std::size_t>(axis)] * s.dp);
            }
            const Vector3 inertial = M * s.ddp, coriolis = M_dot * s.dp;
            const Vector3 lagrange = inertial + coriolis - centrifugal + dV + friction;
            const double scale = 1e-3 + inertial.cwiseAbs().maxCoeff() + coriolis.cwiseAbs().maxCoeff() +
                                 centrifugal.cwiseAbs().maxCoeff() + dV.cwiseAbs().maxCoeff() +
                                 friction.cwiseAbs().maxCoeff();
            // A_p = du/dp: the actuated joints' rows
            Eigen::MatrixXd A_p(static_cast<Eigen::Index>(mechanics.actuated().size()), 3);
            for (std::size_t a = 0; a < mechanics.actuated().size(); ++a)
                A_p.row(static_cast<Eigen::Index>(a)) = G_joints.row(mechanics.actuated()[a]);
            if (!inverseDynamics(model, full, s.p, s.dp, s.ddp) ||
                !inverseDynamicsFast(model, lean, s.p, s.dp, s.ddp)) {
                ADD_FAILURE() << "the inverse dynamics fails: " << where(GetParam(), s);
                continue;
            }
            const Vector3 generalized_full = A_p.transpose() * Eigen::VectorXd(full.tau);
            const Vector3 generalized_lean = A_p.transpose() * Eigen::VectorXd(lean.tau);
            worst = std::max(worst, (generalized_full - lagrange).cwiseAbs().maxCoeff() / scale);
            worst = std::max(worst, (generalized_lean - lagrange).cwiseAbs().maxCoeff() / scale);
            for (int axis = 0; axis < 3; ++axis) {
                EXPECT_NEAR(generalized_full(axis), lagrange(axis), kLagrangeTolerance * scale)
                    << "full path, p component " << axis << ": " << where(GetParam(), s);
                EXPECT_NEAR(generalized_lean(axis), lagrange(axis), kLagrangeTolerance * scale)
                    << "lean path, p component " << axis << ": " << where(GetParam(), s);
            }
            ++checked;
        }
        std::printf("%s: Lagrange's equations hold to %.2g of the terms' scale\n", label(GetParam()).c_str(), worst);
        return checked;
    });
}

TEST_P(LagrangeRandomRobots, EnergiesAndFrictionPowerEqualIndependentSums) {
    // The model's kinetic and potential energy and friction power against dp^T M dp / 2, V and
    // sum (damping q'^2 + friction |q'|) from the description's coefficients.
    forEachRobot([](const RobotDescription& robot, const Model& model, const std::vector<Sample>& samples) {
        IndependentMechanics mechanics(robot, model);
        Data data(model);
        int checked = 0;
        double worst = 0.0;
        for (const Sample& s : samples) {
            Eigen::MatrixXd G, G_joints;
            Matrix3 M;
            double V = 0.0;
            if (!mechanics.jacobian(s.p, G, G_joints) || !mechanics.inertia(s.p, M) || !mechanics.potential(s.p, V) ||
                !inverseDynamics(model, data, s.p, s.dp, s.ddp)) {
                ADD_FAILURE() << "the sample fails: " << where(GetParam(), s);
                continue;
            }
            const Eigen::VectorXd rates = G_joints * s.dp;
            double friction_power = 0.0, friction_scale = 1e-6;
            for (Eigen::Index i = 0; i < rates.size(); ++i) {
                friction_power += mechanics.friction(static_cast<int>(i), rates(i)) * rates(i);
                friction_scale += std::abs(mechanics.friction(static_cast<int>(i), rates(i)) * rates(i));
            }
            const double kinetic = 0.5 * s.dp.dot(M * s.dp);
            double potential_scale = 1e-6;
            for (int i = 0; i < mechanics.bodies(); ++i) potential_scale += mechanics.dyad(i)(1) * robot.gravity.norm();
            worst = std::max({worst, std::abs(kineticEnergy(model, data) - kinetic) / kinetic,
                              std::abs(potentialEnergy(model, data) - V) / potential_scale,
                              std::abs(frictionPower(model, data) - friction_power) / friction_scale});
            EXPECT_NEAR(kineticEnergy(model, data), kinetic, kEnergyTolerance * kinetic) << where(GetParam(), s);
            EXPECT_NEAR(potentialEnergy(model, data), V, kEnergyTolerance * potential_scale) << where(GetParam(), s);
            EXPECT_NEAR(frictionPower(model, data), friction_power, kEnergyTolerance * friction_scale)
                << where(GetParam(), s);
            ++checked;
        }
        std::printf("%s: energies and friction power agree to %.2g\n", label(GetParam()).c_str(), worst);
        return checked;
    });
}

INSTANTIATE_TEST_SUITE_P(EveryLimbType, LagrangeRandomRobots, ::testing::ValuesIn(specs()), testName);

}  // namespace
}  // namespace nocdyn::test
