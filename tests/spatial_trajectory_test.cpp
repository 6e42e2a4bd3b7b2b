// A spatial robot's trajectory (nocdyn/spatial_trajectory.hpp), its files
// (io/trajectory_yaml.hpp) and `nocdyn inverse-dynamics` on spatial robots: the trajectory's
// derivatives against finite differences (harmonic and sampled axes) and allocation-free; the
// command's CSV against spatial::inverseDynamics sample by sample; the power balance
// tau . du = dE/dt along the shipped trajectories (friction off); every bad file refused in one
// line naming the file and the field, with no output file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "allocation_counter.hpp"
#include "cli_support.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_trajectory.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::spatial {
namespace {

std::string source(const std::string& path) { return std::string(NOCDYN_SOURCE_DIR) + "/" + path; }

SpatialRobotDescription frictionless(SpatialRobotDescription d) {
    for (SpatialLimbDescription& limb : d.limbs) {
        for (SpatialJointDescription& joint : limb.joints) joint.damping = joint.friction = 0.0;
    }
    return d;
}

/// A file private to the running test with `text` in it.
std::string scratchFile(const std::string& name, const std::string& text) {
    const std::filesystem::path dir = test::freshScratchDirectory("spatial_trajectory");
    const std::filesystem::path path = dir / name;
    std::ofstream(path) << text;
    return path.string();
}

/// Central differences of p and dp against dp and ddp at t (step h), max |error| / (1 + |value|).
void expectDerivatives(const Trajectory& trajectory, double t, double h, double tolerance) {
    TaskVector p, dp, ddp, p_plus, dp_plus, ddp_plus, p_minus, dp_minus, ddp_minus;
    trajectory.evaluate(t, p, dp, ddp);
    trajectory.evaluate(t + h, p_plus, dp_plus, ddp_plus);
    trajectory.evaluate(t - h, p_minus, dp_minus, ddp_minus);
    ASSERT_EQ(p.size(), trajectory.dimension);
    for (int i = 0; i < trajectory.dimension; ++i) {
        const double dp_fd = (p_plus(i) - p_minus(i)) / (2.0 * h);
        const double ddp_fd = (dp_plus(i) - dp_minus(i)) / (2.0 * h);
        EXPECT_NEAR(dp_fd, dp(i), tolerance * (1.0 + std::abs(dp(i))))
            << trajectory.name << ", " << kCoordinateNames[static_cast<std::size_t>(i)] << ", t = " << t;
        EXPECT_NEAR(ddp_fd, ddp(i), tolerance * (1.0 + std::abs(ddp(i))))
            << trajectory.name << ", " << kCoordinateNames[static_cast<std::size_t>(i)] << ", t = " << t;
    }
}

TEST(SpatialTrajectory, HarmonicDerivativesMatchFiniteDifferences) {
    // central differences err by h^2 p''' / 6: a few 1e-9 at h = 1e-5 s and 3 Hz
    constexpr double kTolerance = 1e-7;
    const Trajectory sway = io::loadSpatialTrajectory(source("trajectories/stewart-sway.yaml"), 6);
    const Trajectory pick = io::loadSpatialTrajectory(source("trajectories/delta-pick.yaml"), 3);
    EXPECT_EQ(sway.duration, 2.0);
    EXPECT_DOUBLE_EQ(sway.highestFrequency(), 3.0);
    EXPECT_EQ(sway.harmonics(), 6U);
    for (const double t : {0.0, 0.1234, 0.77, 1.5}) {
        expectDerivatives(sway, t, 1e-5, kTolerance);
        expectDerivatives(pick, t, 1e-5, kTolerance);
    }
    // the values themselves: z = 1.0579369000754848 + 0.004 sin(2 pi 1.5 t), yaw 0.026 sin(3 pi t - 0.3)
    TaskVector p, dp, ddp;
    sway.evaluate(0.1234, p, dp, ddp);
    EXPECT_DOUBLE_EQ(p(2), 1.0579369000754848 + 0.004 * std::sin(2.0 * M_PI * 1.5 * 0.1234));
    EXPECT_DOUBLE_EQ(p(5), 0.026 * std::sin(2.0 * M_PI * 1.5 * 0.1234 - 0.3));
    pick.evaluate(0.0, p, dp, ddp);
    EXPECT_DOUBLE_EQ(p(2), -0.775);  // up between pick and place
    EXPECT_NEAR(dp(0), 0.2 * M_PI, 1e-15);
}

TEST(SpatialTrajectory, SampledDerivativesMatchFiniteDifferencesAndReproduceCubics) {
    // samples of cubics: the not-a-knot spline reproduces them, so its derivatives are exact
    std::string csv = "t,x,y,z,roll,pitch,yaw\n";
    const auto cubic = [](double t, double a) { return a * (1.0 + t - 2.0 * t * t + 3.0 * t * t * t); };
    for (int k = 0; k <= 20; ++k) {
        const double t = 0.01 * k;
        csv += std::to_string(t);
        for (const double a : {0.001, -0.002, 1.05, 0.01, 0.02, -0.03}) csv += "," + text::allDigits(cubic(t, a));
        csv += "\n";
    }
    const Trajectory sampled = io::parseSpatialTrajectoryCsv(csv, "cubic.csv", 6);
    EXPECT_EQ(sampled.duration, 0.2);
    EXPECT_EQ(sampled.highestFrequency(), 0.0);
    for (const double t : {0.013, 0.0777, 0.1509}) {
        expectDerivatives(sampled, t, 1e-6, 1e-6);
        TaskVector p, dp, ddp;
        sampled.evaluate(t, p, dp, ddp);
        EXPECT_NEAR(p(2), cubic(t, 1.05), 1e-12);
        EXPECT_NEAR(dp(2), 1.05 * (1.0 - 4.0 * t + 9.0 * t * t), 1e-10);
        EXPECT_NEAR(ddp(2), 1.05 * (-4.0 + 18.0 * t), 1e-8);
    }
}

TEST(SpatialTrajectory, EvaluateAllocatesNothing) {
    const Trajectory sway = io::loadSpatialTrajectory(source("trajectories/stewart-sway.yaml"), 6);
    TaskVector p(6), dp(6), ddp(6);
    const long before = test::allocationCount();
    for (int k = 0; k < 100; ++k) sway.evaluate(0.01 * k, p, dp, ddp);
    EXPECT_EQ(test::allocationCount(), before);
}

/// The command's CSV against spatial::inverseDynamics at each row's time, 1e-12 relative.
void expectCliMatchesCore(const std::string& robot, const std::string& trajectory_file, double duration, double rate) {
    const std::string out = scratchFile("unused", "");
    const std::string csv_path = std::filesystem::path(out).parent_path() / "id.csv";
    const test::CliResult result = test::runCli(
        "inverse-dynamics --robot " + source("robots/" + robot + ".yaml") + " --trajectory " + source(trajectory_file) +
        " --duration " + std::to_string(duration) + " --rate " + std::to_string(rate) + " --output " + csv_path);
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const io::Table table = io::readCsvFile(csv_path);
    const Model model(io::loadSpatialRobotDescription(source("robots/" + robot + ".yaml")));
    const Trajectory trajectory = io::loadSpatialTrajectory(source(trajectory_file), model.task_dimension);
    const int d = model.task_dimension, n = model.actuators;
    ASSERT_EQ(table.columns.size(), static_cast<std::size_t>(2 + d + 4 * n));
    EXPECT_EQ(table.columns[1], "x");
    EXPECT_EQ(table.columns[static_cast<std::size_t>(d)], d == 6 ? "yaw" : "z");
    EXPECT_EQ(table.columns[static_cast<std::size_t>(1 + d)], "u1");
    EXPECT_EQ(table.columns.back(), "kinetic");
    ASSERT_EQ(table.rows.size(), static_cast<std::size_t>(std::lround(duration * rate)));
    Data data(model);
    TaskVector p, dp, ddp;
    const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(1.0, std::abs(b)); };
    for (std::size_t k = 0; k < table.rows.size(); ++k) {
        const std::vector<double>& row = table.rows[k];
        EXPECT_EQ(row[0], static_cast<double>(k) / rate);
        trajectory.evaluate(row[0], p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp)) << "t = " << row[0];
        for (int i = 0; i < d; ++i) EXPECT_EQ(row[static_cast<std::size_t>(1 + i)], p(i));
        std::size_t c = static_cast<std::size_t>(1 + d);
        for (const ActuatorVector* v : {&data.u, &data.du, &data.ddu, &data.tau}) {
            for (int a = 0; a < n; ++a, ++c) {
                EXPECT_PRED2(near, row[c], (*v)(a)) << robot << ", t = " << row[0] << ", " << table.columns[c];
            }
        }
        EXPECT_PRED2(near, row[c], kineticEnergy(model, data)) << robot << ", t = " << row[0];
    }
}

TEST(SpatialInverseDynamicsCli, CsvEqualsTheCoreSampleBySample) {
    expectCliMatchesCore("stewart", "trajectories/stewart-sway.yaml", 0.25, 200.0);
    expectCliMatchesCore("delta", "trajectories/delta-pick.yaml", 0.25, 200.0);
}

/// tau . du = dE/dt, E the kinetic plus the potential energy, by central differences of E along
/// the file's trajectory with friction off.
void expectPowerBalance(const std::string& robot, const std::string& trajectory_file) {
    const Model model(frictionless(io::loadSpatialRobotDescription(source("robots/" + robot + ".yaml"))));
    const Trajectory trajectory = io::loadSpatialTrajectory(source(trajectory_file), model.task_dimension);
    Data data(model);
    TaskVector p, dp, ddp;
    const auto energy = [&](double t) {
        trajectory.evaluate(t, p, dp, ddp);
        EXPECT_TRUE(inverseDynamics(model, data, p, dp, ddp));
        return kineticEnergy(model, data) + potentialEnergy(model, data);
    };
    constexpr double h = 1e-5;
    double peak = 0.0, worst = 0.0;
    for (int k = 0; k < 40; ++k) {
        const double t = *trajectory.duration * (k + 0.5) / 40.0;
        const double dE = (energy(t + h) - energy(t - h)) / (2.0 * h);
        trajectory.evaluate(t, p, dp, ddp);
        ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp));
        const double power = data.tau.dot(data.du);
        peak = std::max(peak, std::abs(power));
        worst = std::max(worst, std::abs(power - dE));
    }
    // rounding of E (~1e-16 E / h) and the h^2 truncation: measured 5e-9 (Stewart) and 3e-9
    // (Delta) of the peak power
    EXPECT_GT(peak, 1.0) << robot;  // the motion does work
    EXPECT_LT(worst, 1e-7 * peak) << robot << ": worst |tau . du - dE/dt| = " << worst << " W of " << peak;
}

TEST(SpatialInverseDynamics, PowerBalanceHoldsAlongTheShippedTrajectories) {
    expectPowerBalance("stewart", "trajectories/stewart-sway.yaml");
    expectPowerBalance("delta", "trajectories/delta-pick.yaml");
}

/// The command refuses: non-zero exit, one line on stderr containing every `needles`, no file.
void expectRefused(const std::string& robot, const std::string& trajectory, const std::vector<std::string>& needles,
                   const std::string& options = "") {
    const std::string output = (std::filesystem::path(trajectory).parent_path() / "out.csv").string();
    const test::CliResult result =
        test::runCli("inverse-dynamics --robot " + source("robots/" + robot + ".yaml") + " --trajectory " + trajectory +
                     " --rate 1000 --output " + output + options);
    EXPECT_NE(result.exit_code, 0) << trajectory;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    for (const std::string& needle : needles) EXPECT_NE(result.err.find(needle), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(output)) << result.err;
}

TEST(SpatialInverseDynamicsCli, BadFilesAreRefusedInOneLineNamingFileAndField) {
    const std::string home = "x: {offset: 0}\ny: {offset: 0}\nz: {offset: -0.8}\n";
    std::string f = scratchFile("theta.yaml", home + "theta: {offset: 0.1}\n");
    expectRefused("delta", f, {f + ":4: theta: a planar robot's coordinate"});
    f = scratchFile("roll.yaml", home + "roll: {offset: 0}\n");
    expectRefused("delta", f, {f + ":4: roll: a translation robot"});
    f = scratchFile("missing.yaml", "x: {offset: 0}\ny: {offset: 0}\n");
    expectRefused("delta", f, {f + ":1: z: missing"});
    f = scratchFile("missing6.yaml", home);
    expectRefused("stewart", f, {f + ":1: roll: missing"});
    f = scratchFile("unknown.yaml", home + "w: {offset: 0}\n");
    expectRefused("delta", f, {f + ":4: w: unknown key"});
    f = scratchFile("no-amplitude.yaml", "x: {harmonics: [{frequency: 2}]}\ny: {offset: 0}\nz: {offset: -0.8}\n");
    expectRefused("delta", f, {f + ":1: x.harmonics[0].amplitude"});
    f = scratchFile("theta.csv", "t,x,y,theta\n0,0,0,0\n0.1,0,0,0\n");
    expectRefused("delta", f, {f + ":1: column 'theta': a planar robot's coordinate"});
    f = scratchFile("roll.csv", "t,x,y,z,roll\n0,0,0,-0.8,0\n0.1,0,0,-0.8,0\n");
    expectRefused("delta", f, {f + ":1: column 'roll': a translation robot"});
    f = scratchFile("missing.csv", "t,x,y\n0,0,0\n0.1,0,0\n");
    expectRefused("delta", f, {f + ":1: column 'z': missing"});
    f = scratchFile("back.csv", "t,x,y,z\n0,0,0,-0.8\n0.1,0,0,-0.8\n0.05,0,0,-0.8\n");
    expectRefused("delta", f, {f + ":4: column 't'"});
    expectRefused("delta", "paper1", {"trajectory 'paper1'", "planar"});
    // a motor beyond its range, then (its limits allowed) a sample out of reach: the time and the
    // limb, and no partial file (the first rows are fine)
    f = scratchFile("reach.yaml",
                    "duration: 0.25\nx: {offset: 0}\ny: {offset: 0}\n"
                    "z: {offset: -0.8, harmonics: [{amplitude: 0.6, frequency: 1}]}\n");
    expectRefused("delta", f, {"t = 0.078 s: joint range exceeded: limb 1 (arm1), joint 1: q = -0.806696"});
    expectRefused("delta", f, {"t = 0.108 s: pose out of reach: limb 1 (arm1) cannot close"}, " --allow-limits");
}

TEST(SpatialTrajectory, ReadersNameTheLineAndField) {
    try {
        (void)io::parseSpatialTrajectory("x: {offset: 0}\ny: {offset: [1]}\nz: {offset: 1}\n", "t.yaml", 3);
        FAIL() << "accepted a list as an offset";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("t.yaml:2: y.offset", 0), 0U) << e.what();
    }
    EXPECT_THROW((void)io::parseSpatialTrajectory("x: {offset: 0}\n", "t.yaml", 4), Error);
}

}  // namespace
}  // namespace nocdyn::spatial
