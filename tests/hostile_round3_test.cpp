// Hostile input, third round, at the library: each test holds one finding of the review with
// its exact input (docs/hardening.md lists them). Expressions in parametric robot files, AT2
// headers, the Pareto front, design ranges, the Markdown escaper and a singular mass matrix.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <random>
#include <string>
#include <vector>

#include "nocdyn/analysis/design.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"

namespace nocdyn::test {
namespace {

std::string readWhole(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The three limbs of examples/design_3rrr/family.yaml at its values (robots/3-rrr.yaml).
std::string limbs() {
    const std::string text = readWhole(std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rrr.yaml");
    return text.substr(text.find("limbs:\n") + 7);
}

/// A parametric robot file in block style, `value` standing for the platform's mass and
/// `parameter` a line of its own in parameters:.
std::string robotWithPlatformMass(const std::string& value, const std::string& parameter = "") {
    return "parameters:\n"
           "  r: 0.2\n" +
           parameter +
           "platform:\n"
           "  mass: " +
           value +
           "\n"
           "  inertia: 0.01\n"
           "limbs:\n" +
           limbs();
}

/// The message of parsing `yaml`, or "" when it parses.
std::string parseError(const std::string& yaml) {
    try {
        (void)io::parseRobotDescription(yaml, "family.yaml");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(HostileRound3Expressions, ADecimalCommaIsAnErrorNamingTheFieldNot75257Kilograms) {
    const std::string message = parseError(robotWithPlatformMass("1,75257"));
    EXPECT_TRUE(has(message, "platform.mass")) << message;
    EXPECT_TRUE(has(message, "comma outside a function's argument list")) << message;
    const std::string parameter = parseError(robotWithPlatformMass("m", "  m: 1,75257\n"));
    EXPECT_TRUE(has(parameter, "parameters.m")) << parameter;
    EXPECT_TRUE(has(parameter, "comma")) << parameter;
    // a comma in parentheses that are not a call is the same list
    EXPECT_TRUE(has(parseError(robotWithPlatformMass("\"max((1, 2), 3)\"")), "comma")) << "(1, 2)";
}

TEST(HostileRound3Expressions, CommasBetweenAFunctionsArgumentsStillWork) {
    EXPECT_EQ(parseError(robotWithPlatformMass("\"max(1.5, min(2, r))\"")), "");
    const RobotDescription robot = io::parseRobotDescription(robotWithPlatformMass("atan2(1, 1) * 4"), "f.yaml");
    EXPECT_DOUBLE_EQ(robot.platform.mass, M_PI);
}

TEST(HostileRound3Expressions, NanInsideMaxIsAnErrorNamingTheSubExpression) {
    // max(0, sqrt(-1)) gave 0 and max(sqrt(-1), 0) an error: both are errors now
    for (const char* expression : {"max(0, sqrt(-1))", "max(sqrt(-1), 0)"}) {
        const std::string message = parseError(robotWithPlatformMass(std::string("\"") + expression + "\""));
        EXPECT_TRUE(has(message, "platform.mass")) << message;
        EXPECT_TRUE(has(message, "sqrt(-1) = nan is not finite")) << message;
    }
}

TEST(HostileRound3Expressions, OneOverOneOverZeroIsAnErrorNotZero) {
    const std::string message = parseError(robotWithPlatformMass("\"1/(1/0)\""));
    EXPECT_TRUE(has(message, "1 / 0 = inf is not finite")) << message;
    // an overflow inside that a later division would bring back is refused the same way
    EXPECT_TRUE(has(parseError(robotWithPlatformMass("\"1e300 * 1e300 / 1e300\"")), "1e+300 * 1e+300 = inf"));
}

TEST(HostileRound3Expressions, ASignWithNothingAfterItIsNotAnInternalError) {
    const std::string message = parseError(robotWithPlatformMass("\"2 *+\""));
    EXPECT_FALSE(has(message, "Internal error")) << message;
    EXPECT_TRUE(has(message, "a sign that has no number after it")) << message;
}

const char* const kAt2Header =
    "PEER NGA STRONG MOTION DATABASE RECORD\n"
    "test\n"
    "ACCELERATION TIME SERIES IN UNITS OF G\n";

TEST(HostileRound3At2, AnNptsSmallerThanTheDataIsAnError) {
    const std::string text = std::string(kAt2Header) + "NPTS=    3, DT= .0100 SEC\n  0.1  0.2  0.3  0.4\n";
    try {
        (void)io::parseAt2(text, "short.AT2");
        ADD_FAILURE() << "a record cut to NPTS = 3 of its 4 values was accepted";
    } catch (const Error& e) {
        EXPECT_TRUE(has(e.what(), "short.AT2:5: the data go on past NPTS = 3 values (value 4 is '0.4')")) << e.what();
    }
    // a zero on the next line is data, not padding
    EXPECT_THROW((void)io::parseAt2(std::string(kAt2Header) + "NPTS=    2, DT= .01\n 0.1 0.2\n 0.0\n", "z.AT2"), Error);
    // the count agreeing with the data still reads, trailing blanks, blank lines and zeros
    // padding the last line included
    const io::GroundMotionRecord record = io::parseAt2(
        std::string(kAt2Header) + "NPTS=    4, DT= .0100 SEC\n  0.1  0.2\n  0.3  0.4  0.0  0.0 \n\n", "ok.AT2");
    EXPECT_EQ(record.acceleration.size(), 4u);
}

TEST(HostileRound3At2, TheRecordsShippedAndSharedAllAgreeWithTheirNpts) {
    int read = 0;
    for (const std::string& folder : {std::string(NOCDYN_SOURCE_DIR) + "/data", std::string("/work/shared/data")}) {
        std::error_code error;
        for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
            if (entry.path().extension() != ".AT2") continue;
            EXPECT_NO_THROW((void)io::readAt2File(entry.path().string())) << entry.path();
            ++read;
        }
    }
    EXPECT_GE(read, 1);
}

TEST(HostileRound3At2, ANulByteIsShownEscapedAndTheMessageGoesOn) {
    std::string text = std::string(kAt2Header) + "NPTS=    2, DT= .0100 SEC\n  0.1  0.2";
    text += std::string("\0", 1) + "x\n";
    try {
        (void)io::parseAt2(text, "nul.AT2");
        ADD_FAILURE() << "a NUL byte in a value was accepted";
    } catch (const Error& e) {
        const std::string what = e.what();  // as a C string: nothing after a raw NUL would show
        EXPECT_TRUE(has(what, "value 2 '0.2\\x00x' is not a finite decimal number")) << what;
    }
}

/// Indices of the feasible designs no other dominates, by comparing every pair (the definition).
std::vector<std::size_t> bruteForceFront(const std::vector<DesignEvaluation>& designs,
                                         const std::vector<DesignMetric>& metrics) {
    std::vector<std::size_t> front;
    for (std::size_t i = 0; i < designs.size(); ++i) {
        if (!designs[i].feasible) continue;
        bool dominated = false;
        for (std::size_t j = 0; j < designs.size() && !dominated; ++j) {
            if (!designs[j].feasible || j == i) continue;
            bool all = true, one = false;
            for (std::size_t m = 0; m < metrics.size(); ++m) {
                const double s = metrics[m].larger_is_better() ? 1.0 : -1.0;
                const double a = s * designs[j].values[m], b = s * designs[i].values[m];
                all = all && a >= b;
                one = one || a > b;
            }
            dominated = all && one;
        }
        if (!dominated) front.push_back(i);
    }
    return front;
}

std::vector<DesignEvaluation> randomDesigns(std::size_t n, std::size_t metrics, double levels, unsigned seed) {
    std::mt19937_64 engine(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<DesignEvaluation> designs(n);
    for (DesignEvaluation& d : designs) {
        d.feasible = unit(engine) < 0.9;
        for (std::size_t m = 0; m < metrics; ++m) d.values.push_back(std::round(unit(engine) * levels));
    }
    return designs;
}

TEST(HostileRound3Pareto, TheSortedSweepFindsTheFrontOfEveryPairComparisonWithTies) {
    const std::vector<DesignMetric> all = {parseDesignMetric("workspace_area"), parseDesignMetric("moving_mass"),
                                           parseDesignMetric("peak_force")};
    for (const std::size_t m : {1u, 2u, 3u}) {
        const std::vector<DesignMetric> metrics(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(m));
        for (const double levels : {3.0, 20.0, 1e6}) {  // heavy ties, some, none
            const std::vector<DesignEvaluation> designs = randomDesigns(1500, m, levels, 11 + m);
            const std::vector<std::size_t> front = paretoFront(designs, metrics);
            EXPECT_EQ(front, bruteForceFront(designs, metrics)) << m << " metrics, " << levels << " levels";
            EXPECT_FALSE(front.empty());
        }
    }
}

TEST(HostileRound3Pareto, ProgressReachesEveryFeasibleDesign) {
    const std::vector<DesignMetric> metrics = {parseDesignMetric("workspace_area"), parseDesignMetric("moving_mass")};
    const std::vector<DesignEvaluation> designs = randomDesigns(200000, 2, 1000.0, 5);
    const auto feasible = static_cast<std::size_t>(
        std::count_if(designs.begin(), designs.end(), [](const DesignEvaluation& d) { return d.feasible; }));
    std::size_t last = 0, calls = 0;
    (void)paretoFront(designs, metrics, [&](std::size_t done, std::size_t total) {
        EXPECT_EQ(total, feasible);
        EXPECT_GE(done, last);
        last = done;
        ++calls;
    });
    EXPECT_EQ(last, feasible);
    EXPECT_GE(calls, 3u);
}

TEST(HostileRound3Design, ARangeWhoseWidthOverflowsIsRefusedNotInfInTheTable) {
    try {
        (void)sweepPoints({{"r_b", -1e308, 1e308}}, SweepKind::grid, 4, 1);
        ADD_FAILURE() << "a range of width 2e308 was accepted";
    } catch (const Error& e) {
        EXPECT_TRUE(has(e.what(), "'r_b' is wider than a double holds")) << e.what();
    }
    const auto points = sweepPoints({{"r_b", -1e307, 1e307}}, SweepKind::grid, 3, 1);
    for (const auto& p : points) EXPECT_TRUE(std::isfinite(p[0]));
}

TEST(HostileRound3Escape, MarkdownTextCannotForgeARowOrCarryHtml) {
    EXPECT_EQ(io::markdownText("a | pass |<b>x</b>&"), "a \\| pass \\|&lt;b&gt;x&lt;/b&gt;&amp;");
    EXPECT_EQ(io::markdownText("line\nbreak\x1b[31m"), "line\\\\x0Abreak\\\\x1B\\[31m");
    EXPECT_EQ(io::markdownText("*`[]~\\"), "\\*\\`\\[\\]\\~\\\\");
    EXPECT_EQ(io::markdownText("elcentro_1940_ns.AT2"), "elcentro_1940_ns.AT2");
}

TEST(HostileRound3Errors, ASingularMassMatrixNamesTheBodiesWithoutMassOrInertia) {
    // a point-mass platform on massless limbs: M_p = diag(0, m, m), nothing resists a rotation
    RobotDescription description = io::exampleRobot("paper-3prr");
    description.platform.inertia = 0.0;
    description.platform.com.setZero();
    for (LimbDescription& limb : description.limbs) {
        for (BodyDescription& body : limb.bodies) body.mass = body.inertia = 0.0;
    }
    const Model model(description);
    Data data(model);
    const Status status =
        forwardDynamics(model, data, model.home, Twist::Zero(), ActuatorVector::Zero(model.actuators));
    ASSERT_EQ(status.code, StatusCode::singular_mass_matrix) << describe(status, model);
    const std::string message = describe(status, model);
    EXPECT_TRUE(has(message, "the mass matrix M_p is singular")) << message;
    EXPECT_TRUE(has(message, "the platform has zero inertia")) << message;
    EXPECT_TRUE(has(message, model.limbName(0) + " body 2 has zero mass and inertia")) << message;
    EXPECT_FALSE(has(message, "not a finite number")) << message;
}

}  // namespace
}  // namespace nocdyn::test
