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
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/layouts.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kRobots = std::string(NOCDYN_SOURCE_DIR) + "/robots/";

std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

/// The words of column `column` of a CSV text, row by row.
std::vector<std::string> words(const std::string& text, std::size_t column) {
    std::vector<std::string> out;
    std::size_t at = text.find('\n') + 1;
    while (at < text.size()) {
        const std::size_t end = text.find('\n', at);
        std::string line = text.substr(at, end - at);
        for (std::size_t c = 0; c < column; ++c) line = line.substr(line.find(',') + 1);
        out.push_back(line.substr(0, line.find(',')));
        at = end + 1;
    }
    return out;
}

/// The first natural frequency at home as `nocdyn pose --json` reports it.
double poseFirstFrequency(const std::string& robot) {
    const CliResult home = runCli("pose --robot " + robot + " --json 0 0 0");
    EXPECT_EQ(home.exit_code, 0) << home.err;
    return nlohmann::json::parse(home.out)["natural_frequencies"][0].get<double>();
}

TEST(CliEnvelope, ACompliantRobotsBandEndsAtItsFirstNaturalFrequency) {
    const fs::path dir = freshScratchDirectory("cli_envelope");
    const std::string robot = kRobots + "paper-3prr-compliant.yaml";
    const double f1 = poseFirstFrequency(robot);
    ASSERT_GT(f1, 0.0);
    // f_1 / 2, f_1 and 2 f_1, log-spaced, written as the shortest decimals that read back
    char range[120];
    std::snprintf(range, sizeof range, " --points 3 --min-frequency %.17g --max-frequency %.17g", 0.5 * f1, 2.0 * f1);
    const CliResult r = runCli("envelope --robot " + robot + range + " -o " + (dir / "e.csv").string() + " --figure " +
                               (dir / "e").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    char summary[200];
    std::snprintf(summary, sizeof summary, "third bound: first natural frequency %.6g Hz (lumped model at home)", f1);
    EXPECT_NE(r.out.find(summary), std::string::npos) << r.out;

    const io::Table table = io::readCsvFile((dir / "e.csv").string());
    ASSERT_EQ(table.columns, io::columnNames(io::TableId::envelope, {.optional = true}));
    const std::size_t frequency = table.column("frequency"), first = table.column("first_natural_frequency");
    const std::string text = readWhole(dir / "e.csv");
    const std::vector<std::string> axes = words(text, 0), limits = words(text, 3);
    ASSERT_EQ(table.rows.size(), 9u);
    ASSERT_EQ(limits.size(), 9u);
    EXPECT_EQ(axes, (std::vector<std::string>{"x", "x", "x", "y", "y", "y", "theta", "theta", "theta"}));
    for (std::size_t i = 0; i < table.rows.size(); ++i) {
        EXPECT_EQ(table.rows[i][first], f1) << i;  // the same number as `nocdyn pose`, to the bit
        const bool beyond = table.rows[i][frequency] >= f1;
        EXPECT_EQ(limits[i] == "resonance", beyond) << i << ": " << limits[i] << " at " << table.rows[i][frequency];
        if (beyond) EXPECT_EQ(table.rows[i][table.column("actuator")], 0.0) << i;
    }
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
