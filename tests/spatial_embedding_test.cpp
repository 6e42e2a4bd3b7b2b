// The planar robots written in spatial form (spatial_embedding.hpp: each limb's planar joints,
// then an actuated P along z and a U about x and y) give the planar results on a motion that
// stays in the plane (z = 0, roll = pitch = 0, yaw = theta): the spatial model's in-plane
// actuators the planar model's forces, displacements, rates and accelerations (redundant 4-RRR:
// the minimum-norm forces, the two blocks decoupling), the z actuators no force with gravity in
// the plane, and the platform's weight with gravity along -z (sum f_j = m g, sum f_j y_j =
// m g y_c, sum f_j x_j = m g x_c, the moments about x and y of the vertical forces at the U
// points; with four limbs the minimum-norm f), the planar ones then the planar forces without
// gravity. The spatial files are read
// by the spatial reader (the schema's path); the planar robots are the shipped files and random
// robots of every limb type.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/spatial.hpp"
#include "random_robots.hpp"
#include "robot_files.hpp"
#include "spatial_embedding.hpp"

namespace nocdyn::test {
namespace {

constexpr int kSamples = 200;
constexpr double kStep = 0.005;       // [s]: 1 s of a 2-12 Hz two-harmonic motion per axis
constexpr double kAgreement = 1e-10;  // of the peak planar value

/// The largest differences over the trajectory, each relative to the peak planar value.
struct Agreement {
    double tau = 0.0, u = 0.0, du = 0.0, ddu = 0.0;
    double lift = 0.0;      ///< the z actuators: |f_j| (in-plane gravity) or the weight's residuals, over m g
    double peak_tau = 0.0;  ///< the planar forces' peak
    bool planar_ok = true;  ///< the planar model followed the whole trajectory
    [[nodiscard]] double worst() const { return std::max({tau, u, du, ddu}); }
};

/// Planar and spatial inverse dynamics along the same in-plane motion.
Agreement compare(const RobotDescription& planar, const EmbeddingOptions& options) {
    RobotDescription reference = planar;
    if (options.gravity == EmbeddedGravity::vertical) reference.gravity.setZero();
    const SpatialEmbedding embedding = spatialEmbedding(reference, options);
    const spatial::Model smodel(io::parseSpatialRobotDescription(embedding.yaml, planar.name + "-spatial.yaml"));
    spatial::Data sdata(smodel);
    const Model model(reference);
    Data data(model);
    EXPECT_EQ(smodel.actuators, model.actuators + model.limbs);

    std::mt19937 rng(20261130);
    const PoseTrajectory trajectory = trajectoryAround(reference.home, rng);
    const double weight = reference.platform.mass * options.g;
    Agreement a;
    double peak_u = 0.0, peak_du = 0.0, peak_ddu = 0.0;
    for (int k = 0; k < kSamples; ++k) {
        Pose p, dp, ddp;  // [theta, x, y]
        trajectory.evaluate(k * kStep, p, dp, ddp);
        if (!inverseDynamics(model, data, p, dp, ddp).ok()) {
            a.planar_ok = false;  // a random robot's trajectory out of its reach: no reference
            return a;
        }
        spatial::TaskVector sp(6), sdp(6), sddp(6);
        sp << p(1), p(2), 0.0, 0.0, 0.0, p(0);
        sdp << dp(1), dp(2), 0.0, 0.0, 0.0, dp(0);
        sddp << ddp(1), ddp(2), 0.0, 0.0, 0.0, ddp(0);
        const Status sstatus = spatial::inverseDynamics(smodel, sdata, sp, sdp, sddp);
        EXPECT_TRUE(sstatus.ok()) << spatial::describe(sstatus, smodel) << " at sample " << k;
        for (int i = 0; i < model.actuators; ++i) {
            const int s = embedding.in_plane[static_cast<std::size_t>(i)];
            a.peak_tau = std::max(a.peak_tau, std::abs(data.tau(i)));
            peak_u = std::max(peak_u, std::abs(data.u(i)));
            peak_du = std::max(peak_du, std::abs(data.du(i)));
            peak_ddu = std::max(peak_ddu, std::abs(data.ddu(i)));
            a.tau = std::max(a.tau, std::abs(sdata.tau(s) - data.tau(i)));
            a.u = std::max(a.u, std::abs(sdata.u(s) - data.u(i)));
            a.du = std::max(a.du, std::abs(sdata.du(s) - data.du(i)));
            a.ddu = std::max(a.ddu, std::abs(sdata.ddu(s) - data.ddu(i)));
        }
        // the z actuators: no motion along their freedoms
        for (const int s : embedding.lift) {
            a.u = std::max(a.u, std::abs(sdata.u(s)));
            a.du = std::max(a.du, std::abs(sdata.du(s)));
            a.ddu = std::max(a.ddu, std::abs(sdata.ddu(s)));
        }
        if (options.gravity == EmbeddedGravity::in_plane) {
            for (const int s : embedding.lift) a.lift = std::max(a.lift, std::abs(sdata.tau(s)));
        } else {
            // the vertical forces f_j at the U points x_j (fixed in the platform while the U's
            // angles stay 0) hold the weight at the c.o.m. c: B f = m g [1, x_c, y_c] with B's
            // columns [1, x_j, y_j] (force and moments about x and y); f = B^T (B B^T)^-1 m g
            // [1, x_c, y_c], the only solution with three limbs and the minimum-norm one with more
            const Eigen::Matrix2d R = Eigen::Rotation2Dd(p(0) - reference.home(0)).toRotationMatrix();
            const Eigen::Vector2d C0(reference.home(1), reference.home(2)), C(p(1), p(2));
            const Eigen::Vector2d c = C + Eigen::Rotation2Dd(p(0)).toRotationMatrix() * reference.platform.com;
            const auto n = static_cast<Eigen::Index>(embedding.lift.size());
            Eigen::MatrixXd B(3, n);
            for (Eigen::Index j = 0; j < n; ++j) {
                const Eigen::Vector2d x = C + R * (embeddingPoint(reference.limbs[static_cast<std::size_t>(j)]) - C0);
                B.col(j) << 1.0, x.x(), x.y();
            }
            const Eigen::VectorXd f =
                B.transpose() * (B * B.transpose()).ldlt().solve(weight * Eigen::Vector3d(1.0, c.x(), c.y()));
            double residual = 0.0;
            for (Eigen::Index j = 0; j < n; ++j) {
                residual = std::max(residual, std::abs(sdata.tau(embedding.lift[static_cast<std::size_t>(j)]) - f(j)));
            }
            a.lift = std::max(a.lift, residual / weight);
        }
    }
    a.tau /= a.peak_tau;
    a.u /= peak_u;
    a.du /= peak_du;
    a.ddu /= peak_ddu;
    if (options.gravity == EmbeddedGravity::in_plane) a.lift /= a.peak_tau;
    return a;
}

/// The planar robot in a vertical plane with friction at every joint: gravity and friction
/// carried over too.
RobotDescription loaded(RobotDescription robot) {
    robot.gravity = Eigen::Vector2d(1.5, -9.81);
    for (LimbDescription& limb : robot.limbs) {
        for (JointDescription& joint : limb.joints) {
            joint.damping = joint.type == JointType::revolute ? 0.05 : 20.0;
            joint.friction = joint.type == JointType::revolute ? 0.02 : 3.0;
        }
    }
    return robot;
}

void expectAgreement(const Agreement& a, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_TRUE(a.planar_ok);
    EXPECT_GT(a.peak_tau, 0.0);
    EXPECT_LT(a.tau, kAgreement);
    EXPECT_LT(a.u, kAgreement);
    EXPECT_LT(a.du, kAgreement);
    EXPECT_LT(a.ddu, kAgreement);
    EXPECT_LT(a.lift, kAgreement);
    std::printf("%-28s tau %.2e  u %.2e  du %.2e  ddu %.2e  z %.2e\n", what.c_str(), a.tau, a.u, a.du, a.ddu, a.lift);
}

class ShippedEmbedding : public ::testing::TestWithParam<const char*> {};

TEST_P(ShippedEmbedding, InPlaneGravityGivesThePlanarForces) {
    const RobotDescription robot = robotDescription(GetParam());
    expectAgreement(compare(robot, {}), std::string(GetParam()) + " as shipped");
    expectAgreement(compare(loaded(robot), {}), std::string(GetParam()) + " gravity+friction");
}

TEST_P(ShippedEmbedding, VerticalGravityOnTheZActuators) {
    EmbeddingOptions options;
    options.gravity = EmbeddedGravity::vertical;
    expectAgreement(compare(loaded(robotDescription(GetParam())), options), std::string(GetParam()) + " gravity -z");
}

INSTANTIATE_TEST_SUITE_P(Robots, ShippedEmbedding, ::testing::Values("paper-3prr", "3-rrr", "3-rpr", "4-rrr"),
                         [](const auto& info) {
                             std::string name = info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return "robot_" + name;
                         });

TEST(SpatialEmbedding, RandomPlanarRobotsOfEveryLimbType) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> pick(0, static_cast<int>(limbTypes().size()) - 1);
    int tested = 0;
    for (int attempt = 0; attempt < 60 && tested < sweepSize(8); ++attempt) {
        RandomRobotSpec spec;
        const int limbs = tested % 2 == 0 ? 3 : 4;
        for (int j = 0; j < limbs; ++j) spec.limb_types.push_back(limbTypes()[static_cast<std::size_t>(pick(rng))]);
        spec.actuators = limbs;
        spec.gravity = spec.friction = true;
        const auto robot = randomRobot(spec, rng);
        if (!robot) continue;
        const Agreement in_plane = compare(*robot, {});
        if (!in_plane.planar_ok) continue;
        std::string types;
        for (const LimbDescription& limb : robot->limbs) types.append(limb.type()).append(" ");
        expectAgreement(in_plane, "random " + types);
        EmbeddingOptions vertical;
        vertical.gravity = EmbeddedGravity::vertical;
        expectAgreement(compare(*robot, vertical), "random " + types + "-z");
        ++tested;
    }
    EXPECT_EQ(tested, sweepSize(8));
}

// The comparison can fail: one body's c.o.m. 1 mm off in the spatial file moves the forces far
// beyond the agreement above.
TEST(SpatialEmbedding, AComMovedByOneMillimetreIsSeen) {
    EmbeddingOptions options;
    options.com_shift = Eigen::Vector3d(0.001, 0.0, 0.0);
    const Agreement a = compare(loaded(robotDescription("3-rrr")), options);
    std::printf("3-rrr, com 1 mm off: tau %.2e of the peak\n", a.tau);
    EXPECT_GT(a.tau, 1e4 * kAgreement);
    EXPECT_LT(a.u, kAgreement);  // the kinematics does not see it
}

// The same for the z actuators: the platform's c.o.m. 1 mm off along x in the spatial file moves
// their forces away from the closed form of the file's planar robot.
TEST(SpatialEmbedding, APlatformComMovedByOneMillimetreIsSeenOnTheZActuators) {
    EmbeddingOptions options;
    options.gravity = EmbeddedGravity::vertical;
    options.platform_com_shift = Eigen::Vector3d(0.001, 0.0, 0.0);
    const Agreement a = compare(robotDescription("3-rrr"), options);
    std::printf("3-rrr, platform com 1 mm off: z actuators %.2e of m g\n", a.lift);
    EXPECT_GT(a.lift, 1e4 * kAgreement);
}

// The file has the planar robot's structure: six freedoms a limb, its planar joints first, the
// same masses (the added bodies massless), one z actuator a limb after its planar ones.
TEST(SpatialEmbedding, TheFileKeepsThePlanarRobot) {
    const RobotDescription planar = robotDescription("4-rrr");
    const SpatialEmbedding embedding = spatialEmbedding(planar);
    const SpatialRobotDescription spatial = io::parseSpatialRobotDescription(embedding.yaml, "4-rrr-spatial.yaml");
    ASSERT_EQ(spatial.limbs.size(), planar.limbs.size());
    double planar_mass = planar.platform.mass;
    for (std::size_t j = 0; j < planar.limbs.size(); ++j) {
        EXPECT_EQ(spatial.limbs[j].type(), planar.limbs[j].type() + "PU");
        EXPECT_EQ(spatial.limbs[j].freedoms(), 6);
        for (const BodyDescription& body : planar.limbs[j].bodies) planar_mass += body.mass;
        EXPECT_EQ(spatial.limbs[j].bodies[2].mass + spatial.limbs[j].bodies[3].mass, 0.0);
    }
    EXPECT_NEAR(spatial.totalMass(), planar_mass, 1e-15 * planar_mass);
    EXPECT_EQ(spatial.actuatorCount(), 8);
    EXPECT_EQ(embedding.in_plane, (std::vector<int>{0, 2, 4, 6}));
    EXPECT_EQ(embedding.lift, (std::vector<int>{1, 3, 5, 7}));
    EXPECT_EQ(spatial.home(5), planar.home(0));
}

}  // namespace
}  // namespace nocdyn::test
