// The paper's trajectories against the independent golden values in ../shared/golden
// (virtual power with 50-digit finite differences, no NOC).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "nocdyn/dynamics.hpp"

#include "nocdyn/trajectory.hpp"
#include "support.hpp"

namespace nocdyn::test {
namespace {

struct GoldenCase {
    const char* file;
    PoseTrajectory (*trajectory)();
};

class GoldenTrajectory : public ::testing::TestWithParam<GoldenCase> {};

// Relative 1e-9, with an absolute floor of 1e-12 of the column's peak for values that pass
// through zero (u is ~1e-19 m at t = 0 in the golden file).
constexpr double kRelative = 1e-9;
constexpr double kFloorOfPeak = 1e-12;

/// u1..3, du1..3, ddu1..3, tau1..3 and the kinetic energy at one pose sample.
using Evaluation = std::array<double, 13>;

/// Compares one model's evaluation with every row of a golden file.
template <typename Evaluate>
void compareWithGolden(const GoldenCase& golden, Evaluate evaluate) {
    const io::Table table = io::readCsvFile(goldenPath(golden.file));
    ASSERT_EQ(table.rows.size(), 20u);
    const PoseTrajectory trajectory = golden.trajectory();
    const std::vector<std::string> columns = {"u1",   "u2",   "u3",   "du1",  "du2",  "du3",    "ddu1",
                                              "ddu2", "ddu3", "tau1", "tau2", "tau3", "kinetic"};
    std::vector<double> peak(columns.size(), 0.0);
    for (const auto& row : table.rows) {
        for (std::size_t c = 0; c < columns.size(); ++c)
            peak[c] = std::max(peak[c], std::abs(row[table.column(columns[c])]));
    }
    double worst = 0.0;          // relative to the value, where it is above 1e-6 of the peak
    double worst_of_peak = 0.0;  // relative to the column's peak
    for (const auto& row : table.rows) {
        const double t = row[table.column("t")];
        Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        EXPECT_NEAR(p(1), row[table.column("x")], 1e-15);
        EXPECT_NEAR(p(2), row[table.column("y")], 1e-15);
        EXPECT_NEAR(p(0), row[table.column("theta")], 1e-15);
        const Evaluation ours = evaluate(p, dp, ddp);
        for (std::size_t c = 0; c < columns.size(); ++c) {
            const double expected = row[table.column(columns[c])];
            const Tolerance tolerance{kFloorOfPeak * peak[c], kRelative};
            EXPECT_TRUE(tolerance.accepts(ours[c], expected))
                << golden.file << " t = " << t << " " << columns[c] << ": ours " << ours[c] << ", golden " << expected;
            const double error = std::abs(ours[c] - expected);
            worst_of_peak = std::max(worst_of_peak, error / peak[c]);
            if (std::abs(expected) > 1e-6 * peak[c]) worst = std::max(worst, error / std::abs(expected));
        }
    }
    ::testing::Test::RecordProperty("largest_relative_error", std::to_string(worst));
    std::printf("%s: largest error %.3g relative to the value, %.3g relative to the column peak\n", golden.file, worst,
                worst_of_peak);
}

TEST_P(GoldenTrajectory, ReproducesGoldenJointMotionForcesAndEnergyTo1e9Relative) {
    const prr3::Model model;
    prr3::Data data;
    compareWithGolden(GetParam(), [&](const Pose& p, const Twist& dp, const Twist& ddp) {
        solve(model, data, p, dp, ddp);
        return Evaluation{data.u(0),
                          data.u(1),
                          data.u(2),
                          data.du(0),
                          data.du(1),
                          data.du(2),
                          data.ddu(0),
                          data.ddu(1),
                          data.ddu(2),
                          data.tau(0),
                          data.tau(1),
                          data.tau(2),
                          prr3::kineticEnergy(model, data)};
    });
}

// The general model, built from the short form, on its full and lean paths.
TEST_P(GoldenTrajectory, GeneralModelReproducesGoldenValuesOnBothPaths) {
    const Model model{RobotParameters{}};
    Data full(model), lean(model);
    compareWithGolden(GetParam(), [&](const Pose& p, const Twist& dp, const Twist& ddp) {
        const Status status = inverseDynamics(model, full, p, dp, ddp);
        EXPECT_TRUE(status.ok()) << describe(status, model);
        const Status fast = inverseDynamicsFast(model, lean, p, dp, ddp);
        EXPECT_TRUE(fast.ok()) << describe(fast, model);
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(lean.tau(a), full.tau(a), 1e-12 * (1.0 + std::abs(full.tau(a))));
        return Evaluation{full.u(0),
                          full.u(1),
                          full.u(2),
                          full.du(0),
                          full.du(1),
                          full.du(2),
                          full.ddu(0),
                          full.ddu(1),
                          full.ddu(2),
                          full.tau(0),
                          full.tau(1),
                          full.tau(2),
                          kineticEnergy(model, full)};
    });
}

INSTANTIATE_TEST_SUITE_P(Paper, GoldenTrajectory,
                         ::testing::Values(GoldenCase{"paper_trajectory1.csv", &paperTrajectory1},
                                           GoldenCase{"paper_trajectory2.csv", &paperTrajectory2}),
                         [](const auto& info) { return std::string(info.param.file).substr(0, 17); });

}  // namespace
}  // namespace nocdyn::test
