// `nocdyn animate`: one self-contained page (no external script, nothing fetched), under 2 MB
// for 0.2 s at 10 kHz, keeping every sample's extremes in its plots; motions from
// inverse-dynamics, simulate and control; names from files shown as data; bad input refused in
// one line with no file left behind; static frames as PNG and SVG.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "page_data.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

fs::path scratchDirectory() { return freshScratchDirectory("nocdyn_cli_animate_test"); }

std::string robotFile(const std::string& name) { return std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml"; }

void expectSelfContained(const std::string& page) {
    EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_EQ(page.substr(page.size() - 8), "</html>\n");
    EXPECT_EQ(occurrences(page, "<script"), 2u);  // the data and the inline program
    EXPECT_EQ(occurrences(page, "</script>"), 2u);
    EXPECT_EQ(page.find(" src="), std::string::npos);
    EXPECT_EQ(page.find("http://"), std::string::npos);
    EXPECT_EQ(page.find("https://"), std::string::npos);
    EXPECT_EQ(page.find("<link"), std::string::npos);
    EXPECT_EQ(page.find("import("), std::string::npos);
    EXPECT_EQ(page.find("fetch("), std::string::npos);
}

TEST(CliAnimate, PageOfEveryExampleRobotIsSelfContainedAndUnder2MBFor02sAt10kHz) {
    const fs::path dir = scratchDirectory();
    for (const std::string robot : {"paper-3prr", "paper-3prr-general", "3-rrr", "3-rpr", "4-rrr"}) {
        const fs::path page = dir / (robot + ".html");
        const CliResult r = runCli("animate --robot " + robotFile(robot) +
                                   " --trajectory paper1 --duration 0.2 --rate 10000 --output " + page.string());
        ASSERT_EQ(r.exit_code, 0) << robot << ": " << r.err;
        const std::string text = readWhole(page);
        expectSelfContained(text);
        EXPECT_LT(text.size(), 2'000'000u) << robot;
        const nlohmann::json data = pageData(text);
        EXPECT_EQ(data["samples"], 2000) << robot;
        EXPECT_EQ(data["frames"]["t"].size(), 2000u) << robot;
        EXPECT_EQ(data["frames"]["points"].size(), 2000u * data["stride"].get<std::size_t>()) << robot;
    }
}

TEST(CliAnimate, PlotsKeepEverySamplesExtremesOfTheInverseDynamics) {
    const fs::path dir = scratchDirectory();
    const std::string robot = robotFile("3-rpr");
    const fs::path csv = dir / "id.csv", page = dir / "page.html";
    ASSERT_EQ(
        runCli("inverse-dynamics --robot " + robot + " --trajectory paper2 --rate 10000 -o " + csv.string()).exit_code,
        0);
    const CliResult r =
        runCli("animate --robot " + robot + " --trajectory paper2 --rate 10000 --output " + page.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Table table = io::readCsvFile(csv.string());
    const nlohmann::json data = pageData(readWhole(page));
    ASSERT_LT(data["plots"]["t"].size(), table.rows.size());  // decimated...
    for (const std::string series : {"u", "tau"}) {
        for (std::size_t a = 0; a < 3; ++a) {
            const std::size_t c = table.column(series + std::to_string(a + 1));
            double lo = INFINITY, hi = -INFINITY;
            for (const auto& row : table.rows) {
                lo = std::min(lo, row[c]);
                hi = std::max(hi, row[c]);
            }
            const auto& s = data["plots"][series][a];
            const double page_lo = *std::min_element(s["lo"].begin(), s["lo"].end());
            const double page_hi = *std::max_element(s["hi"].begin(), s["hi"].end());
            // ...but every extreme is there (6 significant digits)
            EXPECT_NEAR(page_lo, lo, 1e-5 * std::abs(lo)) << series << a + 1;
            EXPECT_NEAR(page_hi, hi, 1e-5 * std::abs(hi)) << series << a + 1;
        }
    }
}

TEST(CliAnimate, MotionsWrittenByInverseDynamicsSimulateAndControlAreAnimated) {
    const fs::path dir = scratchDirectory();
    const std::string robot = robotFile("3-rrr");
    const fs::path id = dir / "id.csv", sim = dir / "sim.csv", ctl = dir / "ctl.csv";
    ASSERT_EQ(runCli("inverse-dynamics --robot " + robot + " --trajectory paper1 --duration 0.02 --rate 2000 -o " +
                     id.string())
                  .exit_code,
              0);
    const CliResult s = runCli("simulate --robot " + robot + " --forces " + id.string() + " -o " + sim.string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const CliResult c = runCli("control --plant nocdyn --robot " + robot +
                               " --trajectory paper1 --duration 0.02 --rate 2000 -o " + ctl.string());
    ASSERT_EQ(c.exit_code, 0) << c.err;
    for (const fs::path& motion : {id, sim, ctl}) {
        const fs::path page = dir / (motion.stem().string() + ".html");
        const CliResult r = runCli("animate --robot " + robot + " --motion " + motion.string() + " --output " +
                                   page.string() + " --slow-motion 20 --magnify 5");
        ASSERT_EQ(r.exit_code, 0) << motion << ": " << r.err;
        const std::string text = readWhole(page);
        expectSelfContained(text);
        const nlohmann::json data = pageData(text);
        const io::Table table = io::readCsvFile(motion.string());
        EXPECT_EQ(data["samples"], table.rows.size());
        EXPECT_EQ(data["slowMotion"], 20.0);
        EXPECT_EQ(data["magnify"], 5.0);
        // the first frame's C is the first row's pose, in micrometres
        const auto& points = data["frames"]["points"];
        const std::size_t stride = data["stride"];
        EXPECT_NEAR(points[stride - 2].get<double>(), 1e6 * table.rows[0][table.column("x")], 0.5);
        EXPECT_NEAR(points[stride - 1].get<double>(), 1e6 * table.rows[0][table.column("y")], 0.5);
    }
}

TEST(CliAnimate, RobotNameCannotLeaveTheDataScript) {
    const fs::path dir = scratchDirectory();
    std::ifstream in(robotFile("3-rrr"));
    std::string text((std::istreambuf_iterator<char>(in)), {});
    const std::string name = "x</script><script>alert(1)</script><!--&";
    const std::size_t at = text.find("name: ");
    text.replace(at, text.find('\n', at) - at, "name: \"" + name + "\"");
    std::ofstream(dir / "robot.yaml") << text;
    const fs::path page = dir / "page.html";
    const CliResult r = runCli("animate --robot " + (dir / "robot.yaml").string() +
                               " --trajectory paper1 --rate 1000 --output " + page.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string html = readWhole(page);
    expectSelfContained(html);
    EXPECT_EQ(html.find("alert(1)</script>"), std::string::npos);
    EXPECT_EQ(pageData(html)["robot"], name);  // shown as it is
}

/// Runs animate expecting a one-line error containing every piece of `expected`, and no output.
void expectRefused(const std::string& arguments, const std::vector<std::string>& expected, const fs::path& out) {
    const CliResult r = runCli("animate " + arguments + " --output " + out.string());
    EXPECT_NE(r.exit_code, 0) << arguments;
    EXPECT_EQ(occurrences(r.err, "\n"), 1u) << r.err;
    for (const std::string& piece : expected) EXPECT_NE(r.err.find(piece), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << arguments;
}

TEST(CliAnimate, BadInputIsOneLineNamingFileLineAndFieldAndWritesNothing) {
    const fs::path dir = scratchDirectory();
    const fs::path out = dir / "never.html";
    const std::string robot = robotFile("3-rrr");
    std::ofstream(dir / "no_tau.csv") << "t,theta,x,y,tau1,tau2\n0,0,0,0,1,2\n";
    expectRefused("--robot " + robot + " --motion " + (dir / "no_tau.csv").string(), {"no_tau.csv", "tau3"}, out);
    std::ofstream(dir / "backwards.csv")
        << "t,theta,x,y,tau1,tau2,tau3\n0,0,0,0,1,2,3\n0.1,0,0,0,1,2,3\n0.1,0,0,0,1,2,3\n";
    expectRefused("--robot " + robot + " --motion " + (dir / "backwards.csv").string(), {"backwards.csv:4", "t = 0.1"},
                  out);
    std::ofstream(dir / "far.csv") << "t,theta,x,y,tau1,tau2,tau3\n0,0,0,0,1,2,3\n0.1,0,2.5,0,1,2,3\n";
    expectRefused("--robot " + robot + " --motion " + (dir / "far.csv").string(), {"far.csv:3", "t = 0.1", "limb"},
                  out);
    std::ofstream(dir / "nan.csv") << "t,theta,x,y,tau1,tau2,tau3\n0,0,nan,0,1,2,3\n";
    expectRefused("--robot " + robot + " --motion " + (dir / "nan.csv").string(), {"nan.csv:2"}, out);
    expectRefused("--robot " + robot, {"--trajectory or --motion"}, out);
    expectRefused("--trajectory paper1 --motion " + (dir / "far.csv").string(), {"excludes"}, out);
    expectRefused("--trajectory paper1 --slow-motion 0", {"--slow-motion"}, out);
    expectRefused("--trajectory paper1 --magnify nan", {"--magnify"}, out);
    expectRefused("--trajectory paper1 --rate 1e8 --duration 1", {"samples"}, out);
    expectRefused("--trajectory paper1 --frame 0.1", {"--png or --svg"}, out);
    expectRefused("--trajectory paper1 --png x.png", {"--frame"}, out);
}

TEST(CliAnimate, FrameIsDrawnAsPngAndSvgOfTheRobot) {
    const fs::path dir = scratchDirectory();
    const fs::path png = dir / "frame.png", svg = dir / "frame.svg";
    const CliResult r =
        runCli("animate --robot " + robotFile("3-rpr") + " --trajectory paper1 --rate 1000 --frame 0.05 --png " +
               png.string() + " --svg " + svg.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(fs::is_regular_file(png));
    EXPECT_GT(fs::file_size(png), 5000u);
    const std::string drawing = readWhole(svg);
    EXPECT_NE(drawing.find("<svg"), std::string::npos);
    EXPECT_NE(drawing.find("3-rpr at t = 0.05 s"), std::string::npos);
    EXPECT_NE(drawing.find("rails (stroke)"), std::string::npos);  // the RPR's telescopic legs
    // in millimetres, as every other figure
    EXPECT_NE(drawing.find("x [mm]"), std::string::npos);
    EXPECT_NE(drawing.find("y [mm]"), std::string::npos);
    EXPECT_FALSE(fs::exists("robot.html"));  // no page without --output
}

}  // namespace
}  // namespace nocdyn::test
