// `nocdyn envelope` on the command line: its points in the order x, y, theta; with a robot file
// that declares compliance, the band's third bound (the first natural frequency at home, as
// `nocdyn pose --json` reports it) in the summary line, the CSV's first_natural_frequency column
// and the limit `resonance` at and above it, and a figure that draws it; without, the CSV of
// old and a summary that says why the bound is unknown.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/io/layouts.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kRobots = std::string(NOCDYN_SOURCE_DIR) + "/robots/";

std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

/// The cells of each line of a CSV text (the header first).
std::vector<std::vector<std::string>> cells(const std::string& text) {
    std::vector<std::vector<std::string>> out;
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t end = text.find('\n', at);
        const std::string line = text.substr(at, end - at);
        std::vector<std::string> row;
        for (std::size_t from = 0;;) {
            const std::size_t comma = line.find(',', from);
            row.push_back(line.substr(from, comma - from));
            if (comma == std::string::npos) break;
            from = comma + 1;
        }
        out.push_back(std::move(row));
        at = end == std::string::npos ? text.size() : end + 1;
    }
    return out;
}

/// The words of column `column` of a CSV text, row by row.
std::vector<std::string> words(const std::string& text, std::size_t column) {
    std::vector<std::string> out;
    const auto rows = cells(text);
    for (std::size_t i = 1; i < rows.size(); ++i) out.push_back(rows[i].at(column));
    return out;
}

/// The first natural frequency at home as `nocdyn pose --json` reports it.
double poseFirstFrequency(const std::string& robot) {
    const CliResult home = runCli("pose --robot " + robot + " --json 0 0 0");
    EXPECT_EQ(home.exit_code, 0) << home.err;
    return nlohmann::json::parse(home.out)["natural_frequencies"][0].get<double>();
}

// With --amplification 1.5 the band of each axis ends between f_1 / 2 (x: 1 / (1 - 1/4) = 1.33,
// theta a little less) and f_1: the rows at f_1 and 2 f_1 are beyond it.
TEST(CliEnvelope, ACompliantRobotsBandEndsWhereItsAmplificationReachesTheLimit) {
    const fs::path dir = freshScratchDirectory("cli_envelope");
    const std::string robot = kRobots + "paper-3prr-compliant.yaml";
    const double f1 = poseFirstFrequency(robot);
    ASSERT_GT(f1, 0.0);
    // f_1 / 2, f_1 and 2 f_1, log-spaced, written as the shortest decimals that read back
    char range[120];
    std::snprintf(range, sizeof range, " --points 3 --min-frequency %.17g --max-frequency %.17g --amplification 1.5",
                  0.5 * f1, 2.0 * f1);
    const CliResult r = runCli("envelope --robot " + robot + range + " -o " + (dir / "e.csv").string() + " --figure " +
                               (dir / "e").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    char summary[200];
    std::snprintf(summary, sizeof summary, "damping ratio 0.02, first natural frequency %.6g Hz) leaves [1/1.5, 1.5]",
                  f1);
    EXPECT_NE(r.out.find(summary), std::string::npos) << r.out;

    const auto rows = cells(readWhole(dir / "e.csv"));
    ASSERT_EQ(rows.size(), 10u);
    ASSERT_EQ(rows[0], io::columnNames(io::TableId::envelope, {.optional = true}));
    const std::vector<std::string> axes = words(readWhole(dir / "e.csv"), 0);
    EXPECT_EQ(axes, (std::vector<std::string>{"x", "x", "x", "y", "y", "y", "theta", "theta", "theta"}));
    int beyond_rows = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        // columns: frequency 1, limit 3, actuator 6, first_natural_frequency 11
        EXPECT_EQ(std::stod(rows[i][11]), f1) << i;  // the same number as `nocdyn pose`, to the bit
        const double f = std::stod(rows[i][1]);
        const bool beyond = f >= f1;
        beyond_rows += beyond ? 1 : 0;
        EXPECT_EQ(rows[i][3] == "resonance", beyond) << i << ": " << rows[i][3] << " at " << f;
        if (beyond) {
            EXPECT_EQ(rows[i][6], "0") << i;
        }
    }
    EXPECT_EQ(beyond_rows, 6);  // f_1 and 2 f_1 on each axis
    // the figure draws the bound with its number and shades what lies beyond
    const std::string svg = readWhole(dir / "e.svg");
    char label[80];
    std::snprintf(label, sizeof label, "first natural frequency %.4g Hz", f1);
    EXPECT_NE(svg.find(label), std::string::npos);
    EXPECT_NE(svg.find("beyond the band"), std::string::npos);
}

TEST(CliEnvelope, WithoutComplianceTheTableIsAsBeforeAndTheSummarySaysWhyTheBoundIsUnknown) {
    const fs::path dir = freshScratchDirectory("cli_envelope");
    const CliResult r = runCli("envelope --points 2 --robot " + kRobots + "3-rrr.yaml -o " + (dir / "e.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out,
              "third bound (first natural frequency): unknown, the robot file declares no compliance (joint "
              "stiffness, body elastic: docs/robot-files.md, Compliance)\n");
    const std::string text = readWhole(dir / "e.csv");
    EXPECT_EQ(
        firstLine(text),
        "axis,frequency,amplitude,limit,limb,joint,actuator,kinematic_amplitude,peak_effort_ratio,peak_u,peak_tau");
    EXPECT_EQ(words(text, 0), (std::vector<std::string>{"x", "x", "y", "y", "theta", "theta"}));
    for (const std::string& limit : words(text, 3)) EXPECT_NE(limit, "resonance");
    // the table on stdout, axis after axis in the same order, then the summary
    const CliResult table = runCli("envelope --points 1 --robot " + kRobots + "3-rrr.yaml");
    ASSERT_EQ(table.exit_code, 0) << table.err;
    const std::size_t x = table.out.find("\nx "), y = table.out.find("\ny "), theta = table.out.find("\ntheta ");
    EXPECT_TRUE(x < y && y < theta && theta != std::string::npos) << table.out;
    EXPECT_NE(table.out.find("\nthird bound (first natural frequency): unknown"), std::string::npos) << table.out;
}

}  // namespace
}  // namespace nocdyn::test
