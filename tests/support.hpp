// Shared test helpers: named tolerances, random poses across the workspace of any robot, the
// whole per-sample path, the paper robot's forward singularity, golden files.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "nocdyn/io/short_form.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "random_robots.hpp"

namespace nocdyn::test {

/// |a - b| <= abs + rel * |b|
struct Tolerance {
    double abs;
    double rel;
    [[nodiscard]] bool accepts(double a, double b) const { return std::abs(a - b) <= abs + rel * std::abs(b); }
};

inline std::string describePose(const Pose& p) {
    std::ostringstream out;
    out.precision(17);
    out << "pose [theta, x, y] = [" << p(0) << ", " << p(1) << ", " << p(2) << "]";
    return out.str();
}

/// "robot NAME, pose [...]": how failure messages name the case.
inline std::string describeCase(const Model& model, const Pose& p) {
    return "robot " + model.description.name + ", " + describePose(p);
}

/// Random poses spread across the reachable workspace of `model` around its home pose (rotation
/// up to +-angle, centre within +-position; by default +-0.35 rad and +-60 mm, the paper's
/// workspace), accepted by the position and velocity stages with every limb Jacobian and the
/// actuation map conditioned better than 1e3; deterministic per seed. A pose that takes more
/// than kMaxAttempts draws fails the test.
class WorkspaceSampler {
public:
    static constexpr int kMaxAttempts = 1000000;

    explicit WorkspaceSampler(const Model& model, unsigned seed = 2024, double angle = 0.35, double position = 0.06)
        : model_(model), data_(model), rng_(seed), angle_(-angle, angle), position_(-position, position) {}

    /// Next pose accepted by the position and velocity stages (home when none is found).
    Pose next() {
        for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
            // one draw a statement: a call's arguments are evaluated in an order GCC and clang
            // do not share, and the poses must not depend on the compiler (y, x, theta: GCC 12's
            // order for the former Pose(angle, position, position))
            const double y = position_(rng_);
            const double x = position_(rng_);
            const double theta = angle_(rng_);
            const Pose p = model_.home + Pose(theta, x, y);
            if (!inverseDisplacement(model_, data_, p)) continue;
            if (!velocityFromPlatformTwist(model_, data_, Twist::Zero())) continue;
            if (data_.cond_A > 1e3) continue;
            bool regular = true;
            for (int j = 0; j < model_.limbs; ++j)
                regular = regular && data_.limb[static_cast<std::size_t>(j)].cond <= 1e3;
            if (regular) return p;
        }
        ADD_FAILURE() << "robot " << model_.description.name << ": no regular pose in " << kMaxAttempts << " draws";
        return model_.home;
    }

    /// A random platform twist: up to +-5 rad/s and +-1 m/s.
    Twist twist() {
        std::uniform_real_distribution<double> w(-5.0, 5.0), v(-1.0, 1.0);
        return {w(rng_), v(rng_), v(rng_)};
    }

    std::mt19937& rng() { return rng_; }

private:
    const Model& model_;
    Data data_;
    std::mt19937 rng_;
    std::uniform_real_distribution<double> angle_, position_;
};

/// A robot under test and the box of poses around its home that its WorkspaceSampler draws.
struct RobotCase {
    std::string name;
    std::unique_ptr<Model> model;
    double angle, position;  ///< half-widths of the box [rad, m]
};

/// The example robots (in the paper's workspace box), then `per_type` random robots of every
/// limb type (three limbs, three actuators at random joints; a box of +-0.1 rad, +-10 mm).
inline std::vector<RobotCase> exampleAndRandomRobots(int per_type, unsigned seed) {
    std::vector<RobotCase> out;
    for (const std::string& name : io::exampleRobotNames()) {
        out.push_back({name, std::make_unique<Model>(io::exampleRobot(name)), 0.35, 0.06});
    }
    for (const std::string& type : limbTypes()) {
        std::mt19937 rng(seed);
        int kept = 0;
        for (int tried = 0; kept < per_type && tried < 100; ++tried) {
            const auto robot = randomRobot({{type, type, type}, 3, false, false}, rng);
            if (!robot) continue;
            ++kept;
            out.push_back({"random " + type + " #" + std::to_string(kept), std::make_unique<Model>(*robot), 0.1, 0.01});
        }
        EXPECT_EQ(kept, per_type) << "random robots of type " << type;
    }
    return out;
}

/// Calls check(c, p, sampler) at `poses` regular poses p of every case (a WorkspaceSampler of
/// the case's box, seeded with `seed`, which check may draw twists from); check returns whether
/// it checked the pose (false: not applicable to this robot). Returns how many it checked.
template <class Check>
int forEachPose(const std::vector<RobotCase>& cases, int poses, Check check, unsigned seed = 2024) {
    int checked = 0;
    for (const RobotCase& c : cases) {
        WorkspaceSampler sampler(*c.model, seed, c.angle, c.position);
        for (int k = 0; k < poses; ++k) {
            const Pose p = sampler.next();
            checked += check(c, p, sampler) ? 1 : 0;
        }
    }
    return checked;
}

/// Fourth-order central difference of f at 0, (8 (f(h) - f(-h)) - (f(2h) - f(-2h))) / (12 h):
/// truncation O(h^4), for quantities whose second derivatives are large near singularities.
template <class F>
auto centralDifference(F f, double h) {
    return ((8.0 * (f(h) - f(-h)) - (f(2.0 * h) - f(-2.0 * h))) / (12.0 * h)).eval();
}

/// Runs the whole per-sample path; fails the test (with the robot and pose) when it does not
/// succeed.
inline void solve(const Model& model, Data& data, const Pose& p, const Twist& dp, const Twist& ddp) {
    const Status status = inverseDynamics(model, data, p, dp, ddp);
    ASSERT_TRUE(status.ok()) << describeCase(model, p) << ": " << describe(status, model);
}

/// The paper's robot with every condition number accepted (the largest max_condition a
/// description may have), to walk up to its singularities.
inline Model permissivePaperRobot() {
    RobotDescription robot = io::exampleRobot("paper-3prr-general");
    robot.max_condition = 1e12;
    return Model(robot);
}

/// The platform rotation about O (C = O) at which the three link lines of the paper's robot
/// meet at C, so that h_j1 = 0 (eq. 7) and the actuation map du = A xi_P (eq. 5) is singular:
/// near theta = -2.08 rad, where phi_Mj = pi/6. Found by bisection on det A.
inline double concurrentLinkLinesRotation() {
    const Model probe = permissivePaperRobot();
    Data data(probe);
    auto det = [&](double theta) {
        EXPECT_TRUE(inverseDisplacement(probe, data, Pose(theta, 0.0, 0.0)).ok()) << "theta = " << theta;
        (void)velocityFromPlatformTwist(probe, data, Twist::Zero());
        return Matrix3(data.A.topRows<3>()).determinant();
    };
    double lo = -2.6, hi = -1.5;
    EXPECT_LT(det(lo) * det(hi), 0.0);
    for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
        const double mid = 0.5 * (lo + hi);
        (det(lo) * det(mid) <= 0.0 ? hi : lo) = mid;
    }
    return lo;
}

/// The paper's 3-PRR written from its equations (eqs. 8, 32, 35, 37-41), independent of the
/// model code: rail directions e_j and inward normals n_j = E e_j, base vertices B_j, platform
/// vertices M_j - C at theta = 0, and the origin s_ref_j of u_j (the reference posture).
struct PaperGeometry {
    explicit PaperGeometry(const io::RobotParameters& robot = io::RobotParameters{})
        : l(robot.link_length), stroke(robot.stroke), max_condition(robot.max_condition) {
        const double R = robot.base_side / std::sqrt(3.0), r = robot.platform_side / std::sqrt(3.0);
        for (std::size_t j = 0; j < 3; ++j) {
            const double phi = std::array<double, 3>{0.0, 2.0, -2.0}[j] * std::numbers::pi / 3.0;  // eq. 8
            const double vertex = phi - std::numbers::pi / 6.0;
            e[j] = Vector2(std::cos(phi), std::sin(phi));                  // eq. 40
            n[j] = perp(e[j]);                                             // into the base triangle
            B[j] = R * Vector2(std::cos(vertex), std::sin(vertex));        // eq. 35
            M_local[j] = r * Vector2(std::cos(vertex), std::sin(vertex));  // eq. 41
        }
        const Vector3 u = actuators(Pose::Zero()).value_or(Vector3::Constant(NAN));
        for (std::size_t j = 0; j < 3; ++j) s_ref[j] = u(static_cast<Eigen::Index>(j));
    }

    /// e_j . (A_j - B_j) - s_ref_j at pose p (eqs. 37-40), or nothing when a limb cannot reach
    /// (d_j^M not in (0, l)) or D is conditioned worse than max_condition (eq. 6).
    [[nodiscard]] std::optional<Vector3> actuators(const Pose& p) const {
        Vector3 u, cos_A;
        for (std::size_t j = 0; j < 3; ++j) {
            const auto i = static_cast<Eigen::Index>(j);
            const Vector2 M = p.tail<2>() + Eigen::Rotation2Dd(p(0)) * M_local[j];
            const double d = n[j].dot(M - B[j]);
            if (!(d > 0.0 && d < l)) return std::nullopt;
            cos_A(i) = std::sqrt(1.0 - (d / l) * (d / l));
            const Vector2 A = M - l * (cos_A(i) * e[j] + (d / l) * n[j]);
            u(i) = e[j].dot(A - B[j]) - s_ref[j];
        }
        if (!(cos_A.maxCoeff() <= max_condition * cos_A.minCoeff())) return std::nullopt;
        return u;
    }

    std::array<Vector2, 3> e{}, n{}, B{}, M_local{};
    std::array<double, 3> s_ref{};
    double l, stroke, max_condition;
};

inline std::string goldenPath(const std::string& file) { return std::string(NOCDYN_GOLDEN_DIR) + "/" + file; }

}  // namespace nocdyn::test
