// `nocdyn workspace --first-frequency / --frequency-map`: the CSV column, the heat map's files,
// the summary naming the lowest first natural frequency and where, agreement with `nocdyn pose`,
// and the refusal of a robot without compliance.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn {
namespace {

namespace fs = std::filesystem;
using test::runCli;

const std::string kCompliant = std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr-compliant.yaml";
const std::string kRigid = std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rrr.yaml";

std::string number(const char* format, double value) {
    char text[64];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

TEST(CliFrequencyMap, WritesTheCsvColumnAndTheHeatMapAndTheSummaryNamesTheLowest) {
    const fs::path dir = test::freshScratchDirectory("cli_frequency_map");
    const test::CliResult r = runCli("workspace --quiet --robot " + kCompliant + " --resolution 41 --frequency-map " +
                                     (dir / "f").string() + " -o " + (dir / "ws.csv").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Table table = io::readCsvFile((dir / "f.csv").string());
    ASSERT_EQ(table.columns, (std::vector<std::string>{"x", "y", "first_frequency"}));
    EXPECT_GT(fs::file_size(dir / "f.png"), 1000u);
    EXPECT_GT(fs::file_size(dir / "f.svg"), 1000u);
    EXPECT_NE(test::readWhole(dir / "f.svg").find("First natural frequency"), std::string::npos);
    // one row per feasible point of the workspace CSV, in its order
    std::istringstream grid(test::readWhole(dir / "ws.csv"));
    std::string line;
    std::size_t feasible = 0;
    while (std::getline(grid, line)) {
        if (!line.ends_with(",feasible")) continue;
        ASSERT_LT(feasible, table.rows.size());
        const auto& row = table.rows[feasible++];
        const std::size_t comma = line.find(',');
        EXPECT_EQ(std::stod(line.substr(0, comma)), row[0]) << line;
        EXPECT_EQ(std::stod(line.substr(comma + 1)), row[1]) << line;
    }
    ASSERT_EQ(table.rows.size(), feasible);
    std::size_t at = 0;
    for (std::size_t k = 1; k < table.rows.size(); ++k) {
        if (table.rows[k][2] < table.rows[at][2]) at = k;
    }
    // the summary (text and JSON) names the CSV's minimum and its point
    const test::CliResult s = runCli("workspace --robot " + kCompliant + " --resolution 41 --first-frequency");
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const std::string expected = "lowest " + number("%.6g", table.rows[at][2]) + " Hz at (x, y) = (" +
                                 number("%.6g", table.rows[at][0] * 1e3) + ", " +
                                 number("%.6g", table.rows[at][1] * 1e3) + ") mm";
    EXPECT_NE(s.out.find(expected), std::string::npos) << expected << "\n" << s.out;
    const test::CliResult j = runCli("workspace --json --robot " + kCompliant + " --resolution 41 --first-frequency");
    ASSERT_EQ(j.exit_code, 0) << j.err;
    const nlohmann::json json = nlohmann::json::parse(j.out);
    EXPECT_EQ(json["first_frequency"]["lowest"].get<double>(), table.rows[at][2]);
    EXPECT_EQ(json["first_frequency"]["lowest_at"]["x"].get<double>(), table.rows[at][0]);
    EXPECT_EQ(json["first_frequency"]["lowest_at"]["y"].get<double>(), table.rows[at][1]);
    EXPECT_EQ(json["first_frequency"]["points"].get<std::size_t>(), feasible);
}

TEST(CliFrequencyMap, ThePointNextToHomeHoldsThePoseCommandsFirstNaturalFrequency) {
    const fs::path dir = test::freshScratchDirectory("cli_frequency_map");
    ASSERT_EQ(
        runCli("workspace --quiet --robot " + kCompliant + " --resolution 41 --frequency-map " + (dir / "f").string())
            .exit_code,
        0);
    const io::Table table = io::readCsvFile((dir / "f.csv").string());
    // the robot's home is C = (0, 0), theta = 0; the grid point nearest to it
    std::size_t at = 0;
    for (std::size_t k = 1; k < table.rows.size(); ++k) {
        if (std::hypot(table.rows[k][0], table.rows[k][1]) < std::hypot(table.rows[at][0], table.rows[at][1])) at = k;
    }
    const double x = table.rows[at][0], y = table.rows[at][1];
    EXPECT_LT(std::hypot(x, y), 1e-3);  // within a grid step of home
    const test::CliResult pose =
        runCli("pose " + number("%.17g", x) + " " + number("%.17g", y) + " 0 --json --robot " + kCompliant);
    ASSERT_EQ(pose.exit_code, 0) << pose.err;
    const double f1 = nlohmann::json::parse(pose.out)["natural_frequencies"][0].get<double>();
    EXPECT_NEAR(table.rows[at][2], f1, 1e-12 * f1);
    // and the home pose itself: the paper's prototype, about 40 Hz
    const test::CliResult home = runCli("pose 0 0 0 --json --robot " + kCompliant);
    ASSERT_EQ(home.exit_code, 0) << home.err;
    EXPECT_NEAR(nlohmann::json::parse(home.out)["natural_frequencies"][0].get<double>(), table.rows[at][2], 0.01);
}

TEST(CliFrequencyMap, ARobotWithoutComplianceIsRefusedWithAClearMessage) {
    const fs::path dir = test::freshScratchDirectory("cli_frequency_map");
    for (const std::string& option : {std::string("--first-frequency"), "--frequency-map " + (dir / "f").string()}) {
        const test::CliResult r = runCli("workspace --resolution 21 --robot " + kRigid + " " + option);
        EXPECT_NE(r.exit_code, 0) << option;
        EXPECT_NE(r.err.find("robot '3-rrr'"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("declares no compliance"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
        EXPECT_FALSE(fs::exists(dir / "f.csv"));
        EXPECT_FALSE(fs::exists(dir / "f.png"));
    }
    // the workspace alone still runs
    EXPECT_EQ(runCli("workspace --quiet --resolution 21 --robot " + kRigid).exit_code, 0);
}

/// The lines of a CSV file split at commas (no quoted fields in these files).
std::vector<std::vector<std::string>> csvRows(const fs::path& path) {
    std::istringstream text(test::readWhole(path));
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(text, line);) {
        std::vector<std::string> fields;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(cell);
        rows.push_back(fields);
    }
    return rows;
}

TEST(CliFrequencyMap, TheDesignMetricIsTheWorkspaceCommandsLowestFirstFrequency) {
    const fs::path dir = test::freshScratchDirectory("cli_frequency_map");
    // the 3-RRR family with a drive stiffness of 20 N m/rad at each actuated joint
    std::string family = test::readWhole(fs::path(NOCDYN_SOURCE_DIR) / "examples" / "design_3rrr" / "family.yaml");
    for (std::size_t at = family.find("actuated: true,"); at != std::string::npos;
         at = family.find("actuated: true,", at + 1)) {
        family.insert(at + std::string("actuated: true,").size(), " stiffness: 20.0,");
    }
    std::ofstream(dir / "family.yaml") << family;
    const std::string sweep =
        " --vary r_b=0.19:0.21 --sweep grid --samples 2 --resolution 21 --threads 1 --metric "
        "first_frequency_min --metric workspace_area --out-dir ";
    const test::CliResult r =
        runCli("design --robot " + (dir / "family.yaml").string() + sweep + (dir / "run").string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = csvRows(dir / "run" / "designs.csv");
    ASSERT_EQ(rows.size(), 3u);
    ASSERT_EQ(rows[0], (std::vector<std::string>{"design", "r_b", "first_frequency_min", "workspace_area", "feasible",
                                                 "reason"}));
    for (std::size_t k = 1; k < rows.size(); ++k) {
        ASSERT_EQ(rows[k][4], "true") << rows[k][5];
        const test::CliResult w = runCli("workspace --json --first-frequency --resolution 21 --robot " +
                                         (dir / "family.yaml").string() + " --set r_b=" + rows[k][1]);
        ASSERT_EQ(w.exit_code, 0) << w.err;
        const double lowest = nlohmann::json::parse(w.out)["first_frequency"]["lowest"].get<double>();
        EXPECT_EQ(std::stod(rows[k][2]), lowest) << rows[k][1];
        EXPECT_GT(lowest, 1.0);
    }
    // the family as it is (no compliance, a structural fact): refused before the first design,
    // as workspace --first-frequency refuses the robot
    const test::CliResult rigid = runCli("design --robot " + std::string(NOCDYN_SOURCE_DIR) +
                                         "/examples/design_3rrr/family.yaml" + sweep + (dir / "rigid").string());
    EXPECT_EQ(rigid.exit_code, 2) << rigid.out;
    EXPECT_NE(rigid.err.find("--metric: first_frequency_min: the family '3-rrr-family' declares no compliance"),
              std::string::npos)
        << rigid.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "rigid" / "designs.csv"));
}

}  // namespace
}  // namespace nocdyn
