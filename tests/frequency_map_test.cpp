// The first natural frequency over the workspace (analysis/frequency_map.hpp) and the design
// metric first_frequency_min (analysis/design.hpp) that is its lowest value.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "allocation_counter.hpp"
#include "nocdyn/analysis/design.hpp"
#include "nocdyn/analysis/frequency_map.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"

namespace nocdyn {
namespace {

RobotDescription robotFile(const std::string& name) {
    return io::loadRobotDescription(std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml");
}

WorkspaceMap mapAtHome(const Model& model, int resolution) {
    return workspaceMap(model, WorkspaceOptions{model.home(0), resolution, false});
}

TEST(FirstFrequencyMap, EveryFeasiblePointHoldsStiffnessAndModesAndTheLowestIsWhereReported) {
    const Model model(robotFile("paper-3prr-compliant"));
    const WorkspaceMap map = mapAtHome(model, 41);
    const FirstFrequencyMap f = firstFrequencyMap(model, map);
    ASSERT_EQ(f.first.size(), map.cells.size());
    const StiffnessModel compliance(model);
    Data data(model);
    StiffnessData K;
    LumpedModes modes;
    int feasible = 0;
    double lowest = std::numeric_limits<double>::infinity(), highest = 0.0;
    for (int i = 0; i < map.n; ++i) {
        for (int k = 0; k < map.n; ++k) {
            const double value = f.at(i, k, map.n);
            if (map.cell(i, k) != WorkspaceCell::feasible) {
                EXPECT_TRUE(std::isnan(value)) << i << ", " << k;
                continue;
            }
            ++feasible;
            ASSERT_TRUE(stiffnessAndModes(model, compliance, data,
                                          Pose(map.theta, map.x0 + i * map.step, map.y0 + k * map.step), K, modes));
            EXPECT_EQ(value, modes.frequency(0));
            lowest = std::min(lowest, value);
            highest = std::max(highest, value);
        }
    }
    EXPECT_EQ(f.points, feasible);
    EXPECT_GT(feasible, 100);
    EXPECT_EQ(f.lowest, lowest);
    EXPECT_EQ(f.highest, highest);
    EXPECT_EQ(f.at(f.lowest_i, f.lowest_k, map.n), f.lowest);
    EXPECT_EQ(f.lowest_x, map.x0 + f.lowest_i * map.step);
    EXPECT_EQ(f.lowest_y, map.y0 + f.lowest_k * map.step);
    // the reported point, recomputed from its (x, y) alone
    ASSERT_TRUE(stiffnessAndModes(model, compliance, data, Pose(map.theta, f.lowest_x, f.lowest_y), K, modes));
    EXPECT_EQ(modes.frequency(0), f.lowest);
    // the voice coils' 2e5 N/m under about 3 kg each: near 40 Hz (the file's comment), and it varies
    EXPECT_GT(f.lowest, 35.0);
    EXPECT_LT(f.highest, 45.0);
    EXPECT_GT(f.highest - f.lowest, 0.1);
}

TEST(FirstFrequencyMap, AllocatesNothingPerGridPoint) {
    // elastic links: the elastodynamic model (which allocates) checks only the points next to
    // a limb singularity (nearLimbSingularity), and this map has none
    const Model model(robotFile("paper-3prr-compliant"));
    ASSERT_TRUE(StiffnessModel(model).any_elastic);
    const WorkspaceMap small = mapAtHome(model, 21), large = mapAtHome(model, 81);
    const auto allocations = [&](const WorkspaceMap& map) {
        const long before = test::allocationCount();
        const FirstFrequencyMap f = firstFrequencyMap(model, map);
        const long count = test::allocationCount() - before;
        EXPECT_GT(f.points, 0);
        EXPECT_EQ(f.elastodynamic_checks, 0);
        return count;
    };
    (void)allocations(small);
    // 16 times the points, the same allocations: none per point
    EXPECT_EQ(allocations(small), allocations(large));
}

TEST(FirstFrequencyMap, ReportsProgressPerColumnAndStopsWhenProgressThrows) {
    const Model model(robotFile("paper-3prr-compliant"));
    const WorkspaceMap map = mapAtHome(model, 21);
    int calls = 0, last = 0;
    (void)firstFrequencyMap(model, map, [&](int done, int total) {
        ++calls;
        last = done;
        EXPECT_EQ(total, 21);
    });
    EXPECT_EQ(calls, 21);
    EXPECT_EQ(last, 21);
    struct Stop {};
    calls = 0;
    EXPECT_THROW((void)firstFrequencyMap(model, map,
                                         [&](int, int) {
                                             if (++calls == 3) throw Stop{};
                                         }),
                 Stop);
    EXPECT_EQ(calls, 3);
}

TEST(FirstFrequencyMap, ARobotWithoutComplianceIsRefusedByName) {
    const Model model(robotFile("3-rrr"));
    const WorkspaceMap map = mapAtHome(model, 21);
    try {
        (void)firstFrequencyMap(model, map);
        FAIL() << "a robot without compliance was mapped";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("robot '3-rrr'"), std::string::npos) << message;
        EXPECT_NE(message.find("3-rrr.yaml"), std::string::npos) << message;
        EXPECT_NE(message.find("declares no compliance"), std::string::npos) << message;
    }
}

TEST(FirstFrequencyMinMetric, IsTheMapsLowestOnTheSameGrid) {
    const DesignMetric metric = parseDesignMetric("first_frequency_min");
    EXPECT_EQ(metric.kind, DesignMetricKind::first_frequency_min);
    EXPECT_EQ(metric.name(), "first_frequency_min");
    EXPECT_EQ(metric.unit(), "Hz");
    EXPECT_TRUE(metric.larger_is_better());
    EXPECT_FALSE(metric.along_trajectory());

    const RobotDescription robot = robotFile("paper-3prr-compliant");
    DesignOptions options;
    options.workspace.resolution = 41;
    const DesignEvaluation e = evaluateDesign(
        robot, {parseDesignMetric("workspace_area"), metric, parseDesignMetric("condition_worst")}, options);
    ASSERT_TRUE(e.feasible) << e.reason;
    const Model model(robot);
    const WorkspaceMap map = mapAtHome(model, 41);
    EXPECT_EQ(e.values[0], map.area);
    EXPECT_EQ(e.values[1], firstFrequencyMap(model, map).lowest);
    EXPECT_EQ(e.values[2], dexterity(map).worst);
    EXPECT_GT(e.values[1], 35.0);
}

TEST(FirstFrequencyMinMetric, ADesignWithoutComplianceIsInfeasibleWithTheReason) {
    DesignOptions options;
    options.workspace.resolution = 21;
    const DesignEvaluation e = evaluateDesign(
        robotFile("3-rrr"), {parseDesignMetric("moving_mass"), parseDesignMetric("first_frequency_min")}, options);
    EXPECT_FALSE(e.feasible);
    EXPECT_NE(e.reason.find("declares no compliance"), std::string::npos) << e.reason;
    EXPECT_NE(e.reason.find("first_frequency_min"), std::string::npos) << e.reason;
    EXPECT_TRUE(std::isnan(e.values[0]) && std::isnan(e.values[1]));
}

}  // namespace
}  // namespace nocdyn
