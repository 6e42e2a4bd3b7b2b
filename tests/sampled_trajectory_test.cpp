// Sampled trajectories: the not-a-knot spline of positions, the integrated spline of
// accelerations, and the CSV reader's refusals (file, line and column named).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "nocdyn/error.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

/// Non-uniform knots on [0, 1.2].
std::vector<double> unevenTimes() {
    std::vector<double> t;
    double s = 0.0;
    for (int i = 0; i < 25; ++i) {
        t.push_back(s);
        s += 0.03 + 0.04 * std::abs(std::sin(1.7 * i));
    }
    return t;
}

TEST(SampledTrajectory, PositionSplineReproducesACubicAndItsDerivativesExactly) {
    const auto cubic = [](double t) { return 0.3 - 1.2 * t + 0.7 * t * t - 2.1 * t * t * t; };
    const std::vector<double> t = unevenTimes();
    std::vector<double> q;
    for (double ti : t) q.push_back(cubic(ti));
    const SampledAxis axis = splineOfPositions(t, q);
    for (double s = 0.0; s <= t.back(); s += 0.0137) {
        double v = 0, dv = 0, ddv = 0;
        axis.evaluate(s, v, dv, ddv);
        EXPECT_NEAR(v, cubic(s), 1e-12) << s;
        EXPECT_NEAR(dv, -1.2 + 1.4 * s - 6.3 * s * s, 1e-11) << s;
        EXPECT_NEAR(ddv, 1.4 - 12.6 * s, 1e-10) << s;
    }
}

TEST(SampledTrajectory, DerivativesAgreeWithFiniteDifferencesOfTheSpline) {
    const std::vector<double> t = unevenTimes();
    std::vector<double> q;
    for (double ti : t) q.push_back(std::sin(7.0 * ti) + 0.2 * std::cos(19.0 * ti));
    const SampledAxis axis = splineOfPositions(t, q);
    const double h = 1e-6;
    for (double s = 0.011; s < t.back() - 0.01; s += 0.0371) {
        double v0, d0, dd0, vp, dp, ddp, vm, dm, ddm;
        axis.evaluate(s, v0, d0, dd0);
        axis.evaluate(s + h, vp, dp, ddp);
        axis.evaluate(s - h, vm, dm, ddm);
        EXPECT_NEAR(d0, (vp - vm) / (2 * h), 1e-6) << s;
        EXPECT_NEAR(dd0, (dp - dm) / (2 * h), 1e-4) << s;
    }
    // C2 at the knots: value, slope and curvature continuous
    for (std::size_t i = 1; i + 1 < t.size(); ++i) {
        double va, da, dda, vb, db, ddb;
        axis.evaluate(t[i] - 1e-12, va, da, dda);
        axis.evaluate(t[i] + 1e-12, vb, db, ddb);
        EXPECT_NEAR(va, vb, 1e-9);
        EXPECT_NEAR(da, db, 1e-8);
        EXPECT_NEAR(dda, ddb, 1e-6);
    }
}

TEST(SampledTrajectory, AccelerationSplineIntegratesACubicAccelerationExactly) {
    // a = 2 - 3 t + 4 t^3, v = 2 t - 1.5 t^2 + t^4, q = t^2 - 0.5 t^3 + 0.2 t^5 (from rest)
    const std::vector<double> t = unevenTimes();
    std::vector<double> a;
    for (double ti : t) a.push_back(2.0 - 3.0 * ti + 4.0 * ti * ti * ti);
    const SampledAxis axis = splineOfAccelerations(t, a);
    for (double s = 0.0; s <= t.back(); s += 0.0291) {
        double q, dq, ddq;
        axis.evaluate(s, q, dq, ddq);
        EXPECT_NEAR(ddq, 2.0 - 3.0 * s + 4.0 * s * s * s, 1e-10);
        EXPECT_NEAR(dq, 2.0 * s - 1.5 * s * s + std::pow(s, 4), 1e-11);
        EXPECT_NEAR(q, s * s - 0.5 * s * s * s + 0.2 * std::pow(s, 5), 1e-11);
    }
}

TEST(SampledTrajectory, IntegratedHarmonicAccelerationMatchesItsClosedFormDisplacement) {
    // a = -w^2 A sin(w t) from v0 = A w: q = A sin(w t), sampled at 200 Hz
    const double w = 2.0 * 3.141592653589793 * 2.0, amp = 0.01;
    std::vector<double> t, a;
    for (int i = 0; i <= 400; ++i) {
        t.push_back(i / 200.0);
        a.push_back(-w * w * amp * std::sin(w * t.back()));
    }
    const SampledAxis axis = splineOfAccelerations(t, a, amp * w, 0.0);
    double q, dq, ddq;
    axis.evaluate(2.0, q, dq, ddq);
    EXPECT_NEAR(q, amp * std::sin(w * 2.0), 1e-7);
    EXPECT_NEAR(dq, amp * w * std::cos(w * 2.0), 1e-6);
}

TEST(SampledTrajectory, ExtrapolatesBeyondTheEndsAtTheEndRate) {
    const SampledAxis axis = splineOfPositions(std::vector<double>{0.0, 1.0}, std::vector<double>{1.0, 3.0});
    double q, dq, ddq;
    axis.evaluate(1.5, q, dq, ddq);
    EXPECT_DOUBLE_EQ(q, 4.0);
    EXPECT_DOUBLE_EQ(dq, 2.0);
    EXPECT_DOUBLE_EQ(ddq, 0.0);
}

TEST(SampledTrajectory, CsvTrajectoryDrivesPoseTrajectoryEvaluate) {
    const PoseTrajectory traj =
        io::parseTrajectoryCsv("t,x,ay,theta\n0,0,1,0\n0.1,0.001,1,0.01\n0.25,0.004,1,0.02\n0.3,0.009,1,0\n", "m.csv");
    ASSERT_TRUE(traj.duration);
    EXPECT_DOUBLE_EQ(*traj.duration, 0.3);
    Pose p, dp, ddp;
    traj.evaluate(0.2, p, dp, ddp);
    EXPECT_NEAR(p(2), 0.5 * 0.2 * 0.2, 1e-15);  // constant ay = 1 from rest
    EXPECT_NEAR(dp(2), 0.2, 1e-15);
    EXPECT_NEAR(ddp(2), 1.0, 1e-15);
    traj.evaluate(0.1, p, dp, ddp);
    EXPECT_NEAR(p(1), 0.001, 1e-15);
    EXPECT_NEAR(p(0), 0.01, 1e-15);
}

void expectCsvError(const std::string& text, std::initializer_list<const char*> fragments) {
    try {
        (void)io::parseTrajectoryCsv(text, "motion.csv");
        ADD_FAILURE() << "accepted:\n" << text;
    } catch (const Error& e) {
        for (const char* f : fragments) EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
    }
}

TEST(SampledTrajectory, CsvRefusalsNameFileLineAndColumn) {
    expectCsvError("t,x\n0,0\n0.2,1\n0.1,2\n", {"motion.csv:4:", "column 't'", "not after"});
    expectCsvError("t,x\n0,0\n0.1,1\n0.2,2\n5,3\n5.1,2\n", {"motion.csv:5:", "gap"});
    expectCsvError("t,x\n0,0\n0.1,nan\n", {"motion.csv:3:", "column 'x'"});
    expectCsvError("x,y\n0,0\n0.1,1\n", {"motion.csv:1:", "column 't'", "missing"});
    expectCsvError("t\n0\n0.1\n", {"motion.csv:1:", "missing columns"});
    expectCsvError("t,x,ax\n0,0,0\n0.1,1,1\n", {"motion.csv:1:", "column 'ax'"});
    expectCsvError("t,z\n0,0\n0.1,1\n", {"motion.csv:1:", "column 'z'", "unknown"});
    expectCsvError("t,x\n0,0\n", {"motion.csv:1:", "at least 2"});
}

// Finite samples whose spline would overflow: a time beyond the bound (a fuzzer's find: the
// acceleration 1e45 integrated over 7e101 s), values beyond the bounds, steps so short that the
// divided differences overflow.
TEST(SampledTrajectory, CsvRefusesSamplesWhoseSplineWouldOverflow) {
    expectCsvError("t,ax,ay,alpha\n0,0,0,0\n0.02,-1,0.5,0\n7e101,0,0.5,0\n",
                   {"motion.csv:4:", "column 't'", "out of range"});
    expectCsvError("t,ax\n0,1e45\n0.02,-1\n0.04,0\n", {"motion.csv:2:", "column 'ax'", "out of range"});
    expectCsvError("t,x\n0,0\n0.02,1e4\n", {"motion.csv:3:", "column 'x'", "out of range"});
    expectCsvError("t,x\n0,0\n1e-300,1000\n2e-300,-1000\n3e-300,1000\n", {"motion.csv:3:", "less than 1e-09 s"});
}

TEST(SampledTrajectory, SplineBuildersRefuseOverflow) {
    EXPECT_THROW((void)splineOfPositions({0.0, 1e-300, 2e-300}, {0.0, 1e300, 0.0}), Error);
    EXPECT_THROW((void)splineOfAccelerations({0.0, 1e200, 2e200}, {1e200, 0.0, 1e200}), Error);
    // and accept the ordinary
    EXPECT_NO_THROW((void)splineOfAccelerations({0.0, 0.01, 0.02}, {1.0, 0.0, 1.0}));
}

}  // namespace
}  // namespace nocdyn::test
