// Parametric robot files (expressions of named parameters) and the metrics of one design
// (design.hpp, io/design.hpp): each metric is the number the single-robot computation gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <thread>

#include "nocdyn/analysis/design.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/tables/design.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/analysis/workspace.hpp"

namespace nocdyn {
namespace {

const std::string kSource = NOCDYN_SOURCE_DIR;
/// The plain robot files give 6 significant digits.
constexpr double kPrintedDigits = 2e-6;

std::string text(const std::string& relative) { return io::readRobotFileText(kSource + "/" + relative); }

std::string errorOf(const std::string& yaml, const io::ParameterSet& overrides = {}) {
    try {
        (void)io::parseRobotDescription(yaml, "family.yaml", overrides);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

void expectSameRobot(const RobotDescription& a, const RobotDescription& b, double tolerance) {
    ASSERT_EQ(a.limbs.size(), b.limbs.size());
    EXPECT_NEAR(a.platform.mass, b.platform.mass, tolerance);
    for (std::size_t j = 0; j < a.limbs.size(); ++j) {
        for (std::size_t k = 0; k < 3; ++k) {
            const JointDescription &ja = a.limbs[j].joints[k], &jb = b.limbs[j].joints[k];
            EXPECT_EQ(ja.type, jb.type) << "limb " << j << " joint " << k;
            // (a P joint's point is not part of its screw: the short form's expansion keeps the slider's)
            if (ja.type == JointType::revolute) {
                EXPECT_NEAR((ja.point - jb.point).norm(), 0.0, tolerance) << "limb " << j << " joint " << k;
            }
            EXPECT_NEAR((ja.direction - jb.direction).norm(), 0.0, tolerance) << "limb " << j << " joint " << k;
            EXPECT_EQ(ja.actuated, jb.actuated);
        }
        for (std::size_t k = 0; k < 2; ++k) {
            const BodyDescription &ba = a.limbs[j].bodies[k], &bb = b.limbs[j].bodies[k];
            EXPECT_NEAR(ba.mass, bb.mass, tolerance) << "limb " << j << " body " << k;
            EXPECT_NEAR(ba.inertia, bb.inertia, tolerance) << "limb " << j << " body " << k;
            EXPECT_NEAR((ba.com - bb.com).norm(), 0.0, tolerance) << "limb " << j << " body " << k;
        }
    }
}

const char* const kSmall = R"yaml(parameters:
  r: 0.2
  half: r / 2
  theta0: 7 * pi / 6
platform: {mass: 1.0, inertia: 0.01}
limbs:
  - joints:
      - {type: R, point: [r * cos(theta0), r * sin(theta0)], actuated: true}
      - {type: R, point: [-0.1, -0.05]}
      - {type: R, point: [-half, 0.0]}
    bodies:
      - {mass: 0.2, inertia: 0.001, com: [-0.15, -0.07]}
      - {mass: 0.1, inertia: "max(0.001, 0.0005)", com: [-0.1, -0.02]}
)yaml";

TEST(ParametricRobotFile, ThreeRrrFamilyAtItsValuesIsTheExampleRobot) {
    const RobotDescription family = io::parseRobotDescription(text("examples/design_3rrr/family.yaml"), "family");
    expectSameRobot(family, io::exampleRobot("3-rrr"), kPrintedDigits);
}

TEST(ParametricRobotFile, VibrationGeneratorFamilyAtItsValuesIsThePaperPrototype) {
    const RobotDescription family =
        io::parseRobotDescription(text("examples/design_vibration_generator/family.yaml"), "family");
    expectSameRobot(family, io::exampleRobot("paper-3prr"), 1e-12);
}

TEST(ParametricRobotFile, ExpressionsUseParametersAndPi) {
    const std::string yaml = std::string(kSmall);
    const io::ParameterSet declared = io::robotFileParameters(yaml, "family.yaml");
    ASSERT_EQ(declared.size(), 3u);
    EXPECT_EQ(declared[1].name, "half");
    EXPECT_DOUBLE_EQ(declared[1].value, 0.1);
    EXPECT_DOUBLE_EQ(declared[2].value, 7.0 * M_PI / 6.0);
}

TEST(ParametricRobotFile, AnOverrideChangesTheParameterAndEveryValueDerivedFromIt) {
    const io::ParameterSet set = io::robotFileParameters(kSmall, "family.yaml", {{"r", 0.3}});
    EXPECT_DOUBLE_EQ(set[0].value, 0.3);
    EXPECT_DOUBLE_EQ(set[1].value, 0.15);  // half = r / 2
    EXPECT_NE(errorOf(kSmall, {{"nope", 1.0}}).find("parameter 'nope' is set but the file declares only: r, half"),
              std::string::npos)
        << errorOf(kSmall, {{"nope", 1.0}});
}

TEST(ParametricRobotFile, AnErrorNamesFileLineFieldAndExpression) {
    std::string yaml = text("examples/design_3rrr/family.yaml");
    const auto at = yaml.find("[ex1, ey1]");
    yaml.replace(at, 10, "[ex1, ey1 + ey9]");
    const auto line =
        std::to_string(1 + std::count(yaml.begin(), yaml.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    const std::string message = errorOf(yaml);
    EXPECT_NE(message.find("family.yaml:" + line +
                           ": limbs[0].joints[1].point: expression 'ey1 + ey9': unknown name "
                           "'ey9'"),
              std::string::npos)
        << message;
}

TEST(ParametricRobotFile, OnlyTheDocumentedFunctionsAndOperatorsAreAccepted) {
    for (const std::string bad : {"exp(1)", "log(2)", "2 * _pi", "1 < 2", "r = 3", "1 ? 2 : 3", "r && 1", "sum(1, 2)",
                                  "system(1)", "`ls`", "$HOME", "1; 2"}) {
        std::string yaml = kSmall;
        yaml.replace(yaml.find("mass: 1.0"), 9, "mass: \"" + bad + "\"");
        const std::string message = errorOf(yaml);
        EXPECT_NE(message.find("family.yaml:5: platform.mass: expression '" + bad + "'"), std::string::npos)
            << bad << ": " << message;
    }
}

TEST(ParametricRobotFile, ANonFiniteResultIsAnError) {
    std::string yaml = kSmall;
    yaml.replace(yaml.find("mass: 1.0"), 9, "mass: sqrt(-r)");
    EXPECT_NE(errorOf(yaml).find("platform.mass: expression 'sqrt(-r)': the sub-expression sqrt(-0.2) = nan is not "
                                 "finite"),
              std::string::npos)
        << errorOf(yaml);
    yaml = kSmall;
    yaml.replace(yaml.find("mass: 1.0"), 9, "mass: 1 / (r - r)");
    EXPECT_NE(errorOf(yaml).find("the sub-expression 1 / 0 = inf is not finite"), std::string::npos) << errorOf(yaml);
}

TEST(ParametricRobotFile, AssignmentsAreParsedStrictly) {
    EXPECT_EQ(io::parseParameterAssignment("r_b=0.25").value, 0.25);
    for (const std::string bad : {"r_b", "=1", "r_b=", "r_b=1x", "r b=1", "pi=3", "r_b=nan", "r_b=0x10"}) {
        EXPECT_THROW((void)io::parseParameterAssignment(bad), Error) << bad;
    }
}

TEST(ParametricRobotFile, ThePlainFormOfADesignReadsBackAsTheSameRobot) {
    const RobotDescription robot =
        io::parseRobotDescription(text("examples/design_3rrr/family.yaml"), "family.yaml", {{"r_b", 0.25}});
    const RobotDescription again = io::parseRobotDescription(io::descriptionToYaml(robot), "plain.yaml");
    expectSameRobot(robot, again, 0.0);
    EXPECT_DOUBLE_EQ(robot.limbs[1].joints[0].point.x(), 0.25 * std::cos(M_PI / 6.0));
}

tables::DesignFamily threeRrrFamily() {
    tables::DesignFamily family;
    family.text = text("examples/design_3rrr/family.yaml");
    family.source = "family.yaml";
    family.ranges = {{"r_b", 0.15, 0.25}, {"l1", 0.08, 0.14}};
    return family;
}

TEST(DesignMetrics, EachMetricIsTheSingleRobotComputation) {
    const tables::DesignFamily family = threeRrrFamily();
    const std::vector<double> point{0.21, 0.11};
    std::vector<DesignMetric> metrics;
    for (const char* name :
         {"workspace_area", "condition_median", "condition_worst", "envelope_x@50", "envelope_theta@20", "moving_mass"})
        metrics.push_back(parseDesignMetric(name));
    DesignOptions options;
    options.workspace.resolution = 41;
    const DesignEvaluation e = tables::evaluateFamilyDesign(family, point, metrics, options);
    ASSERT_TRUE(e.feasible) << e.reason;
    const Model model(tables::designRobot(family, point));
    const WorkspaceMap map = workspaceMap(model, {model.home(0), 41});
    EXPECT_EQ(e.values[0], map.area);
    EXPECT_EQ(e.values[1], dexterity(map).median);
    EXPECT_EQ(e.values[2], dexterity(map).worst);
    EXPECT_GE(e.values[2], e.values[1]);
    EXPECT_GE(e.values[1], 1.0);
    EXPECT_EQ(e.values[3], maximumAmplitude(model, EnvelopeAxis::x, 50.0).amplitude);
    EXPECT_EQ(e.values[4], maximumAmplitude(model, EnvelopeAxis::theta, 20.0).amplitude);
    EXPECT_GT(e.values[3], 0.0);
    // platform 1.75257 kg, proximal links 0.30 kg and distal 0.25 kg at 105.157 mm, by length
    EXPECT_NEAR(e.values[5], 1.75257 + 3 * 0.30 * 0.11 / 0.105157 + 3 * 0.25, 1e-12);
}

TEST(DesignMetrics, TrajectoryMetricsArePeaksOfTheInverseDynamics) {
    const RobotDescription robot = io::exampleRobot("paper-3prr");
    std::vector<DesignMetric> metrics;
    for (const char* name : {"peak_force", "rms_force", "stroke", "peak_reaction"})
        metrics.push_back(parseDesignMetric(name));
    DesignOptions options;
    options.trajectory = paperTrajectory1();
    options.duration = 0.1;
    options.rate = 2000.0;
    const DesignEvaluation e = evaluateDesign(robot, metrics, options);
    ASSERT_TRUE(e.feasible) << e.reason;
    const InverseDynamicsSeries series =
        sampleInverseDynamics(Model(robot), *options.trajectory, sampleTimes(0.1, 2000.0));
    double peak = 0.0, stroke = 0.0, rms = 0.0;
    for (int a = 0; a < 3; ++a) {
        double lo = INFINITY, hi = -INFINITY, sum = 0.0;
        for (const InverseDynamicsSample& s : series.samples) {
            peak = std::max(peak, std::abs(s.tau(a)));
            lo = std::min(lo, s.u(a));
            hi = std::max(hi, s.u(a));
            sum += s.tau(a) * s.tau(a);
        }
        stroke = std::max(stroke, hi - lo);
        rms = std::max(rms, std::sqrt(sum / static_cast<double>(series.samples.size())));
    }
    EXPECT_DOUBLE_EQ(e.values[0], peak);
    EXPECT_DOUBLE_EQ(e.values[1], rms);
    EXPECT_DOUBLE_EQ(e.values[2], stroke);
    EXPECT_GT(e.values[3], e.values[0] * 0.5);  // a slider bearing carries about its actuator's force
}

TEST(DesignMetrics, ADesignThatDoesNotAssembleIsARowWithItsReason) {
    const tables::DesignFamily family = threeRrrFamily();
    const std::vector<DesignMetric> metrics{parseDesignMetric("workspace_area")};
    // links of 2 x 0.03 m cannot span r_b - r_p = 0.1365 m: h = sqrt(negative)
    tables::DesignFamily shorter = family;
    shorter.fixed = {{"l2", 0.03}};
    const DesignEvaluation e = tables::evaluateFamilyDesign(shorter, {0.2, 0.03}, metrics, {});
    EXPECT_FALSE(e.feasible);
    EXPECT_NE(e.reason.find("expression 'sqrt(l1^2 - ea^2)': the sub-expression sqrt("), std::string::npos) << e.reason;
    EXPECT_NE(e.reason.find(") = nan is not finite"), std::string::npos) << e.reason;
    EXPECT_TRUE(std::isnan(e.values[0]));
}

TEST(DesignMetrics, NamesAreParsedAndUnknownOnesListTheAccepted) {
    EXPECT_EQ(parseDesignMetric("envelope_y@12.5").name(), "envelope_y@12.5");
    EXPECT_EQ(parseDesignMetric("envelope_theta@50").unit(), "rad");
    for (const std::string bad : {"envelope_z@50", "envelope_x@", "envelope_x@nan", "envelope_x@1e9", "area"}) {
        EXPECT_THROW((void)parseDesignMetric(bad), Error) << bad;
    }
}

TEST(DesignSweep, AGridHoldsBothEndsOfEveryRange) {
    const auto points = sweepPoints({{"a", 0.0, 1.0}, {"b", 2.0, 3.0}}, SweepKind::grid, 400, 0);
    ASSERT_EQ(points.size(), 400u);
    EXPECT_EQ(points.front(), (std::vector<double>{0.0, 2.0}));
    EXPECT_NEAR(points[1][1] - points[0][1], 1.0 / 19.0, 1e-15);
    EXPECT_EQ(points.back(), (std::vector<double>{1.0, 3.0}));
    EXPECT_THROW((void)sweepPoints({{"a", 0.0, 1.0}}, SweepKind::random, kMaxDesigns + 1, 0), Error);
    EXPECT_THROW((void)sweepPoints({{"a", 1.0, 0.0}}, SweepKind::random, 4, 0), Error);
    EXPECT_EQ(sweepPoints({{"a", 0.0, 1.0}}, SweepKind::random, 8, 7),
              sweepPoints({{"a", 0.0, 1.0}}, SweepKind::random, 8, 7));
}

TEST(DesignSweep, ParallelEvaluationRecordsEveryDesignOnce) {
    std::vector<int> seen(1000, 0);
    const std::size_t n = evaluateInParallel(
        seen.size(), 4,
        [](std::size_t i) {
            return DesignEvaluation{true, "", {static_cast<double>(i)}};
        },
        [&](std::size_t i, const DesignEvaluation& e) {
            ++seen[i];
            EXPECT_EQ(e.values[0], static_cast<double>(i));
        });
    EXPECT_EQ(n, seen.size());
    EXPECT_EQ(std::set<int>(seen.begin(), seen.end()), std::set<int>{1});
}

TEST(DesignSweep, TheQueueRecordsOnTheCallingThreadAndStopsWhenAsked) {
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<std::atomic<int>> evaluated(1000);
    std::vector<int> recorded(evaluated.size(), 0);
    std::size_t stops = 0;
    const std::size_t n = evaluateInParallel(
        evaluated.size(), 3,
        [&](std::size_t i) {
            EXPECT_NE(std::this_thread::get_id(), caller);
            ++evaluated[i];
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            return DesignEvaluation{true, "", {static_cast<double>(i)}};
        },
        [&](std::size_t i, DesignEvaluation&& e) {
            EXPECT_EQ(std::this_thread::get_id(), caller);
            EXPECT_EQ(e.values.at(0), static_cast<double>(i));
            ++recorded[i];
        },
        [&] {
            EXPECT_EQ(std::this_thread::get_id(), caller);
            return ++stops == 2;  // asked once more, then no new design starts
        });
    EXPECT_EQ(stops, 2U);
    // about 1 ms a design on 3 threads: the stop comes long before the 1000th
    EXPECT_LT(n, 200U);
    std::size_t total = 0;
    for (std::size_t i = 0; i < recorded.size(); ++i) {
        EXPECT_EQ(recorded[i], evaluated[i].load()) << i;  // every design evaluated is recorded, once
        total += static_cast<std::size_t>(recorded[i]);
    }
    EXPECT_EQ(total, n);
}

TEST(DesignSweep, TheQueueRecordsWhatFinishedThenRethrowsAFailure) {
    std::vector<int> recorded(50, 0);
    // one thread: designs 0..6 finish, 7 throws, no design after it starts
    EXPECT_THROW((void)evaluateInParallel(
                     recorded.size(), 1,
                     [](std::size_t i) {
                         if (i == 7) throw Error("design 7");
                         return DesignEvaluation{true, "", {1.0}};
                     },
                     [&](std::size_t i, DesignEvaluation&&) { ++recorded[i]; }),
                 Error);
    for (std::size_t i = 0; i < recorded.size(); ++i) EXPECT_EQ(recorded[i], i < 7 ? 1 : 0) << i;

    // an exception from record (an observer's stop) stops new designs and reaches the caller
    std::atomic<std::size_t> started{0};
    EXPECT_THROW((void)evaluateInParallel(
                     1000, 2,
                     [&](std::size_t) {
                         ++started;
                         std::this_thread::sleep_for(std::chrono::milliseconds(1));
                         return DesignEvaluation{true, "", {1.0}};
                     },
                     [](std::size_t, DesignEvaluation&&) { throw Error("stopped"); }),
                 Error);
    EXPECT_LT(started.load(), 100U);
}

TEST(DesignSweep, TheParetoFrontHoldsTheUndominatedFeasibleDesigns) {
    const std::vector<DesignMetric> metrics{parseDesignMetric("workspace_area"), parseDesignMetric("moving_mass")};
    // maximise the area, minimise the mass
    const std::vector<DesignEvaluation> designs{{true, "", {1.0, 1.0}}, {true, "", {2.0, 2.0}},
                                                {true, "", {1.5, 2.5}}, {false, "x", {9.0, 0.0}},
                                                {true, "", {2.0, 2.0}}, {true, "", {0.5, 1.0}}};
    EXPECT_EQ(paretoFront(designs, metrics), (std::vector<std::size_t>{0, 1, 4}));
    // the same by the senses alone, and with the mass maximised too: (2, 2) twice and (1.5, 2.5)
    EXPECT_EQ(paretoFront(designs, std::vector<bool>{true, false}), (std::vector<std::size_t>{0, 1, 4}));
    EXPECT_EQ(paretoFront(designs, std::vector<bool>{true, true}), (std::vector<std::size_t>{1, 2, 4}));
}

TEST(DesignSweep, ADesignWithANaNValueIsOnTheFrontAndDominatesNone) {
    // a NaN compares neither way: (NaN, 7) is not dominated by (3, 6), nor does it dominate
    // (1, 5), which (3, 6) does not dominate either; (0.5, 9) is dominated by (1, 5)
    const double nan = std::nan("");
    const std::vector<bool> larger{true, false, true};  // area, mass, a third metric
    for (const std::size_t metrics : {1U, 2U, 3U}) {
        std::vector<DesignEvaluation> designs{{true, "", {3.0, 6.0, 0.0}},
                                              {true, "", {nan, 7.0, 0.0}},
                                              {true, "", {1.0, 5.0, 0.0}},
                                              {true, "", {0.5, 9.0, 0.0}},
                                              {true, "", {nan, nan, nan}}};
        for (DesignEvaluation& d : designs) d.values.resize(metrics);
        const std::vector<bool> senses(larger.begin(), larger.begin() + static_cast<std::ptrdiff_t>(metrics));
        const std::vector<std::size_t> expected =
            metrics == 1 ? std::vector<std::size_t>{0, 1, 4} : std::vector<std::size_t>{0, 1, 2, 4};
        EXPECT_EQ(paretoFront(designs, senses), expected) << metrics << " metrics";
    }
    // a feasible design whose values are not one per metric is refused, not read past its end
    EXPECT_THROW((void)paretoFront({{true, "", {1.0}}}, std::vector<bool>{true, true}), Error);
}

std::string readJournal(const std::string& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(DesignJournal, AResumedSweepKeepsTheRecordedDesignsAndDropsAnUnfinishedLine) {
    const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "design_journal";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "journal.csv").string();
    const std::vector<std::string> columns{"design", "a", "workspace_area", "feasible", "reason"};
    {
        tables::DesignJournal journal(path, "sig", columns, 1, 1);
        journal.append({0, {0.1}, {true, "", {0.1 + 0.2}}});
        journal.append({3, {0.4}, {false, "limb 2, \"out\" of reach", {std::nan("")}}});
    }
    std::ofstream(path, std::ios::app) << "6,0.5,0.";  // killed mid-line
    // designs numbered from 1 where a person reads them: design 4 is record 3
    const std::string text = readJournal(path);
    EXPECT_NE(text.find("\n1,0.1,"), std::string::npos) << text;
    EXPECT_NE(text.find("\n4,0.4,"), std::string::npos) << text;
    tables::DesignJournal again(path, "sig", columns, 1, 1);
    ASSERT_EQ(again.previous().size(), 2u);
    EXPECT_EQ(again.previous()[0].index, 0u);
    EXPECT_EQ(again.previous()[0].evaluation.values[0], 0.1 + 0.2);
    EXPECT_EQ(again.previous()[1].index, 3u);
    EXPECT_EQ(again.previous()[1].evaluation.reason, "limb 2, \"out\" of reach");
    EXPECT_TRUE(std::isnan(again.previous()[1].evaluation.values[0]));
    EXPECT_THROW(tables::DesignJournal(path, "another sweep", columns, 1, 1), Error);
}

}  // namespace
}  // namespace nocdyn
