// nocdyn design: every metric in designs.csv equals the single-robot command on the plain
// robot file `nocdyn convert --set` writes for that design; a stopped sweep resumes with the
// same table; bad input is one line naming the parameter, metric or expression.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <string>

#include "cli_support.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

const std::string kFamily = std::string(NOCDYN_SOURCE_DIR) + "/examples/design_3rrr/family.yaml";
/// The workspace summary prints 6 significant digits.
constexpr double kSummaryDigits = 1e-5;

std::vector<std::vector<std::string>> readRows(const fs::path& path) {
    std::vector<std::vector<std::string>> rows;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> fields;
        std::string field;
        bool quoted = false;
        for (const char c : line) {
            if (c == '"')
                quoted = !quoted;
            else if (c == ',' && !quoted) {
                fields.push_back(field);
                field.clear();
            } else {
                field += c;
            }
        }
        fields.push_back(field);
        rows.push_back(fields);
    }
    return rows;
}

double summaryNumber(const std::string& text, const std::string& pattern) {
    std::smatch m;
    if (!std::regex_search(text, m, std::regex(pattern))) return std::nan("");
    return std::stod(m[1].str());
}

std::string sweep(const fs::path& out) {
    return "design --robot " + kFamily +
           " --vary r_b=0.15:0.25 --vary l1=0.08:0.14 --set l2=0.11 --samples 10 --seed 3 --metric workspace_area"
           " --metric condition_median --metric condition_worst --metric envelope_x@50 --metric moving_mass"
           " --resolution 31 --threads 2 --no-figures --out-dir " +
           out.string();
}

TEST(CliDesign, EveryMetricEqualsTheSingleRobotCommandOnTheConvertedDesign) {
    const fs::path dir = freshScratchDirectory("nocdyn_cli_design_test");
    const CliResult r = runCli(sweep(dir / "run"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = readRows(dir / "run" / "designs.csv");
    ASSERT_EQ(rows.size(), 11u);
    EXPECT_EQ(rows[0],
              (std::vector<std::string>{"design", "r_b", "l1", "workspace_area", "condition_median", "condition_worst",
                                        "envelope_x@50", "moving_mass", "feasible", "reason"}));
    // designs numbered from 1, as a person reads them
    for (std::size_t k = 1; k < rows.size(); ++k) EXPECT_EQ(rows[k][0], std::to_string(k));
    EXPECT_TRUE(fs::exists(dir / "run" / "pareto.csv"));
    // the best design by the first metric (workspace_area, larger is better) is named, with its
    // parameters, as designs.csv has it
    std::size_t best = 0;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        if (rows[i][8] == "true" && (best == 0 || std::stod(rows[i][3]) > std::stod(rows[best][3]))) best = i;
    }
    ASSERT_GT(best, 0u);
    const std::string named = "best by workspace_area: design " + rows[best][0] + " (r_b = ";
    EXPECT_NE(r.out.find(named), std::string::npos) << r.out;
    EXPECT_NEAR(summaryNumber(r.out, "best by workspace_area: .*, workspace_area = ([0-9.e+-]+)"),
                std::stod(rows[best][3]), 1e-5 * std::stod(rows[best][3]))
        << r.out;
    std::mt19937 pick(11);
    int checked = 0;
    for (int tries = 0; tries < 40 && checked < 2; ++tries) {
        const auto& row = rows[1 + pick() % 10];
        if (row[8] != "true") continue;
        const fs::path plain = dir / ("design" + row[0] + ".yaml");
        const CliResult c = runCli("convert " + kFamily + " --set r_b=" + row[1] + " --set l1=" + row[2] +
                                   " --set l2=0.11 -o " + plain.string());
        ASSERT_EQ(c.exit_code, 0) << c.err;
        const CliResult w = runCli("workspace --robot " + plain.string() + " --resolution 31 --figure ''");
        ASSERT_EQ(w.exit_code, 0) << w.err;
        const double area = summaryNumber(w.out, "area of ([0-9.e+-]+) mm\\^2") * 1e-6;
        EXPECT_NEAR(std::stod(row[3]), area, kSummaryDigits * area) << w.out;
        const double median = summaryNumber(w.out, "median ([0-9.e+-]+),");
        const double worst = summaryNumber(w.out, "worst ([0-9.e+-]+)\\.");
        EXPECT_NEAR(std::stod(row[4]), median, kSummaryDigits * median) << w.out;
        EXPECT_NEAR(std::stod(row[5]), worst, kSummaryDigits * worst) << w.out;
        const fs::path envelope = dir / ("envelope" + row[0] + ".csv");
        const CliResult e =
            runCli("envelope --robot " + plain.string() +
                   " --min-frequency 50 --max-frequency 50 --points 1 --figure '' -o " + envelope.string());
        ASSERT_EQ(e.exit_code, 0) << e.err;
        // the row of axis x: its amplitude (third column; the axis is a word, not a number)
        std::ifstream in(envelope);
        std::string line;
        int x_rows = 0;
        while (std::getline(in, line)) {
            if (line.rfind("x,", 0) != 0) continue;
            const std::size_t a = line.find(',', 2), b = line.find(',', a + 1);
            EXPECT_EQ(std::stod(row[6]), std::stod(line.substr(a + 1, b - a - 1)));
            ++x_rows;
        }
        EXPECT_EQ(x_rows, 1);
        ++checked;
    }
    EXPECT_EQ(checked, 2);
}

TEST(CliDesign, AStoppedSweepResumesWithTheSameTable) {
    const fs::path dir = freshScratchDirectory("nocdyn_cli_design_test");
    ASSERT_EQ(runCli(sweep(dir / "run")).exit_code, 0);
    const std::string whole = readWhole(dir / "run" / "designs.csv");
    // keep the journal's two header lines, four designs and half of the fifth
    const std::string journal = readWhole(dir / "run" / "journal.csv");
    std::size_t cut = 0;
    for (int line = 0; line < 6; ++line) cut = journal.find('\n', cut) + 1;
    std::ofstream(dir / "run" / "journal.csv", std::ios::trunc) << journal.substr(0, cut + 9);
    fs::remove(dir / "run" / "designs.csv");
    const CliResult again = runCli(sweep(dir / "run"));
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_NE(again.err.find("resuming: 4 of 10 designs already evaluated"), std::string::npos) << again.err;
    EXPECT_EQ(readWhole(dir / "run" / "designs.csv"), whole);
}

TEST(CliDesign, BadInputIsOneLineNamingTheParameterMetricOrExpression) {
    const fs::path dir = freshScratchDirectory("nocdyn_cli_design_test");
    const std::string base = "design --robot " + kFamily + " --no-figures --out-dir " + (dir / "x").string();
    CliResult r = runCli(base + " --vary nope=0:1 --metric workspace_area");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("varied parameter 'nope' is not declared (parameters: r_b, r_p, l1"), std::string::npos)
        << r.err;
    r = runCli(base + " --vary r_b=0.1:0.2 --metric envelope_q@50");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("unknown design metric 'envelope_q@50'"), std::string::npos) << r.err;
    r = runCli(base + " --vary r_b=0.3:0.2 --metric workspace_area");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("expected NAME=LOWER:UPPER"), std::string::npos) << r.err;
    r = runCli("workspace --robot " + kFamily + " --set r_b=abc");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--set"), std::string::npos) << r.err;
    r = runCli("workspace --robot " + kFamily + " --set nope=1 --figure ''");
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("parameter 'nope' is set but the file declares only: r_b"), std::string::npos) << r.err;
    const fs::path bad = dir / "bad.yaml";
    std::string text = readWhole(kFamily);
    text.replace(text.find("r_b - r_p"), 9, "r_b - r_q");
    std::ofstream(bad) << text;
    r = runCli("convert " + bad.string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find(bad.string() + ":12: parameters.d: expression 'r_b - r_q': unknown name 'r_q'"),
              std::string::npos)
        << r.err;
}

}  // namespace
}  // namespace nocdyn::test
