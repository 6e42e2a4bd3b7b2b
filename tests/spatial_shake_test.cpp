// A three-component record on a six-DOF table (nocdyn/sim/spatial_shake.hpp): the specimen on
// the platform, the fit within every leg's limits, the closed-loop replay and its scores, and
// `nocdyn shake` on robots/stewart.yaml: one record (its replay drawn in 3-D) and a suite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "spatial_shake_support.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/ground_motion3.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/spatial_shake.hpp"

namespace nocdyn {
namespace {

const std::string kSource = NOCDYN_SOURCE_DIR;

SpatialRobotDescription stewart() { return io::loadSpatialRobotDescription(kSource + "/robots/stewart.yaml"); }

std::string component(const std::string& name) { return test::elCentroComponent(name); }

/// El Centro 1940 (Array #9) on the table's x, y, z: its first `seconds`.
spatial::GroundRecord3 elCentro(double seconds) { return test::elCentro3(seconds); }

Eigen::Matrix3d shift(const Eigen::Vector3d& r) {
    return r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose();
}

// A point mass at the platform's origin: the mass adds, the c.o.m. is the weighted mean, and the
// inertia about the origin is the platform's about the origin (parallel axes: the point adds none).
TEST(SpatialShake, TheSpecimenIsAPointMassAtThePlatformsOrigin) {
    const SpatialRobotDescription d = stewart();
    const SpatialRobotDescription s = spatial::withSpecimen(d, 100.0);
    const SpatialBodyDescription &p = d.platform, &q = s.platform;
    EXPECT_DOUBLE_EQ(q.mass, p.mass + 100.0);
    EXPECT_TRUE(q.com.isApprox(p.mass * p.com / (p.mass + 100.0), 1e-15));
    const Eigen::Matrix3d about_origin = q.inertia + q.mass * shift(q.com);
    EXPECT_TRUE(about_origin.isApprox(p.inertia + p.mass * shift(p.com), 1e-13)) << about_origin;
    EXPECT_EQ(spatial::withSpecimen(d, 0.0).platform.mass, p.mass);
    EXPECT_THROW((void)spatial::withSpecimen(d, -1.0), Error);
    // the heavier platform needs the more force to hold at home
    const spatial::Model light(d), heavy(s);
    spatial::Data a(light), b(heavy);
    const spatial::TaskVector zero = spatial::TaskVector::Zero(6);
    ASSERT_TRUE(spatial::inverseDynamics(light, a, light.home, zero, zero).ok());
    ASSERT_TRUE(spatial::inverseDynamics(heavy, b, heavy.home, zero, zero).ok());
    // at home the six legs share the weight equally (the hexapod's symmetry): 100 g more in all
    const double extra = (b.tau - a.tau).sum() * heavy.limb[0].freedoms[2].axis.z();
    EXPECT_NEAR(extra, 100.0 * 9.81, 1e-6 * 100.0 * 9.81);
}

// The fit: one time scale and one amplitude for the three axes; the target's accelerations
// are the filtered record's times A, the trajectory's second derivative at each sample; the
// rotations stay at home; the fitted motion uses at most the allowed share of every limit.
TEST(SpatialShake, TheFitKeepsTheMotionsShapeWithinEveryLegsLimits) {
    const spatial::Model model(stewart());
    const spatial::GroundRecord3 record = elCentro(6.0);
    FitOptions options;
    const spatial::FittedRecord3 fit = spatial::fitRecord(model, record, options);
    EXPECT_GE(fit.time_scale, 1.0);
    EXPECT_EQ(fit.amplitude[0], fit.amplitude[1]);
    EXPECT_EQ(fit.amplitude[1], fit.amplitude[2]);
    EXPECT_LE(fit.use.ratio, 1.0);
    EXPECT_GT(fit.use.ratio, 0.5);  // the least compression that fits uses the limits
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const std::vector<double> filtered = highPassZeroPhase(record.a[axis], record.dt, options.highpass);
        ASSERT_EQ(fit.a[axis].size(), filtered.size());
        spatial::TaskVector p, dp, ddp;
        for (std::size_t i = 0; i < filtered.size(); i += 37) {
            EXPECT_NEAR(fit.a[axis][i], fit.amplitude[axis] * filtered[i], 1e-12);
            fit.trajectory.evaluate(fit.t[i], p, dp, ddp);
            EXPECT_NEAR(ddp(static_cast<Eigen::Index>(axis)), fit.a[axis][i], 1e-9);
            for (int c = 3; c < 6; ++c) EXPECT_EQ(p(c), 0.0);
        }
    }
    // a time scale given too small to fit: the amplitude is lowered, the same for the three
    FitOptions fast = options;
    fast.time_scale = 1.0;
    const spatial::FittedRecord3 lowered = spatial::fitRecord(model, record, fast);
    if (fit.time_scale > 1.0) {
        EXPECT_LT(lowered.amplitude[0], 1.0);
        EXPECT_EQ(lowered.amplitude[0], lowered.amplitude[2]);
        EXPECT_LE(lowered.use.ratio, 1.0);
        // per axis: another shape, the limits used as fully, some axis larger than the common scale
        const spatial::FittedRecord3 each = spatial::fitRecord(model, record, fast, true);
        EXPECT_LE(each.use.ratio, 1.0);
        EXPECT_GT(each.use.ratio, 0.99);
        EXPECT_GT(lowered.use.ratio, 0.99);
        EXPECT_GT(*std::max_element(each.amplitude.begin(), each.amplitude.end()), lowered.amplitude[0]);
        EXPECT_NE(each.amplitude[0], each.amplitude[2]);
    }
    spatial::GroundRecord3 bad = record;
    bad.a[2].pop_back();
    EXPECT_THROW((void)spatial::fitRecord(model, bad, options), Error);
}

// Computed torque on the exact model: each axis's acceleration within 5 % RMS of the target
// and its spectrum within +-10 %; the rotations held near zero.
TEST(SpatialShake, TheReplayFollowsEachAxisAndHoldsTheRotations) {
    const spatial::Model model(spatial::withSpecimen(stewart(), 50.0));
    FitOptions options;
    spatial::LoopOptions loop;
    loop.rate = 1000.0;
    loop.natural_frequency = 30.0;
    loop.mid_hold = true;
    const spatial::ShakeReplay3 r =
        spatial::replayRecord(model, spatial::fitRecord(model, elCentro(3.0), options), loop, options.highpass);
    for (std::size_t axis = 0; axis < 3; ++axis) {
        EXPECT_LT(r.score[axis].rms_error, 0.05) << axis;
        EXPECT_GT(r.score[axis].rms_error, 0.0) << axis;
        EXPECT_GT(r.score[axis].counted, 5) << axis;
        EXPECT_EQ(r.score[axis].share_outside, 0.0) << axis;
    }
    for (double angle : r.parasitic) EXPECT_LT(angle, 1e-3);
    EXPECT_LE(r.achieved_use.ratio, 1.0);
    EXPECT_EQ(r.loop.saturated_ticks, 0u);
    // the forces of the tick's state rather than of the hold's middle: an O(dt) error, larger
    loop.mid_hold = false;
    const spatial::ShakeReplay3 start = spatial::replayRecord(model, r.fit, loop, options.highpass);
    for (std::size_t axis = 0; axis < 3; ++axis) EXPECT_GT(start.score[axis].rms_error, 2.0 * r.score[axis].rms_error);
}

// `nocdyn shake` with the three components on the hexapod: the files, the columns and the
// metrics keyed ax, ay, az; the padding said on stderr.
TEST(SpatialShake, TheCommandReplaysAThreeComponentRecordOnTheHexapod) {
    const std::filesystem::path out = test::freshScratchDirectory("spatial_shake");
    const std::string robot = " --robot " + kSource + "/robots/stewart.yaml";
    const std::string records = " --record " + component("-UP.AT2") + " --record " + component("270-hor2.AT2") +
                                " --record " + component("180-hor1.AT2");
    const test::CliResult run =
        test::runCli("shake" + robot + records + " --window 3 --out-dir " + (out / "a").string());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("az: RMS error"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("x at azimuth 180 deg, y at 90 deg"), std::string::npos) << run.out;
    EXPECT_NE(run.err.find("padded with zeros"), std::string::npos) << run.err;
    const io::Table table = io::readCsvFile((out / "a" / "shake.csv").string());
    for (const char* c : {"ax", "ay", "az", "ax_achieved", "ay_achieved", "az_achieved", "roll", "tau6"})
        EXPECT_NE(std::find(table.columns.begin(), table.columns.end(), c), table.columns.end()) << c;
    std::ifstream file(out / "a" / "shake.json");
    const nlohmann::json json = nlohmann::json::parse(file);
    for (const char* axis : {"ax", "ay", "az"}) {
        EXPECT_LT(json["metrics"][axis]["rms_error_percent"].get<double>(), 5.0) << axis;
    }
    EXPECT_EQ(json["x_azimuth"].get<double>(), 180.0);
    EXPECT_EQ(json["controller_rate"].get<double>(), 1000.0);  // a hexapod's own rate, none given
    for (const char* f : {"shake_acceleration.png", "shake_spectrum.svg"})
        EXPECT_TRUE(std::filesystem::exists(out / "a" / f)) << f;
    // a rate given is kept, even when it equals the planar table's default
    const test::CliResult fast =
        test::runCli("shake" + robot + records + " --window 0.5 --rate 10000 --out-dir " + (out / "c").string());
    ASSERT_EQ(fast.exit_code, 0) << fast.err;
    std::ifstream fast_file(out / "c" / "shake.json");
    EXPECT_EQ(nlohmann::json::parse(fast_file)["controller_rate"].get<double>(), 10000.0);
    // a planar-only option is refused by name
    const test::CliResult refused =
        test::runCli("shake" + robot + records + " --axis y --out-dir " + (out / "b").string());
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_NE(refused.err.find("axis"), std::string::npos) << refused.err;
}

/// The 3-D page's embedded data, parsed as the page's script does.
nlohmann::json pageData(const std::string& page) {
    const std::string open = "<script type=\"application/json\" id=\"nocdyn-data\">";
    const std::size_t begin = page.find(open);
    EXPECT_NE(begin, std::string::npos);
    const std::size_t start = begin + open.size();
    return nlohmann::json::parse(page.substr(start, page.find("</script>", start) - start));
}

// The replay drawn in 3-D: shake_animation.html's frames are shake.csv's rows (every one up to
// 2000), their times and leg forces those of the table and their platform point its achieved
// x, y, z (the page holds micrometres).
TEST(SpatialShake, TheReplayIsAnimatedIn3dAlongTheAchievedMotion) {
    const std::filesystem::path out = test::freshScratchDirectory("spatial_shake_animation");
    const test::CliResult run = test::runCli(
        "shake --robot " + kSource + "/robots/stewart.yaml --record " + component("180-hor1.AT2") + " --record " +
        component("270-hor2.AT2") + " --record " + component("-UP.AT2") + " --window 3 --out-dir " + out.string());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("shake_animation.html"), std::string::npos) << run.out;
    const io::Table table = io::readCsvFile((out / "shake.csv").string());
    const std::string page = test::readWhole(out / "shake_animation.html");
    EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
    const nlohmann::json data = pageData(page);
    const auto& t = data["frames"]["t"];
    const auto& tau = data["frames"]["tau"];
    const auto& points = data["frames"]["points"];
    const std::size_t n = data["actuators"].size(), stride = data["stride"];
    ASSERT_EQ(n, 6u);
    EXPECT_EQ(data["samples"], table.rows.size());
    ASSERT_GT(table.rows.size(), 250u);  // 3 s at 0.01 s
    ASSERT_LE(table.rows.size(), 2000u);
    ASSERT_EQ(t.size(), table.rows.size());
    ASSERT_EQ(points.size(), t.size() * stride);
    double moved = 0.0;
    for (std::size_t k = 0; k < table.rows.size(); ++k) {
        const auto& row = table.rows[k];
        EXPECT_NEAR(t[k].get<double>(), row[table.column("t")], 1e-12) << k;
        for (std::size_t a = 0; a < n; ++a) {
            const double expected = row[table.column("tau" + std::to_string(a + 1))];
            EXPECT_NEAR(tau[k * n + a].get<double>(), expected, 1e-9 * std::max(1.0, std::abs(expected))) << k;
        }
        // the platform point, last in the frame, in micrometres: the achieved x, y, z
        const char* axes[] = {"x", "y", "z"};
        for (std::size_t c = 0; c < 3; ++c) {
            const double expected = 1e6 * row[table.column(axes[c])];
            EXPECT_NEAR(points[k * stride + stride - 3 + c].get<double>(), expected, 0.5) << k << " " << axes[c];
            moved = std::max(moved, std::abs(row[table.column(axes[c])] - table.rows[0][table.column(axes[c])]));
        }
    }
    EXPECT_GT(moved, 1e-3);  // the platform moves by millimetres: a check that cannot pass on a still table
}

// A suite on the hexapod: a folder's files grouped by their shared name prefix into records of
// three components, each replayed and scored on ax, ay, az in its own folder, and a summary
// naming the grouping; a component that cannot be grouped is refused naming its file.
TEST(SpatialShake, AFolderOfComponentsIsASuiteOfThreeComponentRecords) {
    const std::filesystem::path out = test::freshScratchDirectory("spatial_shake_suite");
    const std::string robot = "shake --robot " + kSource + "/robots/stewart.yaml";
    const test::CliResult run = test::runCli(robot + " --record " + kSource + "/data/records3 --window 3 --out-dir " +
                                             (out / "suite").string());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::string summary = test::readWhole(out / "suite" / "summary.md");
    EXPECT_EQ(summary, run.out.substr(0, summary.size()));  // printed as written
    EXPECT_NE(summary.find("2 records (three components each)"), std::string::npos) << summary;
    EXPECT_NE(summary.find("grouped into records by their shared name prefix"), std::string::npos) << summary;
    EXPECT_NE(summary.find("RSN1690_NORTH151_SYL090-hor1.AT2, RSN1690_NORTH151_SYL360-hor2.AT2, "
                           "RSN1690_NORTH151_SYL-UP.AT2"),
              std::string::npos)
        << summary;
    EXPECT_NE(
        summary.find("RSN6_IMPVALL.I_I-ELC180-hor1.AT2, RSN6_IMPVALL.I_I-ELC270-hor2.AT2, RSN6_IMPVALL.I_I-ELC-UP.AT2"),
        std::string::npos)
        << summary;
    for (const std::string folder : {"RSN1690_NORTH151_SYL", "RSN6_IMPVALL_I_I-ELC"}) {
        std::ifstream file(out / "suite" / folder / "shake.json");
        ASSERT_TRUE(file.good()) << folder;
        const nlohmann::json json = nlohmann::json::parse(file);
        for (const char* axis : {"ax", "ay", "az"}) {
            const double rms = json["metrics"][axis]["rms_error_percent"].get<double>();
            EXPECT_GT(rms, 0.0) << folder << " " << axis;
            EXPECT_LT(rms, 5.0) << folder << " " << axis;
            // the summary's row of this record and axis carries the same score
            const std::string row = "| " + folder + " | " + axis + " |";
            const std::size_t at = summary.find(row);
            ASSERT_NE(at, std::string::npos) << row << "\n" << summary;
            char printed[32];
            std::snprintf(printed, sizeof printed, "| %.2f %% |", rms);
            EXPECT_NE(summary.substr(at, summary.find('\n', at) - at).find(printed), std::string::npos)
                << printed << " in " << summary.substr(at, summary.find('\n', at) - at);
        }
        EXPECT_TRUE(std::filesystem::exists(out / "suite" / folder / "shake_animation.html")) << folder;
    }
    // the same record alone gives the same scores
    const test::CliResult alone =
        test::runCli(robot + " --record " + component("180-hor1.AT2") + " --record " + component("270-hor2.AT2") +
                     " --record " + component("-UP.AT2") + " --window 3 --out-dir " + (out / "alone").string());
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    EXPECT_EQ(test::readWhole(out / "alone" / "shake.json"),
              test::readWhole(out / "suite" / "RSN6_IMPVALL_I_I-ELC" / "shake.json"));
    // a stray component with no record to join: refused naming it, nothing written
    const std::filesystem::path stray = out / "stray";
    std::filesystem::create_directories(stray);
    for (const char* c : {"180-hor1.AT2", "270-hor2.AT2", "-UP.AT2"})
        std::filesystem::copy_file(component(c), stray / ("RSN6_IMPVALL.I_I-ELC" + std::string(c)));
    std::filesystem::copy_file(kSource + "/data/records3/RSN1690_NORTH151_SYL090-hor1.AT2",
                               stray / "RSN1690_NORTH151_SYL090-hor1.AT2");
    const test::CliResult refused =
        test::runCli(robot + " --record " + stray.string() + " --window 3 --out-dir " + (out / "refused").string());
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
    EXPECT_NE(refused.err.find("RSN1690_NORTH151_SYL090-hor1.AT2: cannot be grouped"), std::string::npos)
        << refused.err;
    EXPECT_FALSE(std::filesystem::exists(out / "refused"));
    // two horizontals without their vertical: refused naming the record and its files
    std::filesystem::remove(stray / "RSN6_IMPVALL.I_I-ELC-UP.AT2");
    for (const char* c : {"-UP.AT2", "360-hor2.AT2"}) {
        std::filesystem::copy_file(kSource + "/data/records3/RSN1690_NORTH151_SYL" + c,
                                   stray / ("RSN1690_NORTH151_SYL" + std::string(c)));
    }
    const test::CliResult no_vertical =
        test::runCli(robot + " --record " + stray.string() + " --window 3 --out-dir " + (out / "refused").string());
    EXPECT_NE(no_vertical.exit_code, 0);
    EXPECT_NE(no_vertical.err.find("RSN6_IMPVALL.I_I-ELC180-hor1.AT2, RSN6_IMPVALL.I_I-ELC270-hor2.AT2): no vertical"),
              std::string::npos)
        << no_vertical.err;
    EXPECT_FALSE(std::filesystem::exists(out / "refused"));
}

}  // namespace
}  // namespace nocdyn
