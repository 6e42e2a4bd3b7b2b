// Direct kinematics of the paper's 3-PRR, by the general solver on the robot its short form
// expands to: every mode found gives back u by inverse displacement; the modes are exactly the
// roots a dense 1-D scan of the 3-PRR's own closure equations finds; the reference posture is
// among the modes at u = 0; within the stroke there are exactly two working modes; the tracker
// follows a trajectory and stays on its mode.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/LU>

#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/trajectory.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

constexpr double kVerify = 1e-12;  // [m]

/// Independent count of the real roots, from the 3-PRR's geometry (the paper's equations, not
/// the general model):
/// sign changes of (circumradius of P_1 P_2 P_3)^2 - l^2 on a fine theta grid,
/// P_j = A_j - Rot(theta) M_local_j, A_j = B_j + (s_ref_j + u_j) e_j: with the sliders locked
/// each closure |C - P_j| = l is a circle of the same radius l, so C is the circumcentre.
int countByScan(const PaperGeometry& paper, const Vector3& u, int samples = 100000) {
    auto f = [&](double theta) {
        std::array<Vector2, 3> P;
        for (int j = 0; j < 3; ++j) {
            const Vector2 a = paper.B[j] + (paper.s_ref[j] + u(j)) * paper.e[j];
            const double c = std::cos(theta), s = std::sin(theta);
            const Vector2& v = paper.M_local[j];
            P[j] = a - Vector2(c * v.x() - s * v.y(), s * v.x() + c * v.y());
        }
        Matrix2 K;
        Vector2 b;
        for (int k = 0; k < 2; ++k) {
            K.row(k) = 2.0 * (P[0] - P[k + 1]).transpose();
            b(k) = P[0].squaredNorm() - P[k + 1].squaredNorm();
        }
        const Vector2 C = K.inverse() * b;
        return (C - P[0]).squaredNorm() - paper.l * paper.l;
    };
    int changes = 0;
    const double pi = std::numbers::pi;
    double previous = f(-pi);
    for (int i = 1; i <= samples; ++i) {
        const double value = f(-pi + 2.0 * pi * i / samples);
        if ((value > 0.0) != (previous > 0.0)) ++changes;
        previous = value;
    }
    return changes;
}

struct Paper {
    io::RobotParameters robot;
    PaperGeometry geometry{robot};
    Model model{io::exampleRobot("paper-3prr")};  // the short form expanded
};

AssemblyModes modesAt(const Model& model, const Vector3& u) {
    Data data(model);
    AssemblyModes modes;
    EXPECT_TRUE(directKinematics(model, data, ActuatorVector(u), modes).ok());
    EXPECT_FALSE(modes.degenerate);
    return modes;
}

/// u recomputed from the pose on the mode's branches within 1e-12 m times the mode's
/// condition number (the round-off of a pose grows with it); for working modes also by
/// inverseDisplacement on the home branches.
void expectVerified(const Model& model, const Vector3& u, const AssemblyMode& mode) {
    const double tolerance = kVerify * std::max(1.0, mode.condition);
    EXPECT_LE(mode.u_error, tolerance) << describePose(mode.p) << ", condition " << mode.condition;
    if (mode.working) {
        Data data(model);
        ASSERT_TRUE(inverseDisplacement(model, data, mode.p).ok()) << describePose(mode.p);
        EXPECT_LE((data.u - u).cwiseAbs().maxCoeff(), tolerance) << describePose(mode.p);
    }
}

int workingCount(const AssemblyModes& modes) {
    int working = 0;
    for (const AssemblyMode& mode : modes) working += mode.working ? 1 : 0;
    return working;
}

TEST(DirectKinematics, ReferencePostureIsASolutionAtZeroDisplacement) {
    const Paper paper;
    const AssemblyModes modes = modesAt(paper.model, Vector3::Zero());
    ASSERT_GT(modes.count, 0);
    bool found = false;
    for (const AssemblyMode& mode : modes) {
        expectVerified(paper.model, Vector3::Zero(), mode);
        found = found || mode.p.cwiseAbs().maxCoeff() <= 1e-12;
    }
    EXPECT_TRUE(found);
}

TEST(DirectKinematics, TwoAssemblyModesAtZeroDisplacementBothWorking) {
    // At u = 0 the triangle P_1 P_2 P_3 stays equilateral and centred on O for every theta,
    // so its circumradius is a single sinusoid in theta: exactly two roots, both on the
    // working branches (theta = 0 and a platform turned by about 170 degrees).
    const Paper paper;
    const AssemblyModes modes = modesAt(paper.model, Vector3::Zero());
    EXPECT_EQ(modes.count, 2);
    EXPECT_EQ(workingCount(modes), 2);
    EXPECT_EQ(countByScan(paper.geometry, Vector3::Zero()), 2);
}

TEST(DirectKinematics, EverySolutionIsVerifiedAndNoneIsMissed) {
    // Random u over a range far beyond the stroke, so that 0, 2, 4 and 6 real solutions occur;
    // the solver must find exactly the roots that a dense scan finds.
    const Paper paper;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> range(-0.2, 0.2);
    int most = 0;
    for (int k = 0; k < 200; ++k) {
        const Vector3 u(range(rng), range(rng), range(rng));
        const AssemblyModes modes = modesAt(paper.model, u);
        for (const AssemblyMode& mode : modes) expectVerified(paper.model, u, mode);
        EXPECT_EQ(modes.count, countByScan(paper.geometry, u)) << "u = [" << u.transpose() << "]";
        most = std::max(most, modes.count);
    }
    EXPECT_EQ(most, 6) << "the 3-PRR has up to six assembly modes";
}

TEST(DirectKinematics, WorkingModesInvertTheInverseDisplacementAcrossTheWorkspace) {
    const Paper paper;
    WorkspaceSampler sampler(paper.model);
    Data data(paper.model);
    for (int k = 0; k < 300; ++k) {
        const Pose p = sampler.next();
        ASSERT_TRUE(inverseDisplacement(paper.model, data, p).ok());
        const Vector3 u = data.u;
        bool found = false;
        for (const AssemblyMode& mode : modesAt(paper.model, u)) {
            expectVerified(paper.model, u, mode);
            found = found || (mode.working && (mode.p - p).cwiseAbs().maxCoeff() <= 1e-10);
        }
        EXPECT_TRUE(found) << describePose(p);
    }
}

TEST(DirectKinematics, WithinTheStrokeThereAreExactlyTwoWorkingModes) {
    const Paper paper;
    std::mt19937 rng(11);
    const double half = 0.5 * paper.robot.stroke;
    std::uniform_real_distribution<double> range(-half, half);
    for (int k = 0; k < 100; ++k) {
        const Vector3 u(range(rng), range(rng), range(rng));
        const AssemblyModes modes = modesAt(paper.model, u);
        EXPECT_EQ(modes.count, 2) << "u = [" << u.transpose() << "]";
        EXPECT_EQ(workingCount(modes), 2) << "u = [" << u.transpose() << "]";
    }
}

TEST(DirectKinematics, TrackerFollowsPaperTrajectory) {
    const Paper paper;
    Data data(paper.model), reference(paper.model);
    const PoseTrajectory trajectory = paperTrajectory1();
    Pose p, dp, ddp;
    Pose tracked = Pose::Zero();  // start from the reference posture, 4 mm away
    double worst = 0.0;
    for (int k = 0; k <= 2000; ++k) {
        trajectory.evaluate(k * 1e-4, p, dp, ddp);
        ASSERT_TRUE(inverseDisplacement(paper.model, reference, p).ok());
        const Status status = trackPose(paper.model, data, reference.u, tracked);
        ASSERT_TRUE(status.ok()) << "t = " << k * 1e-4 << ": " << describe(status, paper.model);
        worst = std::max(worst, (tracked - p).cwiseAbs().maxCoeff());
    }
    EXPECT_LE(worst, 1e-11);
}

TEST(DirectKinematics, TrackerFailsFarOutsideTheWorkspace) {
    const Paper paper;
    Data data(paper.model);
    Pose p = Pose::Zero();
    // Far beyond anything the limbs can reach from the reference posture by small steps.
    const Status status = trackPose(paper.model, data, ActuatorVector(Vector3(0.3, -0.3, 0.3)), p);
    EXPECT_FALSE(status.ok());
    EXPECT_TRUE(p.allFinite());
}

TEST(DirectKinematics, TrackerStaysOnItsMode) {
    // Starting next to the second (turned) assembly mode, the tracker converges there, not
    // to the reference posture.
    const Paper paper;
    const AssemblyModes modes = modesAt(paper.model, Vector3::Zero());
    ASSERT_EQ(modes.count, 2);
    Data data(paper.model);
    for (const AssemblyMode& mode : modes) {
        Pose p = mode.p + Pose(0.01, 0.002, -0.002);
        ASSERT_TRUE(trackPose(paper.model, data, ActuatorVector(Vector3::Zero()), p).ok());
        EXPECT_LE((p - mode.p).cwiseAbs().maxCoeff(), 1e-12) << describePose(mode.p);
    }
}

}  // namespace
}  // namespace nocdyn::test
