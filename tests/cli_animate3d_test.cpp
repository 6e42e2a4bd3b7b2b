// `nocdyn animate` of a spatial robot: one self-contained 3-D page (three.js inlined from
// Debian's libjs-three, nothing referenced outside the page), its frames holding every limb's
// joint chain and the platform point, its forces those of `nocdyn inverse-dynamics`; bad input
// refused in one line with no file left behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "page_data.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

std::string robotFile(const std::string& name) { return std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml"; }
std::string trajectoryFile(const std::string& name) {
    return std::string(NOCDYN_SOURCE_DIR) + "/trajectories/" + name + ".yaml";
}

/// A sway of the 6-RUS about its home (z = 0.308 m): a few mm and about a degree.
fs::path rusSway(const fs::path& dir) {
    const fs::path path = dir / "6-rus-sway.yaml";
    std::ofstream(path) << "name: 6-rus-sway\nduration: 1.0\n"
                           "x: {harmonics: [{amplitude: 0.005, frequency: 2}]}\n"
                           "y: {harmonics: [{amplitude: 0.003, frequency: 3, phase: 0.5}]}\n"
                           "z: {offset: 0.30794957407098617, harmonics: [{amplitude: 0.004, frequency: 1}]}\n"
                           "roll: {harmonics: [{amplitude: 0.0175, frequency: 2}]}\n"
                           "pitch: {harmonics: [{amplitude: 0.0175, frequency: 1, phase: 1.0}]}\n"
                           "yaw: {harmonics: [{amplitude: 0.026, frequency: 3, phase: -0.3}]}\n";
    return path;
}

/// Every library the page inlines, as Debian ships it.
std::vector<std::string> threeJs() {
    return {readWhole("/usr/share/javascript/three/three.min.js"),
            readWhole("/usr/share/javascript/three/examples/js/controls/OrbitControls.js")};
}

TEST(CliAnimate3d, PageOfEverySpatialRobotIsSelfContainedWithItsLimbsAndFrames) {
    const fs::path dir = freshScratchDirectory("nocdyn_cli_animate3d_test");
    struct Case {
        std::string robot, trajectory, rate, chain;
        std::size_t limbs, samples;
    };
    const Case cases[] = {{"delta", trajectoryFile("delta-pick"), "500", "RUU", 3, 500},
                          {"stewart", trajectoryFile("stewart-sway"), "1500", "US", 6, 3000},
                          {"hexa-6rus", rusSway(dir).string(), "300", "RUS", 6, 300}};
    for (const Case& c : cases) {
        const fs::path page = dir / (c.robot + ".html");
        const CliResult r = runCli("animate --robot " + robotFile(c.robot) + " --trajectory " + c.trajectory +
                                   " --rate " + c.rate + " --output " + page.string());
        ASSERT_EQ(r.exit_code, 0) << c.robot << ": " << r.err;
        std::string text = readWhole(page);
        EXPECT_EQ(text.rfind("<!DOCTYPE html>", 0), 0u) << c.robot;
        EXPECT_EQ(text.substr(text.size() - 8), "</html>\n") << c.robot;
        EXPECT_EQ(occurrences(text, "<script"), 3u);  // the data, three.js, the page's program
        EXPECT_EQ(occurrences(text, "</script>"), 3u);
        EXPECT_LT(text.size(), 3'000'000u) << c.robot;
        const nlohmann::json data = pageData(text);
        // three.js is inlined as Debian ships it; apart from its text (where URLs are XML
        // namespaces and comments, never fetched) nothing refers outside the page
        for (const std::string& library : threeJs()) {
            ASSERT_GT(library.size(), 1000u);
            const std::size_t at = text.find(library);
            ASSERT_NE(at, std::string::npos) << c.robot;
            text.erase(at, library.size());
        }
        for (const char* external : {"http://", "https://", " src=", "<link", "import(", "fetch(", "@NOCDYN"})
            EXPECT_EQ(text.find(external), std::string::npos) << c.robot << ": " << external;
        // frames: every sample up to 2000, evenly spread beyond
        const std::size_t frames = std::min<std::size_t>(c.samples, 2000);
        EXPECT_EQ(data["samples"], c.samples) << c.robot;
        ASSERT_EQ(data["frames"]["t"].size(), frames) << c.robot;
        ASSERT_EQ(data["limbs"].size(), c.limbs) << c.robot;
        std::size_t drawn = 0;
        for (const auto& limb : data["limbs"]) {
            EXPECT_EQ(limb["joints"], c.chain) << c.robot;
            EXPECT_EQ(limb["at"], 3 * drawn) << c.robot;
            EXPECT_GE(limb["actuator"].get<int>(), 0) << c.robot;
            drawn += c.chain.size();
        }
        const std::size_t stride = data["stride"];
        EXPECT_EQ(stride, 3 * drawn + 3) << c.robot;  // the joint chains, then the platform point
        EXPECT_EQ(data["frames"]["points"].size(), frames * stride) << c.robot;
        EXPECT_EQ(data["frames"]["tau"].size(), frames * data["actuators"].size()) << c.robot;
        EXPECT_EQ(data["around"].size(), c.limbs) << c.robot;
    }
}

TEST(CliAnimate3d, LegForcesAndPlatformPointAreThoseOfInverseDynamics) {
    const fs::path dir = freshScratchDirectory("nocdyn_cli_animate3d_forces");
    for (const auto& [robot, trajectory] : {std::pair<std::string, std::string>{"stewart", "stewart-sway"},
                                            std::pair<std::string, std::string>{"delta", "delta-pick"}}) {
        const fs::path csv = dir / (robot + ".csv"), page = dir / (robot + ".html");
        const std::string common = "--robot " + robotFile(robot) + " --trajectory " + trajectoryFile(trajectory) +
                                   " --rate 400 --duration 0.5";
        ASSERT_EQ(runCli("inverse-dynamics " + common + " -o " + csv.string()).exit_code, 0) << robot;
        const CliResult r = runCli("animate " + common + " --output " + page.string());
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const io::Table table = io::readCsvFile(csv.string());
        const nlohmann::json data = pageData(readWhole(page));
        const auto& t = data["frames"]["t"];
        const auto& tau = data["frames"]["tau"];
        const auto& points = data["frames"]["points"];
        const std::size_t n = data["actuators"].size(), stride = data["stride"];
        ASSERT_EQ(t.size(), table.rows.size()) << robot;
        for (const std::size_t k : {std::size_t{0}, std::size_t{77}, table.rows.size() - 1}) {
            const auto& row = table.rows[k];
            EXPECT_EQ(t[k].get<double>(), row[table.column("t")]) << robot;
            for (std::size_t a = 0; a < n; ++a) {
                const double expected = row[table.column("tau" + std::to_string(a + 1))];
                EXPECT_NEAR(tau[k * n + a].get<double>(), expected, 1e-12 * std::max(1.0, std::abs(expected)))
                    << robot << " t = " << row[0] << " tau" << a + 1;
            }
            // the platform point, last in the frame, in micrometres
            const char* axes[] = {"x", "y", "z"};
            for (std::size_t c = 0; c < 3; ++c) {
                EXPECT_NEAR(points[k * stride + stride - 3 + c].get<double>(), 1e6 * row[table.column(axes[c])], 0.5)
                    << robot << " t = " << row[0] << " " << axes[c];
            }
        }
        // the forces move: a check that cannot pass on a constant
        EXPECT_NE(tau[0].get<double>(), tau[77 * n].get<double>()) << robot;
    }
}

/// Runs animate expecting a one-line error containing every piece of `expected`, and no output.
void expectRefused(const std::string& arguments, const std::vector<std::string>& expected, const fs::path& out) {
    const CliResult r = runCli("animate " + arguments + " --output " + out.string());
    EXPECT_NE(r.exit_code, 0) << arguments;
    EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
    for (const std::string& piece : expected) EXPECT_NE(r.err.find(piece), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << arguments;
}

TEST(CliAnimate3d, BadInputIsOneLineAndWritesNothing) {
    const fs::path dir = freshScratchDirectory("nocdyn_cli_animate3d_bad");
    const fs::path out = dir / "never.html";
    const std::string stewart = "--robot " + robotFile("stewart");
    expectRefused(stewart + " --trajectory " + (dir / "absent.yaml").string(), {"absent.yaml"}, out);
    // a translation robot's trajectory (x, y, z) for a robot of six coordinates
    expectRefused(stewart + " --trajectory " + trajectoryFile("delta-pick"), {"delta-pick"}, out);
    // the Delta's gripper 5 m below its base: no limb reaches it
    std::ofstream(dir / "far.yaml") << "name: far\nduration: 0.1\nx: {offset: 0}\ny: {offset: 0}\nz: {offset: -5.0}\n";
    expectRefused("--robot " + robotFile("delta") + " --trajectory " + (dir / "far.yaml").string(), {"t = 0", "limb"},
                  out);
    std::ofstream(dir / "bad.yaml") << "name: bad\nx: {offset: [1, 2]}\n";
    expectRefused(stewart + " --trajectory " + (dir / "bad.yaml").string(), {"bad.yaml"}, out);
    std::ofstream(dir / "m.csv") << "t,x,y,theta,tau1\n0,0,0,0,1\n";
    expectRefused(stewart + " --motion " + (dir / "m.csv").string(), {"motion", "planar", "--trajectory"}, out);
    expectRefused(
        stewart + " --trajectory " + trajectoryFile("stewart-sway") + " --frame 0.1 --png " + (dir / "f.png").string(),
        {"frame", "planar", "3-D"}, out);
    EXPECT_FALSE(fs::exists(dir / "f.png"));
    expectRefused(stewart + " --trajectory " + trajectoryFile("stewart-sway") + " --rate 1e6 --duration 100",
                  {"samples"}, out);
}

}  // namespace
}  // namespace nocdyn::test
