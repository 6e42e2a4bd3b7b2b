// The registry of CSV layouts: its expansion, one pose order, the documentation page generated
// from it, and the files the commands write, whose headers must be the registry's.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/tables/tables.hpp"

namespace nocdyn {
namespace {

namespace fs = std::filesystem;
using io::columnNames;
using io::TableId;
using test::runCli;

const std::string kRobot = std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rrr.yaml";

io::LayoutSizes everything() {
    io::LayoutSizes sizes;
    sizes.actuators = 4;
    sizes.limbs = 4;
    sizes.parameters = {"r_b", "l1"};
    sizes.metrics = {"workspace_area", "envelope_x@50"};
    sizes.optional = true;
    return sizes;
}

std::string header(const std::vector<std::string>& names) {
    std::string line;
    for (const std::string& name : names) line += (line.empty() ? "" : ",") + name;
    return line;
}

std::string firstLine(const fs::path& path) {
    const std::string text = test::readWhole(path);
    return text.substr(0, text.find('\n'));
}

std::size_t indexOf(const std::vector<std::string>& names, const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

TEST(Layouts, EveryTableHasUniqueNamedDocumentedColumns) {
    std::set<TableId> ids;
    std::set<std::string_view> headings;
    for (const io::Layout& layout : io::layouts()) {
        EXPECT_TRUE(ids.insert(layout.id).second) << layout.name;
        EXPECT_TRUE(headings.insert(layout.name).second) << layout.name;
        EXPECT_FALSE(layout.written_by.empty()) << layout.name;
        EXPECT_EQ(&io::layout(layout.id), &layout);
        EXPECT_EQ(io::tableId(io::tableKey(layout.id)), layout.id);
        for (const io::Column& c : layout.columns) EXPECT_FALSE(c.meaning.empty()) << layout.name << ": " << c.name;
        const std::vector<std::string> names = columnNames(layout.id, everything());
        EXPECT_FALSE(names.empty()) << layout.name;
        const std::set<std::string> unique(names.begin(), names.end());
        EXPECT_EQ(unique.size(), names.size()) << layout.name << ": " << header(names);
        for (const std::string& name : names) {
            EXPECT_EQ(name.find_first_of("{},\" "), std::string::npos) << layout.name << ": " << name;
        }
    }
    EXPECT_EQ(ids.size(), 13U);
    EXPECT_EQ(io::tableKey(TableId::closed_loop), "closed_loop");
    EXPECT_THROW((void)io::tableId("closed-loop"), Error);
}

TEST(Layouts, ThePoseIsAlwaysXYTheta) {
    int poses = 0;
    for (const io::Layout& layout : io::layouts()) {
        const std::vector<std::string> names = columnNames(layout.id, everything());
        for (const auto& [x, y, theta] : {std::array<std::string, 3>{"x", "y", "theta"},
                                          {"x_d", "y_d", "theta_d"},
                                          {"e_x", "e_y", "e_theta"},
                                          {"peak_force_x", "peak_force_y", "peak_force_theta"}}) {
            const std::size_t ix = indexOf(names, x), iy = indexOf(names, y), it = indexOf(names, theta);
            if (it == names.size()) continue;
            ++poses;
            EXPECT_EQ(iy, ix + 1) << layout.name << ": " << header(names);
            EXPECT_EQ(it, ix + 2) << layout.name << ": " << header(names);
        }
    }
    EXPECT_EQ(poses, 7);  // inverse dynamics, simulate, closed loop (3), loads, shake
}

TEST(Layouts, RepeatedColumnsExpandInFileOrder) {
    EXPECT_EQ(header(columnNames(TableId::inverse_dynamics, {.actuators = 2})),
              "t,x,y,theta,u1,u2,du1,du2,ddu1,ddu2,tau1,tau2,kinetic");
    EXPECT_EQ(header(columnNames(TableId::closed_loop, {.actuators = 2})),
              "t,x_d,y_d,theta_d,x,y,theta,e_x,e_y,e_theta,u1,u2,u1_d,u2_d,tau1,tau2");
    // the three parts of one joint's reaction side by side, joint by joint
    const std::vector<std::string> reactions = columnNames(TableId::reactions, {.limbs = 2});
    ASSERT_EQ(reactions.size(), 18U);
    EXPECT_EQ(header({reactions.begin(), reactions.begin() + 4}), "limb1_j1_fx,limb1_j1_fy,limb1_j1_m,limb1_j2_fx");
    EXPECT_EQ(reactions.back(), "limb2_j3_m");
    // the optional columns only when asked for
    EXPECT_EQ(header(columnNames(TableId::measurements, {.actuators = 1})), "t,u1,tau1");
    EXPECT_EQ(header(columnNames(TableId::measurements, {.actuators = 1, .optional = true})), "t,u1,tau1,du1,ddu1");
    EXPECT_EQ(header(columnNames(TableId::design, everything())),
              "design,r_b,l1,workspace_area,envelope_x@50,feasible,reason");
    EXPECT_EQ(io::columnList(TableId::measurements), "t,u1..un,tau1..taun[,du1..dun,ddu1..ddun]");
    EXPECT_EQ(io::columnList(TableId::loads).substr(io::columnList(TableId::loads).rfind(',')),
              ",peak_force_frequency]");
}

TEST(Layouts, ClosedLoopRowsHoldThePoseUnderItsNames) {
    // Pose vectors are (theta, x, y); the file's columns are named, in the order x, y, theta.
    PoseLoopResult run;
    run.actuators = 1;
    run.t = {0.5};
    run.p_d = {Pose(0.3, 0.1, 0.2)};
    run.p = {Pose(0.03, 0.01, 0.02)};
    ActuatorVector u(1), u_d(1), tau(1);
    u << 7.0;
    u_d << 8.0;
    tau << 9.0;
    run.u = {u};
    run.u_d = {u_d};
    run.tau = {tau};
    const io::Table table = tables::toTable(run);
    ASSERT_EQ(table.columns, columnNames(TableId::closed_loop, {.actuators = 1}));
    ASSERT_EQ(table.rows.size(), 1U);
    const auto at = [&](const char* name) { return table.rows[0][table.column(name)]; };
    EXPECT_EQ(at("t"), 0.5);
    EXPECT_EQ(at("theta_d"), 0.3);
    EXPECT_EQ(at("x_d"), 0.1);
    EXPECT_EQ(at("y_d"), 0.2);
    EXPECT_EQ(at("theta"), 0.03);
    EXPECT_EQ(at("x"), 0.01);
    EXPECT_EQ(at("y"), 0.02);
    EXPECT_DOUBLE_EQ(at("e_theta"), 0.27);
    EXPECT_DOUBLE_EQ(at("e_x"), 0.09);
    EXPECT_DOUBLE_EQ(at("e_y"), 0.18);
    EXPECT_EQ(at("u1"), 7.0);
    EXPECT_EQ(at("u1_d"), 8.0);
    EXPECT_EQ(at("tau1"), 9.0);
}

TEST(Layouts, EnvelopeRowsHoldEveryFieldUnderItsName) {
    EnvelopePoint p;
    p.axis = EnvelopeAxis::y;
    p.frequency = 5.0;
    p.amplitude = 1e-3;
    p.limit = EnvelopeLimit::effort;
    p.limb = 1;
    p.joint = 0;
    p.actuator = 1;
    p.kinematic_amplitude = 2e-3;
    p.peak_effort_ratio = 1.0;
    p.peak_u = 3e-3;
    p.peak_tau = 40.0;
    const io::Table table = tables::toTable(std::vector<EnvelopePoint>{p});
    ASSERT_EQ(table.columns, columnNames(TableId::envelope));
    const std::vector<double>& row = table.rows.at(0);
    ASSERT_EQ(row.size(), table.columns.size());
    EXPECT_EQ(table.categories[table.column("axis")].at(static_cast<std::size_t>(row[table.column("axis")])), "y");
    EXPECT_EQ(table.categories[table.column("limit")].at(static_cast<std::size_t>(row[table.column("limit")])),
              "effort");
    EXPECT_EQ(row[table.column("frequency")], 5.0);
    EXPECT_EQ(row[table.column("amplitude")], 1e-3);
    EXPECT_EQ(row[table.column("limb")], 2.0);
    EXPECT_EQ(row[table.column("joint")], 1.0);
    EXPECT_EQ(row[table.column("actuator")], 2.0);
    EXPECT_EQ(row[table.column("kinematic_amplitude")], 2e-3);
    EXPECT_EQ(row[table.column("peak_effort_ratio")], 1.0);
    EXPECT_EQ(row[table.column("peak_u")], 3e-3);
    EXPECT_EQ(row[table.column("peak_tau")], 40.0);
}

TEST(Layouts, TheDocumentationPageIsTheRegistrys) {
    const fs::path page = fs::path(NOCDYN_SOURCE_DIR) / "docs" / "output-formats.md";
    ASSERT_TRUE(fs::is_regular_file(page)) << page;
    EXPECT_EQ(test::readWhole(page), io::outputFormatsMarkdown())
        << "docs/output-formats.md differs from the registry (src/io/layouts.cpp); regenerate it with\n"
           "  build/nocdyn --output-formats > docs/output-formats.md";
    const test::CliResult r = runCli("--output-formats");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, io::outputFormatsMarkdown());
    // every table and every column is on the page
    for (const io::Layout& layout : io::layouts()) {
        EXPECT_NE(r.out.find("## " + std::string(layout.name) + "\n"), std::string::npos) << layout.name;
        for (const io::Column& c : layout.columns)
            EXPECT_NE(r.out.find("| `" + std::string(c.name) + "`"), std::string::npos) << c.name;
    }
}

TEST(Layouts, TheCommandsWriteTheRegistrysHeaders) {
    const fs::path dir = test::freshScratchDirectory("nocdyn_layouts_test");
    const std::string motion = " --robot " + kRobot + " --trajectory paper1 --duration 0.01 --rate 2000";
    const int n = 3, limbs = 3;

    ASSERT_EQ(runCli("inverse-dynamics" + motion + " -o " + (dir / "id.csv").string()).exit_code, 0);
    EXPECT_EQ(firstLine(dir / "id.csv"), header(columnNames(TableId::inverse_dynamics, {.actuators = n})));

    ASSERT_EQ(runCli("inverse-dynamics" + motion + " --reactions -o " + (dir / "idr.csv").string()).exit_code, 0);
    std::vector<std::string> with_reactions = columnNames(TableId::inverse_dynamics, {.actuators = n});
    for (std::string& name : columnNames(TableId::reactions, {.limbs = limbs})) with_reactions.push_back(name);
    EXPECT_EQ(firstLine(dir / "idr.csv"), header(with_reactions));

    const test::CliResult s = runCli("simulate --robot " + kRobot + " --forces " + (dir / "id.csv").string() + " -o " +
                                     (dir / "sim.csv").string());
    ASSERT_EQ(s.exit_code, 0) << s.err;
    EXPECT_EQ(firstLine(dir / "sim.csv"), header(columnNames(TableId::simulate, {.actuators = n})));

    const test::CliResult c = runCli("control --plant nocdyn" + motion + " -o " + (dir / "ctl.csv").string() +
                                     " --log " + (dir / "log.csv").string());
    ASSERT_EQ(c.exit_code, 0) << c.err;
    EXPECT_EQ(firstLine(dir / "ctl.csv"), header(columnNames(TableId::closed_loop, {.actuators = n})));
    // control logs the commands held over each tick: its force columns say so (tau1_held ...)
    std::vector<std::string> held = columnNames(TableId::measurements, {.actuators = n});
    for (std::string& name : held) {
        if (name.rfind("tau", 0) == 0) name += "_held";
    }
    EXPECT_EQ(firstLine(dir / "log.csv"), header(held));

    const test::CliResult e =
        runCli("envelope --points 2 --figure '' --quiet --robot " + kRobot + " -o " + (dir / "envelope.csv").string());
    ASSERT_EQ(e.exit_code, 0) << e.err;
    EXPECT_EQ(firstLine(dir / "envelope.csv"), header(columnNames(TableId::envelope)));

    const test::CliResult w = runCli("workspace --resolution 11 --figure '' --quiet --robot " + kRobot + " -o " +
                                     (dir / "grid.csv").string());
    ASSERT_EQ(w.exit_code, 0) << w.err;
    EXPECT_EQ(firstLine(dir / "grid.csv"), header(columnNames(TableId::workspace)));

    const test::CliResult l = runCli("loads" + motion + " -o " + (dir / "loads.csv").string());
    ASSERT_EQ(l.exit_code, 0) << l.err;
    EXPECT_EQ(firstLine(dir / "loads.csv"), header(columnNames(TableId::loads)));
}

}  // namespace
}  // namespace nocdyn
