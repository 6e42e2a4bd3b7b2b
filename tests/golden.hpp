// The paper's trajectories against the independent golden values in tests/data/golden
// (virtual power with 50-digit finite differences, no NOC): one evaluation per golden row,
// compared column by column.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "nocdyn/trajectory.hpp"
#include "support.hpp"

namespace nocdyn::test {

struct GoldenCase {
    const char* file;
    PoseTrajectory (*trajectory)();
    const char* robot;  ///< example robot: the paper's prototype, short or general form
};

// Relative 1e-9, with an absolute floor of 1e-12 of the column's peak for values that pass
// through zero (u is ~1e-19 m at t = 0 in the golden file).
inline constexpr double kGoldenRelative = 1e-9;
inline constexpr double kGoldenFloorOfPeak = 1e-12;

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
            const Tolerance tolerance{kGoldenFloorOfPeak * peak[c], kGoldenRelative};
            EXPECT_TRUE(tolerance.accepts(ours[c], expected))
                << golden.file << " (" << golden.robot << ") t = " << t << " " << columns[c] << ": ours " << ours[c]
                << ", golden " << expected;
            const double error = std::abs(ours[c] - expected);
            worst_of_peak = std::max(worst_of_peak, error / peak[c]);
            if (std::abs(expected) > 1e-6 * peak[c]) worst = std::max(worst, error / std::abs(expected));
        }
    }
    ::testing::Test::RecordProperty("largest_relative_error", std::to_string(worst));
    std::printf("%s (%s): largest error %.3g relative to the value, %.3g relative to the column peak\n", golden.file,
                golden.robot, worst, worst_of_peak);
}

}  // namespace nocdyn::test
