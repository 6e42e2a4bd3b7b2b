// Hostile input at the library, compliance and frequency responses: each test holds one finding
// with its exact input. A stiffness contrast of many decades, stiffness values at the edge of
// their range, very stiff beams, the frequency response at very low frequency, the lumped model
// next to a limb singularity, and long calls that must answer a stop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "robot_files.hpp"

namespace nocdyn {
namespace {

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

/// sqrt(eig(K, M)) / 2 pi ascending, by a general (non-symmetric) solver on M^-1 K: an
/// independent route to the lumped frequencies of the same K and M.
Vector3 frequenciesOf(const Matrix3& K, const Matrix3& M) {
    const Eigen::EigenSolver<Matrix3> eig(M.inverse() * K);
    Vector3 f;
    for (int i = 0; i < 3; ++i) f(i) = std::sqrt(std::max(eig.eigenvalues()(i).real(), 0.0)) / (2.0 * std::numbers::pi);
    std::sort(f.data(), f.data() + 3);
    return f;
}

/// The compliant 3-PRR with drive 1 at `k1` N/m and every link's EA at `EA` N.
RobotDescription contrast(double k1, double EA) {
    RobotDescription robot = robotDescription("paper-3prr-compliant");
    robot.limbs[0].joints[0].stiffness = k1;
    for (LimbDescription& limb : robot.limbs) limb.bodies[1].elastic->EA = EA;
    return robot;
}

/// The 3-RRR, drive springs `k` N m/rad, every link an elastic beam EA = EI = X (0: rigid).
RobotDescription rrrBeams(double k, double X) {
    RobotDescription robot = robotDescription("3-rrr");
    for (LimbDescription& limb : robot.limbs) {
        limb.joints[0].stiffness = k;
        limb.joints[0].limits = JointLimits{};
        if (X > 0.0) {
            limb.bodies[0].elastic = ElasticBeam{X, X};
            limb.bodies[1].elastic = ElasticBeam{X, X};
        }
    }
    return robot;
}

std::string validationError(RobotDescription robot) {
    try {
        validate(robot);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(HostileRound4, AStiffnessContrastAboveOneBillionKeepsTheHeldDirectionsHeld) {
    // drive 1 at 5e14 N/m and the links' EA at 1e15 N, drives 2 and 3 at 2e5 N/m
    for (const double k1 : {1e13, 1e14, 5e14, 1e15}) {
        AtPose at(contrast(k1, 1e15), Pose::Zero());
        ASSERT_TRUE(at.status.ok()) << describe(at.status, at.model);
        EXPECT_EQ(at.K.free_directions, 0) << k1;
        if (k1 >= 1e15) {
            EXPECT_GT(at.K.contrast, 1e9);
        }
        const Vector3 f = frequenciesOf(at.K.K, at.modes.M);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(at.modes.frequency(i) / f(i), 1.0, 1e-6) << k1 << " mode " << i;
        // the soft modes stay where the soft drives put them: about 41 and 44 Hz
        EXPECT_NEAR(at.modes.frequency(0), 41.3, 0.5) << k1;
        EXPECT_NEAR(at.modes.frequency(1), 43.8, 0.5) << k1;
        EXPECT_EQ(contrastWarning(at.K).empty(), at.K.contrast <= kContrastWarning);
    }
    // and the envelope keeps its third bound
    const EnvelopeResonance resonance = envelopeResonance(Model(contrast(5e14, 1e15)));
    EXPECT_TRUE(resonance.known) << resonance.reason;
    EXPECT_NEAR(resonance.frequency, 41.3, 0.5);
}

TEST(HostileRound4, AContrastBeyondDoublePrecisionIsRefusedByName) {
    RobotDescription robot = robotDescription("paper-3prr-compliant");
    robot.limbs[0].joints[0].stiffness = 1e15;
    robot.limbs[1].joints[0].stiffness = 1e15;
    robot.limbs[2].joints[0].stiffness = 1e-3;
    for (LimbDescription& limb : robot.limbs) limb.bodies[1].elastic->EA = 1e15;
    AtPose at(robot, Pose::Zero());
    ASSERT_EQ(at.status.code, StatusCode::stiffness_contrast);
    EXPECT_GT(at.status.value, kContrastLimit);
    EXPECT_NE(describe(at.status, at.model).find("stiffness contrast"), std::string::npos);
    EXPECT_FALSE(envelopeResonance(at.model).known);
}

TEST(HostileRound4, AFreeDirectionNextToAStiffOneIsFreeAndTheOthersAreExact) {
    // drive 1 a force actuator (free), drive 2 1e10 times stiffer than drive 3
    RobotDescription robot = robotDescription("paper-3prr-compliant");
    robot.limbs[0].joints[0].stiffness = 0.0;
    robot.limbs[1].joints[0].stiffness = 1e12;
    robot.limbs[2].joints[0].stiffness = 1e2;
    AtPose at(robot, Pose(0.01, 0.001, 0.002));
    ASSERT_TRUE(at.status.ok()) << describe(at.status, at.model);
    ASSERT_EQ(at.K.free_directions, 1);
    EXPECT_EQ(at.modes.frequency(0), 0.0);
    EXPECT_GT(at.modes.frequency(1), 0.0);
    // every mode: K v = w^2 M v, v^T M v = 1
    for (int i = 0; i < 3; ++i) {
        const Vector3 v = at.modes.shape.col(i);
        const double w = 2.0 * std::numbers::pi * at.modes.frequency(i);
        EXPECT_NEAR(v.dot(at.modes.M * v), 1.0, 1e-10);
        EXPECT_LT((at.K.K * v - w * w * (at.modes.M * v)).norm(), 1e-6 * at.K.K.norm() * v.norm()) << i;
    }
}

TEST(HostileRound4, StiffnessTooSmallForItsComplianceIsRefusedNamingTheField) {
    RobotDescription robot = robotDescription("3-rrr");
    robot.limbs[0].joints[0].stiffness = 1e-320;
    std::string message = validationError(robot);
    EXPECT_NE(message.find("joints[0].stiffness"), std::string::npos) << message;
    EXPECT_NE(message.find("1e-09"), std::string::npos) << message;
    robot.limbs[0].joints[0].stiffness = 2000.0;
    robot.limbs[0].bodies[0].elastic = ElasticBeam{1e7, 1e-300};
    message = validationError(robot);
    EXPECT_NE(message.find("elastic.EI"), std::string::npos) << message;
    // at the range's edge, finite numbers or the contrast named
    for (LimbDescription& limb : robot.limbs) limb.joints[0].stiffness = 1e-9;
    robot.limbs[0].bodies[0].elastic = ElasticBeam{1e-9, 1e-9};
    EXPECT_EQ(validationError(robot), "");
    AtPose at(robot, Pose::Zero());
    if (at.status.ok()) {
        EXPECT_TRUE(at.K.K.allFinite());
        EXPECT_TRUE(at.modes.frequency.allFinite());
    } else {
        EXPECT_EQ(at.status.code, StatusCode::stiffness_contrast) << describe(at.status, at.model);
    }
}

TEST(HostileRound4, VeryStiffBeamsTendToTheRigidLinks) {
    AtPose rigid(rrrBeams(2000.0, 0.0), Pose::Zero());
    ASSERT_TRUE(rigid.status.ok());
    for (const double X : {1e10, 1e13, 1e15}) {
        AtPose at(rrrBeams(2000.0, X), Pose::Zero());
        ASSERT_TRUE(at.status.ok()) << describe(at.status, at.model);
        ElastodynamicModes modes;
        ASSERT_TRUE(elastodynamicModes(at.model, at.compliance, at.data, modes).ok());
        for (int i = 0; i < 3; ++i) {
            EXPECT_NEAR(modes.frequency(i) / rigid.modes.frequency(i), 1.0, 1e-6) << "X = " << X << " mode " << i;
        }
        // the mode shapes are the rigid links' platform motions and mass-normalised
        for (int i = 0; i < 3; ++i) {
            const Vector3 a = modes.platform_shape.col(i), b = rigid.modes.shape.col(i);
            EXPECT_NEAR(std::abs(a.dot(rigid.modes.M * b)), 1.0, 1e-4) << "X = " << X << " mode " << i;
        }
        EXPECT_TRUE(modes.frequency.allFinite());
    }
}

TEST(HostileRound4, VeryStiffBeamsTendToTheRigidLinksBesideAFreeDirection) {
    // drive 1 a force actuator (stiffness 0): one free direction, two held modes
    RobotDescription rigid_robot = rrrBeams(2000.0, 0.0);
    rigid_robot.limbs[0].joints[0].stiffness = 0.0;
    AtPose rigid(rigid_robot, Pose::Zero());
    ASSERT_TRUE(rigid.status.ok());
    ASSERT_EQ(rigid.K.free_directions, 1);
    for (const double X : {1e10, 1e15}) {
        RobotDescription robot = rrrBeams(2000.0, X);
        robot.limbs[0].joints[0].stiffness = 0.0;
        AtPose at(robot, Pose::Zero());
        ASSERT_TRUE(at.status.ok()) << describe(at.status, at.model);
        ElastodynamicModes modes;
        ASSERT_TRUE(elastodynamicModes(at.model, at.compliance, at.data, modes).ok());
        EXPECT_EQ(modes.frequency(0), 0.0);
        for (int i = 1; i < 3; ++i) {
            EXPECT_NEAR(modes.frequency(i) / rigid.modes.frequency(i), 1.0, 1e-6) << "X = " << X << " mode " << i;
        }
    }
}

TEST(HostileRound4, TheFrequencyResponseKeepsItsDigitsAtVeryLowFrequency) {
    // undamped, so that the reference below is real
    RobotDescription undamped = robotDescription("paper-3prr-compliant");
    undamped.damping_ratio = 0.0;
    const Model model(undamped);
    const StiffnessModel compliance(model);
    Data data(model);
    StateSpace system;
    ASSERT_TRUE(linearizeCompliant(model, compliance, data, Pose::Zero(), Twist::Zero(),
                                   ActuatorVector::Zero(model.actuators), LinearOutput::platform_acceleration, system)
                    .ok());
    const Eigen::MatrixXd Q = -system.A.bottomLeftCorner(3, 3), P = system.B.bottomRows(3);
    for (const double f : {1e-9, 1e-7, 1e-6, 1e-3, 1.0, 1e3}) {
        const double w = 2.0 * std::numbers::pi * f;
        // exact: y = s^2 x1, (Q - w^2 I) x1 = P at s = j w (no damping at rest)
        const Eigen::MatrixXd exact = -w * w * (Q - w * w * Eigen::MatrixXd::Identity(3, 3)).lu().solve(P);
        const Eigen::MatrixXcd H = frequencyResponse(system, f);
        for (int o = 0; o < 3; ++o) {
            for (int i = 0; i < 3; ++i) {
                EXPECT_NEAR(std::abs(H(o, i)) / std::abs(exact(o, i)), 1.0, 1e-9)
                    << f << " Hz (" << o << ", " << i << ")";
            }
        }
    }
    // the rigid model's actuator output, y = A_p x1: finite and growing as 1 / w^2
    StateSpace rigid;
    ASSERT_TRUE(linearize(model, data, Pose::Zero(), Twist::Zero(), ActuatorVector::Zero(model.actuators),
                          LinearOutput::actuator_variables, rigid)
                    .ok());
    const Eigen::MatrixXcd a = frequencyResponse(rigid, 1e-9), b = frequencyResponse(rigid, 1e-8);
    ASSERT_TRUE(a.allFinite());
    EXPECT_NEAR(std::abs(a(0, 0)) / std::abs(b(0, 0)), 100.0, 1e-6);
}

TEST(HostileRound4, NextToALimbSingularityTheLumpedModelIsSaidNotToHold) {
    RobotDescription robot = robotDescription("3-rrr-elastic");
    for (LimbDescription& limb : robot.limbs) limb.joints[0].limits = JointLimits{};
    const Model model(robot);
    const StiffnessModel compliance(model);
    const auto lumpedAndElastic = [&](const Pose& p, LumpedModes& lumped, ElastodynamicModes& elastic) {
        Data data(model);
        StiffnessData K;
        Status s = stiffnessAndModes(model, compliance, data, p, K, lumped);
        if (s) s = elastodynamicModes(model, compliance, data, elastic);
        return s;
    };
    LumpedModes lumped;
    ElastodynamicModes elastic;
    ASSERT_TRUE(lumpedAndElastic(Pose::Zero(), lumped, elastic).ok());
    EXPECT_EQ(lumpedMismatchWarning(lumped, elastic), "");
    // the reach boundary below home, by bisection on y
    double lo = 0.0, hi = 0.2;
    for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (lumpedAndElastic(Pose(0.0, 0.0, -mid), lumped, elastic).ok() ? lo : hi) = mid;
    }
    ASSERT_TRUE(lumpedAndElastic(Pose(0.0, 0.0, -(lo - 1e-9)), lumped, elastic).ok());
    const std::string warning = lumpedMismatchWarning(lumped, elastic);
    EXPECT_GT(std::abs(lumped.frequency(0) / elastic.frequency(0) - 1.0), kLumpedMismatch);
    EXPECT_NE(warning.find("lumped model does not hold"), std::string::npos) << warning;
    // the first frequency to use there is the elastodynamic one (lumped 9.805 Hz, elastodynamic
    // 29.905 Hz), with the warning that says so; at home the lumped one, without a word
    EXPECT_NEAR(lumped.frequency(0), 9.805, 1e-2);
    EXPECT_NEAR(elastic.frequency(0), 29.905, 3e-2);
    EXPECT_NEAR(lumped.frequency(0) / elastic.frequency(0), 0.328, 1e-3);
    EXPECT_NE(warning.find("the elastodynamic frequencies are used here"), std::string::npos) << warning;
    EXPECT_NE(lumpedMismatchWarning(lumped, elastic, false).find("are the ones to use here"), std::string::npos);
    EXPECT_FALSE(lumpedHolds(lumped, elastic));
    Data data(model);
    StiffnessData K;
    ASSERT_TRUE(stiffnessAndModes(model, compliance, data, Pose(0.0, 0.0, -(lo - 1e-9)), K, lumped).ok());
    std::string used;
    EXPECT_EQ(firstFrequency(model, compliance, data, lumped, &used), elastic.frequency(0));
    EXPECT_EQ(used, warning);
    ASSERT_TRUE(stiffnessAndModes(model, compliance, data, Pose::Zero(), K, lumped).ok());
    used.clear();
    EXPECT_EQ(firstFrequency(model, compliance, data, lumped, &used), lumped.frequency(0));
    EXPECT_EQ(used, "");
}

TEST(HostileRound4, ALongIntegrationAnswersItsPollAndStops) {
    const Model model(robotDescription("3-rrr"));
    SimulatorOptions options;
    options.max_step = 1e-5;
    int polls = 0;
    options.poll = [&polls] {
        if (++polls == 3) throw std::runtime_error("stop");
    };
    Simulator simulator(model, options);
    ASSERT_TRUE(simulator.reset(model.home).ok());
    EXPECT_THROW((void)simulator.advance(100.0, ActuatorVector::Zero(model.actuators)), std::runtime_error);
    EXPECT_EQ(polls, 3);
    EXPECT_LT(simulator.time(), 1.0);  // stopped after about 3 x 1024 steps, not at 100 s
}

TEST(HostileRound4, TheEnvelopeAnswersItsPollWithinAPoint) {
    const Model model(robotDescription("3-rrr"));
    EnvelopeOptions options;
    options.points = 1;
    options.samples_per_period = 64;
    int polls = 0;
    options.poll = [&polls] {
        if (++polls == 2) throw std::runtime_error("stop");
    };
    EXPECT_THROW((void)operatingEnvelope(model, options), std::runtime_error);
    EXPECT_EQ(polls, 2);
}

}  // namespace
}  // namespace nocdyn
