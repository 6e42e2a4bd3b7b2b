// Drive-signal iteration on a six-DOF table (nocdyn/sim/spatial_shake.hpp, iterateReplay): El
// Centro's three components on robots/stewart.yaml, the passes' errors per axis, the pass
// kept, the gain and the tolerance honoured, and `nocdyn shake --iterations` on the hexapod:
// shake.json's passes and stop, the summary's line, a planar-only drive model refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "spatial_shake_support.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/spatial_shake.hpp"

namespace nocdyn {
namespace {

const std::string kSource = NOCDYN_SOURCE_DIR;

std::string component(const std::string& name) { return test::elCentroComponent(name); }

/// El Centro 1940 (Array #9) on the table's x, y, z: its first `seconds`.
spatial::GroundRecord3 elCentro(double seconds) { return test::elCentro3(seconds); }

/// The shake command's loop on the hexapod: computed torque at 1 kHz, the hold's middle state.
spatial::LoopOptions hexapodLoop() {
    spatial::LoopOptions loop;
    loop.rate = 1000.0;
    loop.natural_frequency = 30.0;
    loop.mid_hold = true;
    return loop;
}

struct Bench {
    spatial::Model model{
        spatial::withSpecimen(io::loadSpatialRobotDescription(kSource + "/robots/stewart.yaml"), 50.0)};
    FitOptions fit;
    spatial::FittedRecord3 target = spatial::fitRecord(model, elCentro(2.0), fit);
};

spatial::ShakeReplay3 iterate(const Bench& b, int iterations, double gain, double tolerance,
                              spatial::DriveIterationPasses& passes) {
    spatial::DriveIterationOptions options;
    options.iterations = iterations;
    options.iteration_gain = gain;
    options.iteration_tolerance = tolerance;
    options.fit = b.fit;
    return spatial::iterateReplay(b.model, b.target, hexapodLoop(), b.fit.highpass, options, passes);
}

// Two passes after the first: the pass kept lowers the RMS error of every axis below the first
// pass's; its scores are against the target (the first pass's are replayRecord's own).
TEST(SpatialShakeIteration, TheKeptPassLowersEveryAxissError) {
    const Bench b;
    spatial::DriveIterationPasses passes;
    const spatial::ShakeReplay3 r = iterate(b, 2, 0.7, 0.02, passes);
    const spatial::ShakeReplay3 first = spatial::replayRecord(b.model, b.target, hexapodLoop(), b.fit.highpass);
    ASSERT_GE(passes.rms.size(), 2u);
    ASSERT_EQ(passes.worst.size(), passes.rms.size());
    for (std::size_t axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(passes.rms[0][axis], first.score[axis].rms_error) << axis;  // the same deterministic loop
    }
    ASSERT_GE(passes.best_pass, 1);
    const auto kept = static_cast<std::size_t>(passes.best_pass);
    for (std::size_t axis = 0; axis < 3; ++axis) {
        EXPECT_LT(passes.rms[kept][axis], passes.rms[0][axis]) << axis;
        EXPECT_EQ(r.score[axis].rms_error, passes.rms[kept][axis]) << axis;
    }
    EXPECT_EQ(passes.worst[kept], *std::min_element(passes.worst.begin(), passes.worst.end()));
    EXPECT_FALSE(passes.stop.empty());
    // the kept pass is scored against the target: its fit is the target's
    EXPECT_EQ(r.fit.a[0], b.target.a[0]);
    EXPECT_LE(r.achieved_use.ratio, 1.0);
}

// The gain: a loop close to identity leaves (1 - g) of the error after one correction, so a
// smaller gain leaves the more; the tolerance: 0 plays every pass asked, 0.9 stops after the
// first correction (it cannot lower the error by 90 %), naming the tolerance.
TEST(SpatialShakeIteration, TheGainAndTheToleranceAreHonoured) {
    const Bench b;
    spatial::DriveIterationPasses low, high, strict;
    (void)iterate(b, 1, 0.3, 0.0, low);
    (void)iterate(b, 1, 0.9, 0.0, high);
    ASSERT_EQ(low.worst.size(), 2u);
    ASSERT_EQ(high.worst.size(), 2u);
    EXPECT_EQ(low.worst[0], high.worst[0]);
    EXPECT_EQ(low.stop, kLastPassAsked);
    EXPECT_GT(low.worst[1], high.worst[1]);
    (void)iterate(b, 3, 0.7, 0.9, strict);
    EXPECT_EQ(strict.worst.size(), 2u);
    EXPECT_EQ(strict.stop, "pass 1 improved the RMS error by less than 90 %");
    // no iteration: the first pass alone, no stop
    spatial::DriveIterationPasses none;
    (void)iterate(b, 0, 0.7, 0.02, none);
    EXPECT_EQ(none.worst.size(), 1u);
    EXPECT_TRUE(none.stop.empty());
    EXPECT_THROW((void)iterate(b, 1, 0.0, 0.02, none), Error);
}

// `nocdyn shake --iterations 2` on the hexapod: shake.json keeps the planar table's keys (each
// pass's RMS error, the pass kept) with each axis's errors and the stop; the text says them.
// A planar drive model and a tolerance without iterations are refused in one line naming them.
TEST(SpatialShakeIteration, TheCommandIteratesTheHexapodsDrive) {
    const std::filesystem::path out = test::freshScratchDirectory("spatial_shake_iteration");
    const std::string command = "shake --robot " + kSource + "/robots/stewart.yaml --record " +
                                component("180-hor1.AT2") + " --record " + component("270-hor2.AT2") + " --record " +
                                component("-UP.AT2") + " --window 2";
    const test::CliResult run = test::runCli(command + " --iterations 2 --out-dir " + (out / "a").string());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::ifstream file(out / "a" / "shake.json");
    const nlohmann::json json = nlohmann::json::parse(file);
    const auto passes = json["pass_rms_error_percent"].get<std::vector<double>>();
    ASSERT_GE(passes.size(), 2u);
    const int kept = json["pass_kept"].get<int>();
    ASSERT_GE(kept, 1);
    EXPECT_FALSE(json["iteration_stop"].get<std::string>().empty());
    for (const char* axis : {"ax", "ay", "az"}) {
        const auto rms = json["pass_rms_error_percent_axes"][axis].get<std::vector<double>>();
        ASSERT_EQ(rms.size(), passes.size()) << axis;
        EXPECT_LT(rms[static_cast<std::size_t>(kept)], rms[0]) << axis;
        EXPECT_LE(rms[0], passes[0]) << axis;  // the worst axis's is the pass's
        EXPECT_NEAR(json["metrics"][axis]["rms_error_percent"].get<double>(), rms[static_cast<std::size_t>(kept)], 1e-9)
            << axis;
    }
    EXPECT_NE(run.out.find("drive iteration"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("pass " + std::to_string(kept) + " kept"), std::string::npos) << run.out;
    const test::CliResult model =
        test::runCli(command + " --iterations 2 --drive-model exact --out-dir " + (out / "b").string());
    EXPECT_NE(model.exit_code, 0);
    EXPECT_NE(model.err.find("drive-model"), std::string::npos) << model.err;
    EXPECT_EQ(std::count(model.err.begin(), model.err.end(), '\n'), 1) << model.err;
    EXPECT_FALSE(std::filesystem::exists(out / "b" / "shake.json"));
    const test::CliResult tolerance =
        test::runCli(command + " --iteration-tolerance 0.1 --out-dir " + (out / "c").string());
    EXPECT_NE(tolerance.exit_code, 0);
    EXPECT_NE(tolerance.err.find("iteration-tolerance"), std::string::npos) << tolerance.err;
}

}  // namespace
}  // namespace nocdyn
