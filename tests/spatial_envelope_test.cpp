// The envelope of spatial robots (spatial_envelope.hpp): the Gough-Stewart platform's stroke
// bound along z against the closed form of its legs' lengths, the limit-use ratio at the
// amplitude found and just above it, the effort bound's 1 / f^2, the Delta's three axes, and
// the command's files and its refusal of an option that does not apply.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "cli_support.hpp"
#include "nocdyn/analysis/spatial_envelope.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"

namespace nocdyn::spatial {
namespace {

std::string source(const std::string& path) { return std::string(NOCDYN_SOURCE_DIR) + "/" + path; }

constexpr int kZ = 2;

TEST(SpatialEnvelope, TheStewartsStrokeBindsAlongZAtTheLegLengthsClosedForm) {
    // each leg runs from its base U at a_i to its platform S at s_i (home); moved along z by d
    // the leg is |s_i + d e_z - a_i| long, and its P joint's variable is that length less the
    // home length; the stroke [-0.15, 0.15] m allows d within [d_down, d_up] per leg, solved
    // in closed form: h_i the horizontal distance, v_i the height of s_i - a_i,
    //   sqrt(h^2 + (v + d)^2) = L_0 +- 0.15  =>  d = +-sqrt((L_0 +- 0.15)^2 - h^2) - v
    const SpatialRobotDescription d = io::loadSpatialRobotDescription(source("robots/stewart.yaml"));
    double expected = std::numeric_limits<double>::infinity();
    for (const SpatialLimbDescription& limb : d.limbs) {
        const Eigen::Vector3d leg = limb.joints.back().point - limb.joints.front().point;
        const double h = leg.head<2>().norm(), v = leg.z(), length = leg.norm();
        const double lower = limb.joints[1].limits.lower, upper = limb.joints[1].limits.upper;
        const double up = std::sqrt((length + upper) * (length + upper) - h * h) - v;
        const double down = v - std::sqrt((length + lower) * (length + lower) - h * h);
        expected = std::min({expected, up, down});
    }
    const Model model(d);
    nocdyn::EnvelopeOptions options;
    options.relative_tolerance = 1e-10;
    const EnvelopePoint p = maximumAmplitude(model, kZ, 0.01, options);
    EXPECT_EQ(p.limit, EnvelopeLimit::range);
    EXPECT_GE(p.actuator, 0);
    EXPECT_NEAR(p.amplitude, expected, 1e-8);
    EXPECT_NEAR(p.kinematic_amplitude, expected, 1e-8);
    EXPECT_NEAR(p.peak_u, 0.15, 1e-8);  // the binding leg at its stroke's end
    EXPECT_GT(expected, 0.1);           // a real number: about 0.17 m
}

TEST(SpatialEnvelope, TheLimitUseIsOneAtTheAmplitudeAndExceedsOneJustAbove) {
    const Model model(io::loadSpatialRobotDescription(source("robots/stewart.yaml")));
    Data data(model);
    nocdyn::EnvelopeOptions options;
    options.relative_tolerance = 1e-9;
    // low, middle and high frequencies along x, z and yaw: each limit binds somewhere
    bool seen[3] = {false, false, false};
    for (const int axis : {0, 2, 5}) {
        for (const double f : {0.05, 3.0, 60.0}) {
            const EnvelopePoint p = maximumAmplitude(model, axis, f, options);
            ASSERT_NE(p.limit, EnvelopeLimit::none) << axis << " " << f;
            const int n = options.samples_per_period;
            const double at = limitUse(model, data, axis, f, p.amplitude, n).peak_ratio;
            EXPECT_NEAR(at, 1.0, 1e-3) << axis << " " << f;
            EXPECT_GT(limitUse(model, data, axis, f, 1.01 * p.amplitude, n).peak_ratio, 1.0) << axis << " " << f;
            if (p.limit == EnvelopeLimit::range) seen[0] = true;
            if (p.limit == EnvelopeLimit::velocity) seen[1] = true;
            if (p.limit == EnvelopeLimit::effort) seen[2] = true;
        }
    }
    EXPECT_TRUE(seen[0] && seen[1] && seen[2]);
}

TEST(SpatialEnvelope, WhereTheEffortBindsTheAmplitudeFallsAsOneOverFSquared) {
    // at high f the inertia forces dominate gravity and friction: tau ~ A (2 pi f)^2, so
    // A(f_1) / A(f_2) ~ (f_2 / f_1)^2
    const Model model(io::loadSpatialRobotDescription(source("robots/stewart.yaml")));
    for (const int axis : {0, 1, 2, 3, 4, 5}) {
        const EnvelopePoint a = maximumAmplitude(model, axis, 100.0);
        const EnvelopePoint b = maximumAmplitude(model, axis, 200.0);
        ASSERT_EQ(a.limit, EnvelopeLimit::effort) << axis;
        ASSERT_EQ(b.limit, EnvelopeLimit::effort) << axis;
        EXPECT_NEAR(a.amplitude / b.amplitude, 4.0, 0.4) << axis;
        EXPECT_NEAR(a.peak_effort_ratio, 1.0, 1e-5) << axis;
    }
}

TEST(SpatialEnvelope, ATranslationRobotHasThreeAxesAndEveryPointWithinItsLimits) {
    const Model model(io::loadSpatialRobotDescription(source("robots/delta.yaml")));
    nocdyn::EnvelopeOptions options;
    options.min_frequency = 0.1;
    options.max_frequency = 100.0;
    options.points = 3;
    const std::vector<EnvelopePoint> points = operatingEnvelope(model, options);
    ASSERT_EQ(points.size(), 9U);
    Data data(model);
    for (const EnvelopePoint& p : points) {
        EXPECT_LT(p.axis, 3);
        EXPECT_GT(p.amplitude, 1e-4) << p.axis << " " << p.frequency;
        EXPECT_LE(p.amplitude, p.kinematic_amplitude * (1.0 + 1e-12));
        EXPECT_LE(limitUse(model, data, p.axis, p.frequency, p.amplitude, 256).peak_ratio, 1.0);
    }
    // the low frequency's amplitude is the kinematic one; 100 Hz is far below it
    EXPECT_EQ(points[0].limit, EnvelopeLimit::range);
    EXPECT_LT(points[2].amplitude, 0.01 * points[0].amplitude);
}

TEST(SpatialEnvelope, TheCommandWritesItsFilesAndRefusesTheResonanceBoundInOneLine) {
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_envelope_cli");
    const std::filesystem::path csv = dir / "envelope.csv", figure = dir / "envelope";
    const std::string robot = source("robots/stewart.yaml");
    const test::CliResult r =
        test::runCli("envelope --robot " + robot + " --points 2 --min-frequency 1 " + "--max-frequency 100 --output " +
                     csv.string() + " --figure " + figure.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "envelope.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "envelope.svg"));
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line.rfind("axis,frequency,amplitude,limit,limb,joint,actuator,kinematic_amplitude", 0), 0U) << line;
    std::string axes;
    int rows = 0;
    while (std::getline(in, line)) {
        axes += line.substr(0, line.find(',')) + " ";
        ++rows;
    }
    EXPECT_EQ(rows, 12);
    EXPECT_EQ(axes, "x x y y z z roll roll pitch pitch yaw yaw ");

    const std::filesystem::path refused = dir / "refused.csv";
    const test::CliResult a =
        test::runCli("envelope --robot " + robot + " --amplification 2 --output " + refused.string());
    EXPECT_NE(a.exit_code, 0);
    EXPECT_EQ(a.err.rfind("nocdyn: error: --amplification: applies to planar robots only", 0), 0U) << a.err;
    EXPECT_EQ(std::count(a.err.begin(), a.err.end(), '\n'), 1) << a.err;
    EXPECT_FALSE(std::filesystem::exists(refused));
}

}  // namespace
}  // namespace nocdyn::spatial
