// Static stiffness and natural frequencies by the virtual joint method (analysis/stiffness.hpp):
// identities, finite differences of the springs' energy, an analytic cantilever-and-strut limb,
// the elastodynamic model condensed back onto the platform, and the robot file's fields.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "robot_files.hpp"

namespace nocdyn {
namespace {

std::string robotText(const std::string& robot) {
    return io::readRobotFileText(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + robot + ".yaml");
}

/// The paper's 3-PRR with drive springs k on its sliders (links rigid, passive joints free).
RobotDescription prrWithDriveSprings(const Eigen::Vector3d& k) {
    RobotDescription robot = robotDescription("paper-3prr-general");
    for (int j = 0; j < 3; ++j) robot.limbs[static_cast<std::size_t>(j)].joints[0].stiffness = k(j);
    return robot;
}

/// The 3-RPR with drive springs on its legs and flexure hinges at every pivot.
RobotDescription rprWithFlexures() {
    RobotDescription robot = robotDescription("3-rpr");
    const double drive[3] = {2.0e5, 2.5e5, 3.0e5};
    for (std::size_t j = 0; j < 3; ++j) {
        robot.limbs[j].joints[0].stiffness = 40.0 + 5.0 * static_cast<double>(j);
        robot.limbs[j].joints[1].stiffness = drive[j];
        robot.limbs[j].joints[2].stiffness = 25.0 + 3.0 * static_cast<double>(j);
    }
    return robot;
}

/// The 3-RRR with aluminium links (EA, EI of a 10 x 4 mm bar lying flat), motors locked.
RobotDescription rrrWithElasticLinks() {
    RobotDescription robot = robotDescription("3-rrr");
    for (LimbDescription& limb : robot.limbs) {
        limb.bodies[0].elastic = ElasticBeam{70e9 * 10e-3 * 4e-3, 70e9 * 4e-3 * std::pow(10e-3, 3) / 12.0};
        limb.bodies[1].elastic = ElasticBeam{70e9 * 8e-3 * 4e-3, 70e9 * 4e-3 * std::pow(8e-3, 3) / 12.0};
    }
    return robot;
}

struct AtPose {
    Model model;
    StiffnessModel compliance;
    Data data;
    StiffnessData K;
    LumpedModes modes;
    Status status;
    AtPose(RobotDescription robot, const Pose& p) : model(std::move(robot)), compliance(model), data(model) {
        status = stiffnessAndModes(model, compliance, data, p, K, modes);
    }
};

double relativeError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

/// D K D with D = diag(L, 1, 1): every entry in N/m, for comparisons that weigh them alike.
Matrix3 scaledK(const Matrix3& K, double L) {
    const Vector3 d(1.0 / L, 1.0, 1.0);
    return d.asDiagonal() * K * d.asDiagonal();
}

TEST(Stiffness, DriveSpringsAloneGiveATransposeDiagKA) {
    const Eigen::Vector3d k(1.0e5, 2.0e5, 3.0e5);
    for (const Pose& p : {Pose(0.0, 0.0, 0.0), Pose(0.03, 0.002, -0.003), Pose(-0.05, -0.004, 0.001)}) {
        AtPose at(prrWithDriveSprings(k), p);
        ASSERT_TRUE(at.status.ok()) << describe(at.status, at.model);
        const Matrix3 AS = Matrix3(at.data.A) * platformTwistMap(p.tail<2>());
        const Matrix3 expected = AS.transpose() * k.asDiagonal() * AS;
        EXPECT_LT(relativeError(scaledK(at.K.K, at.model.length_scale), scaledK(expected, at.model.length_scale)),
                  1e-12);
        EXPECT_EQ(at.K.free_directions, 0);
    }
}

TEST(Stiffness, DriveSpringsAloneGiveATransposeDiagKAOnThe3Rrr) {
    RobotDescription robot = robotDescription("3-rrr");
    const Eigen::Vector3d k(15.0, 20.0, 25.0);  // N m/rad: motors under a position loop
    for (int j = 0; j < 3; ++j) robot.limbs[static_cast<std::size_t>(j)].joints[0].stiffness = k(j);
    const Pose p(0.02, 0.003, -0.002);
    AtPose at(std::move(robot), p);
    ASSERT_TRUE(at.status.ok()) << describe(at.status, at.model);
    const Matrix3 AS = Matrix3(at.data.A) * platformTwistMap(p.tail<2>());
    const Matrix3 expected = AS.transpose() * k.asDiagonal() * AS;
    EXPECT_LT(relativeError(scaledK(at.K.K, at.model.length_scale), scaledK(expected, at.model.length_scale)), 1e-12);
}

TEST(Stiffness, IsSymmetricPositiveDefiniteOnTheThreeValidationRobots) {
    const Pose p(0.02, 0.002, 0.001);
    for (RobotDescription robot :
         {prrWithDriveSprings(Eigen::Vector3d(1e5, 1e5, 1e5)), rprWithFlexures(), rrrWithElasticLinks()}) {
        AtPose at(std::move(robot), p);
        ASSERT_TRUE(at.status.ok()) << describe(at.status, at.model);
        EXPECT_LT((at.K.K - at.K.K.transpose()).norm(), 1e-14 * at.K.K.norm());
        EXPECT_GT(at.K.scaled_eigenvalues(0), 0.0);
        EXPECT_EQ(at.K.free_directions, 0);
    }
}

TEST(Stiffness, AForceActuatorLeavesItsDirectionFreeAndNamed) {
    // stiffness 0 on actuator 1: the platform moves freely where u_1 moves alone
    const Pose p(0.01, 0.001, 0.002);
    AtPose at(prrWithDriveSprings(Eigen::Vector3d(0.0, 2e5, 3e5)), p);
    ASSERT_TRUE(at.status.ok());
    ASSERT_EQ(at.K.free_directions, 1);
    const Matrix3 AS = Matrix3(at.data.A) * platformTwistMap(p.tail<2>());
    const Vector3 expected = AS.inverse().col(0);
    const Vector3 free = at.K.free.col(0);
    EXPECT_NEAR(std::abs(free.dot(expected)) / expected.norm(), 1.0, 1e-9);
    EXPECT_LT((at.K.K * free).norm(), 1e-9 * at.K.K.norm());
    EXPECT_EQ(at.modes.frequency(0), 0.0);
    EXPECT_GT(at.modes.frequency(1), 1.0);
    // a load along the free direction has no equilibrium; one orthogonal to it has
    Vector3 dp;
    const Vector3 loading = free;  // f . dp_free != 0
    EXPECT_FALSE(displacementUnderWrench(at.K, at.model.length_scale, loading, dp));
    const Vector3 reachable = at.K.K * Vector3(0.001, 1e-4, -2e-4);
    ASSERT_TRUE(displacementUnderWrench(at.K, at.model.length_scale, reachable, dp));
    EXPECT_LT((at.K.K * dp - reachable).norm(), 1e-9 * reachable.norm());
    EXPECT_NE(describeDirection(free).find("rotation about the point"), std::string::npos) << describeDirection(free);
}

TEST(Stiffness, ATranslationIsDescribedAsOne) {
    EXPECT_EQ(describeDirection(Vector3(0.0, 0.6, 0.8)), "a translation along (x, y) = (0.6, 0.8)");
    EXPECT_EQ(describeDirection(Vector3(1.0, 0.0, 0.0)),
              "a rotation about the point (x, y) = (0, 0) m from the platform's reference point");
}

TEST(Stiffness, DisplacementUnderAWrenchSolvesKDpEqualsF) {
    AtPose at(rprWithFlexures(), Pose(0.02, 0.003, -0.001));
    ASSERT_TRUE(at.status.ok());
    const Vector3 f(0.3, 5.0, -2.0);  // [N m, N, N]
    Vector3 dp;
    ASSERT_TRUE(displacementUnderWrench(at.K, at.model.length_scale, f, dp));
    EXPECT_LT((at.K.K * dp - f).norm(), 1e-12 * f.norm());
}

/// Energy of the joint springs at pose p, relative to their positions at p0 (rigid bodies).
double springEnergy(const Model& model, const StiffnessModel& compliance, Data& data, const Pose& p,
                    const std::array<Vector3, kMaxLimbs>& q0) {
    EXPECT_TRUE(inverseDisplacement(model, data, p).ok());
    double energy = 0.0;
    for (int j = 0; j < model.limbs; ++j) {
        for (int k = 0; k < 3; ++k) {
            const auto J = static_cast<std::size_t>(j);
            const auto K = static_cast<std::size_t>(k);
            if (compliance.joint[J][K] != JointSpring::spring) continue;
            const double dq = data.limb[J].q(k) - q0[J](k);
            energy += 0.5 * compliance.k[J][K] * dq * dq;
        }
    }
    return energy;
}

TEST(Stiffness, IsTheHessianOfTheSpringEnergyByFiniteDifferences) {
    // the static equilibrium under a small wrench f: grad E(p) = f, so dQ/dp = Hess E at p0
    for (RobotDescription robot : {prrWithDriveSprings(Eigen::Vector3d(1e5, 2e5, 3e5)), rprWithFlexures()}) {
        const Pose p0(0.015, 0.002, -0.001);
        AtPose at(std::move(robot), p0);
        ASSERT_TRUE(at.status.ok());
        std::array<Vector3, kMaxLimbs> q0{};
        for (int j = 0; j < at.model.limbs; ++j)
            q0[static_cast<std::size_t>(j)] = at.data.limb[static_cast<std::size_t>(j)].q;
        Data data(at.model);
        const Vector3 h(1e-4, 1e-4 * at.model.length_scale, 1e-4 * at.model.length_scale);
        Matrix3 hessian;
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
                const Vector3 ea = Vector3::Unit(a) * h(a), eb = Vector3::Unit(b) * h(b);
                const auto E = [&](const Vector3& d) {
                    return springEnergy(at.model, at.compliance, data, p0 + d, q0);
                };
                hessian(a, b) = (E(ea + eb) - E(ea - eb) - E(eb - ea) + E(-ea - eb)) / (4.0 * h(a) * h(b));
            }
        }
        EXPECT_LT(relativeError(scaledK(hessian, at.model.length_scale), scaledK(at.K.K, at.model.length_scale)), 1e-6);
    }
}

TEST(Stiffness, ACantileverAndAStrutPerLimbGiveTheAnalyticStiffness) {
    // 3-RRR, motors locked, proximal links elastic, distal links rigid between free pivots:
    // each distal link is a strut along d (elbow to platform pivot), carried by the proximal
    // cantilever's tip, k_j = 1 / (d_e^2 l / EA + d_n^2 l^3 / (3 EI)), K = S^T sum k_j w w^T S
    RobotDescription robot = robotDescription("3-rrr");
    const double EA = 2.8e6, EI = 23.0;
    for (LimbDescription& limb : robot.limbs) limb.bodies[0].elastic = ElasticBeam{EA, EI};
    const Pose p(0.01, 0.002, 0.003);
    AtPose at(std::move(robot), p);
    ASSERT_TRUE(at.status.ok()) << describe(at.status, at.model);
    Matrix3 K_twist = Matrix3::Zero();
    for (int j = 0; j < 3; ++j) {
        const LimbData& limb = at.data.limb[static_cast<std::size_t>(j)];
        const auto point = [&](int k) {
            return Vector2(-limb.s[static_cast<std::size_t>(k)](2), limb.s[static_cast<std::size_t>(k)](1));
        };
        const Vector2 a = point(0), elbow = point(1), pivot = point(2);
        const double l = (elbow - a).norm();
        const Vector2 e = (elbow - a) / l, n = perp(e);
        const Vector2 d = (pivot - elbow).normalized();
        const double k = 1.0 / (std::pow(d.dot(e), 2) * l / EA + std::pow(d.dot(n), 2) * l * l * l / (3.0 * EI));
        const Wrench w(cross(elbow, d), d.x(), d.y());  // the strut's line of force, referred to O
        K_twist += k * w * w.transpose();
    }
    const Matrix3 S = platformTwistMap(p.tail<2>());
    const Matrix3 expected = S.transpose() * K_twist * S;
    EXPECT_LT(relativeError(scaledK(at.K.K, at.model.length_scale), scaledK(expected, at.model.length_scale)), 1e-12);
}

TEST(Stiffness, TheElastodynamicModelCondensedOntoThePlatformGivesK) {
    const Pose p(0.02, -0.001, 0.002);
    for (RobotDescription robot :
         {prrWithDriveSprings(Eigen::Vector3d(1e5, 2e5, 3e5)), rprWithFlexures(), rrrWithElasticLinks()}) {
        AtPose at(std::move(robot), p);
        ASSERT_TRUE(at.status.ok());
        ElastodynamicModes modes;
        ASSERT_TRUE(elastodynamicModes(at.model, at.compliance, at.data, modes).ok());
        EXPECT_LT(
            relativeError(scaledK(modes.K_condensed, at.model.length_scale), scaledK(at.K.K, at.model.length_scale)),
            1e-9)
            << at.model.description.name;
    }
}

TEST(Stiffness, LumpedAndElastodynamicFrequenciesAreOneWithRigidBodies) {
    const Pose p(0.02, -0.001, 0.002);
    for (RobotDescription robot : {prrWithDriveSprings(Eigen::Vector3d(1e5, 2e5, 3e5)), rprWithFlexures()}) {
        AtPose at(std::move(robot), p);
        ASSERT_TRUE(at.status.ok());
        ElastodynamicModes modes;
        ASSERT_TRUE(elastodynamicModes(at.model, at.compliance, at.data, modes).ok());
        ASSERT_EQ(modes.dofs, 3);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(modes.frequency(i) / at.modes.frequency(i), 1.0, 1e-10);
        // the mode shapes are the same platform motions, to sign
        for (int i = 0; i < 3; ++i) {
            const Vector3 a = modes.platform_shape.col(i), b = at.modes.shape.col(i);
            EXPECT_NEAR(std::abs(a.dot(at.modes.M * b)), 1.0, 1e-9);
        }
    }
}

TEST(Stiffness, LumpedModesAreMassNormalisedAndAscending) {
    AtPose at(rrrWithElasticLinks(), Pose(0.0, 0.0, 0.0));
    ASSERT_TRUE(at.status.ok());
    const Matrix3 VtMV = at.modes.shape.transpose() * at.modes.M * at.modes.shape;
    EXPECT_LT((VtMV - Matrix3::Identity()).norm(), 1e-10);
    const Matrix3 VtKV = at.modes.shape.transpose() * at.K.K * at.modes.shape;
    for (int i = 0; i < 3; ++i) {
        const double w = 2.0 * std::numbers::pi * at.modes.frequency(i);
        EXPECT_NEAR(VtKV(i, i) / (w * w), 1.0, 1e-10);
    }
    EXPECT_LT(at.modes.frequency(0), at.modes.frequency(1));
    EXPECT_LT(at.modes.frequency(1), at.modes.frequency(2));
}

TEST(Stiffness, ElasticLinksAddModesAndStiffLinksTendToTheLumpedModel) {
    AtPose at(rrrWithElasticLinks(), Pose(0.0, 0.0, 0.0));
    ASSERT_TRUE(at.status.ok());
    ElastodynamicModes modes;
    ASSERT_TRUE(elastodynamicModes(at.model, at.compliance, at.data, modes).ok());
    // per limb: 2 beams of 3 deflections and 2 free pivots, less 3 closure equations: 5 internal,
    // of which the two beam tips' rotations at the free pivots carry no mass (condensed)
    EXPECT_EQ(modes.dofs, 3 + 3 * 3);
    // motors on springs and links 1e6 times stiffer: the links' own modes leave the band and
    // the first three frequencies tend to the lumped model's of the motor springs alone
    RobotDescription robot = robotDescription("3-rrr");
    for (LimbDescription& limb : robot.limbs) {
        limb.joints[0].stiffness = 20.0;
        limb.bodies[0].elastic = ElasticBeam{2.8e12, 23.3e6};
        limb.bodies[1].elastic = ElasticBeam{2.2e12, 12.0e6};
    }
    AtPose stiff(robot, Pose(0.01, 0.001, -0.002));
    ASSERT_TRUE(stiff.status.ok());
    ASSERT_TRUE(elastodynamicModes(stiff.model, stiff.compliance, stiff.data, modes).ok());
    for (LimbDescription& limb : robot.limbs) limb.bodies = {limb.bodies[0], limb.bodies[1]};
    for (LimbDescription& limb : robot.limbs) limb.bodies[0].elastic.reset(), limb.bodies[1].elastic.reset();
    AtPose rigid(robot, Pose(0.01, 0.001, -0.002));
    ASSERT_TRUE(rigid.status.ok());
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(modes.frequency(i) / rigid.modes.frequency(i), 1.0, 1e-5);
    EXPECT_GT(modes.frequency(3), 100.0 * rigid.modes.frequency(2));
}

TEST(Stiffness, ALockedLimbWithNothingElseToYieldIsRigidAndNamed) {
    // the paper's robot as written: its drives are locked and its links rigid
    const Model model(robotDescription("paper-3prr-general"));
    const StiffnessModel compliance(model);
    EXPECT_FALSE(compliance.any);
    Data data(model);
    StiffnessData K;
    LumpedModes modes;
    const Status status = stiffnessAndModes(model, compliance, data, Pose::Zero(), K, modes);
    ASSERT_EQ(status.code, StatusCode::rigid_limb);
    EXPECT_EQ(status.limb, 0);
    EXPECT_NE(describe(status, model).find("limb 1"), std::string::npos) << describe(status, model);
}

TEST(Stiffness, APoseOutOfReachIsTheKinematicsError) {
    AtPose at(prrWithDriveSprings(Eigen::Vector3d(1e5, 1e5, 1e5)), Pose(0.0, 0.5, 0.0));
    EXPECT_EQ(at.status.code, StatusCode::unreachable);
}

TEST(Stiffness, ReportedCoordinatesAreNamedWithUnits) {
    EXPECT_EQ(coordinateLabel(0), "x [m]");
    EXPECT_EQ(coordinateLabel(1), "y [m]");
    EXPECT_EQ(coordinateLabel(2), "theta [rad]");
    EXPECT_EQ(stiffnessUnit(2, 2), "N m/rad");
    EXPECT_EQ(stiffnessUnit(0, 0), "N/m");
    EXPECT_EQ(stiffnessUnit(0, 2), "N/rad");
    EXPECT_EQ(stiffnessUnit(2, 1), "N");
}

// ---- the robot file ----

std::string replaceFirst(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

TEST(StiffnessFile, ReadsJointStiffnessAndElasticBodiesAndWritesThemBack) {
    std::string text = replaceFirst(robotText("3-rrr"), "{type: R, point: [0.08, -0.13175]}",
                                    "{type: R, point: [0.08, -0.13175], stiffness: 12.5}");
    text = replaceFirst(text, "com: [0.04, -0.165875]}", "com: [0.04, -0.165875], elastic: {EA: 2.8e6, EI: 23.3}}");
    const RobotDescription robot = io::parseRobotDescription(text, "r.yaml");
    ASSERT_TRUE(robot.limbs[0].joints[1].stiffness.has_value());
    EXPECT_EQ(*robot.limbs[0].joints[1].stiffness, 12.5);
    EXPECT_FALSE(robot.limbs[0].joints[0].stiffness.has_value());
    ASSERT_TRUE(robot.limbs[0].bodies[0].elastic.has_value());
    EXPECT_EQ(robot.limbs[0].bodies[0].elastic->EA, 2.8e6);
    EXPECT_EQ(robot.limbs[0].bodies[0].elastic->EI, 23.3);
    EXPECT_TRUE(robot.hasCompliance());
    EXPECT_TRUE(robot.hasElasticBody());
    const RobotDescription back = io::parseRobotDescription(io::descriptionToYaml(robot), "back.yaml");
    EXPECT_EQ(*back.limbs[0].joints[1].stiffness, 12.5);
    EXPECT_EQ(back.limbs[0].bodies[0].elastic->EI, 23.3);
}

TEST(StiffnessFile, ParametersAndSetReachTheCompliance) {
    std::string text = "parameters:\n  k_drive: 1.0e5\n" + robotText("paper-3prr-general");
    text = replaceFirst(text, "actuated: true,", "actuated: true, stiffness: 2 * k_drive,");
    const RobotDescription robot = io::parseRobotDescription(text, "p.yaml", {{"k_drive", 3.0e4}});
    EXPECT_EQ(*robot.limbs[0].joints[0].stiffness, 6.0e4);
}

void expectError(const std::string& text, const std::string& fragment) {
    try {
        (void)io::parseRobotDescription(text, "bad.yaml");
        ADD_FAILURE() << "accepted; expected an error with " << fragment;
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(fragment), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_EQ(message.rfind("bad.yaml:", 0), 0U) << message;
    }
}

TEST(StiffnessFile, RefusesNegativeOrNanStiffnessZeroRigidityAndABeamOnAPJoint) {
    const std::string prr = robotText("paper-3prr-general");
    expectError(
        replaceFirst(prr, "actuated: true,", "actuated: true, stiffness: -1,"),
        "limbs[0] (limb1).joints[0].stiffness: must be 0 (free) or a finite number in [1e-09, 1e+15] N/m, got -1");
    expectError(replaceFirst(prr, "actuated: true,", "actuated: true, stiffness: .nan,"), "joints[0].stiffness");
    const std::string rrr = robotText("3-rrr");
    expectError(replaceFirst(rrr, "com: [0.04, -0.165875]}", "com: [0.04, -0.165875], elastic: {EA: 0, EI: 1}}"),
                "limbs[0] (limb1).bodies[0].elastic.EA: must be a finite number in [1e-09, 1e+15] N, got 0");
    expectError(replaceFirst(rrr, "com: [0.04, -0.165875]}", "com: [0.04, -0.165875], elastic: {EA: 1e6, EI: 0}}"),
                "bodies[0].elastic.EI");
    expectError(replaceFirst(prr, "com: [-0.08035283213389613, -0.11547005383792514]}",
                             "com: [-0.08035283213389613, -0.11547005383792514], elastic: {EA: 1e6, EI: 10}}"),
                "limbs[0] (limb1).bodies[0].elastic: an elastic body is a beam between two revolute joints, but "
                "limb1's body 1 is carried by a prismatic joint (PRR)");
    expectError(replaceFirst(rrr, "com: [0.04, -0.165875]}", "com: [0.04, -0.165875], elastic: {EA: 1e6}}"), "elastic");
}

}  // namespace
}  // namespace nocdyn
