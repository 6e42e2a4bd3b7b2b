// The `nocdyn` binary end to end: what it writes, and how it refuses bad input
// (one-line error on stderr, non-zero exit, no partial CSV).
#include <gtest/gtest.h>

#include "nocdyn/detail/sanitizer.hpp"
#include "nocdyn/io/short_form.hpp"
#include "nocdyn/dynamics.hpp"
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

struct CliRun {
    int exit_code = -1;
    std::string out, err;
};

std::string slurp(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// A file name private to the running test: ctest runs the tests in parallel processes.
std::string testUnique(const std::string& name) {
    return std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" + name;
}

CliRun run(const std::string& arguments) {
    const fs::path err_file = fs::path(testing::TempDir()) / testUnique("stderr.txt");
    const std::string command = std::string(NOCDYN_CLI) + " " + arguments + " 2>" + err_file.string();
    CliRun result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.out.append(buffer, n);
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.err = slurp(err_file);
    return result;
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(testing::TempDir()) / "nocdyn_cli_test";
    fs::create_directories(dir);
    return dir / testUnique(name);
}

io::Table parseCsv(const std::string& text) {
    const fs::path path = scratch("parsed.csv");
    std::ofstream(path) << text;
    return io::readCsvFile(path.string());
}

TEST(Cli, InverseDynamicsWritesTheDocumentedColumnsAndTheLibrarysNumbers) {
    const CliRun r = run("inverse-dynamics --trajectory paper1 --duration 0.01 --rate 1000");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const io::Table table = parseCsv(r.out);
    const std::vector<std::string> expected = {"t",   "x",   "y",    "theta", "u1",   "u2",   "u3",   "du1",
                                               "du2", "du3", "ddu1", "ddu2",  "ddu3", "tau1", "tau2", "tau3"};
    for (const auto& column : expected) EXPECT_TRUE(table.has(column)) << column;
    ASSERT_EQ(table.rows.size(), 10u);
    const Model model{io::expand(io::RobotParameters{})};
    Data data(model);
    Pose p, dp, ddp;
    const auto& last = table.rows.back();
    EXPECT_EQ(last[table.column("t")], 9.0 / 1000.0);
    paperTrajectory1().evaluate(last[table.column("t")], p, dp, ddp);
    ASSERT_TRUE(inverseDynamics(model, data, p, dp, ddp).ok());
    // shortest round-trip digits: the CSV holds the library's doubles exactly.
    const char* tau_columns[] = {"tau1", "tau2", "tau3"};
    const char* u_columns[] = {"u1", "u2", "u3"};
    for (int j = 0; j < 3; ++j) {
        EXPECT_EQ(last[table.column(tau_columns[j])], data.tau(j));
        EXPECT_EQ(last[table.column(u_columns[j])], data.u(j));
    }
}

TEST(Cli, DefaultSamplingIsTheFilesDurationAtTenKilohertz) {
    const fs::path trajectory = scratch("short.yaml");
    std::ofstream(trajectory) << "duration: 0.05\nx: {harmonics: [{amplitude: 0.001, frequency: 20}]}\n";
    const fs::path output = scratch("short.csv");
    const CliRun r = run("inverse-dynamics --trajectory " + trajectory.string() + " --output " + output.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.out.empty());
    const io::Table table = io::readCsvFile(output.string());
    EXPECT_EQ(table.rows.size(), 500u);
    const CliRun paper = run("inverse-dynamics --trajectory paper2");
    ASSERT_EQ(paper.exit_code, 0) << paper.err;
    EXPECT_EQ(parseCsv(paper.out).rows.size(), 2000u);  // 0.2 s at 10 kHz
}

TEST(Cli, RobotFileChangesTheForces) {
    const fs::path robot = scratch("heavy.yaml");
    std::ifstream in(std::string(NOCDYN_SOURCE_DIR) + "/robots/paper-3prr.yaml");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    text.replace(text.find("mass: 1.75257"), 13, "mass: 3.50514");
    std::ofstream(robot) << text;
    const CliRun light = run("inverse-dynamics --trajectory paper1 --duration 0.003 --rate 1000");
    const CliRun heavy =
        run("inverse-dynamics --trajectory paper1 --duration 0.003 --rate 1000 --robot " + robot.string());
    ASSERT_EQ(light.exit_code, 0) << light.err;
    ASSERT_EQ(heavy.exit_code, 0) << heavy.err;
    const io::Table a = parseCsv(light.out), b = parseCsv(heavy.out);
    EXPECT_GT(std::abs(b.rows[1][b.column("tau1")]), 1.2 * std::abs(a.rows[1][a.column("tau1")]));
}

TEST(Cli, BadArgumentsExitNonZeroWithAMessage) {
    for (const char* args : {"", "inverse-dynamics", "inverse-dynamics --trajectory paper1 --rate -5",
                             "inverse-dynamics --trajectory paper1 --duration abc", "fly-to-the-moon", "pose 0 0",
                             "pose 0 0 0 --robot /nonexistent.yaml"}) {
        const CliRun r = run(args);
        EXPECT_NE(r.exit_code, 0) << args;
        EXPECT_FALSE(r.err.empty()) << args;
    }
}

TEST(Cli, InvalidFilesAreNamedInOneLine) {
    const fs::path robot = scratch("bad-robot.yaml");
    std::ofstream(robot) << "geometry: {base_side: 0.4, platform_side: 0.11, link_length: 0.15915, link_com: 0.08}\n"
                            "slider: {mass: 1}\nlink: {mass: -1, inertia: 1}\nplatform: {mass: 1, inertia: 1}\n"
                            "actuator: {stroke: 0.02, peak_force: 100}\n";
    const CliRun r = run("pose 0 0 0 --robot " + robot.string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("link.mass"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;

    const CliRun missing = run("inverse-dynamics --trajectory /nonexistent/traj.yaml");
    EXPECT_NE(missing.exit_code, 0);
    EXPECT_NE(missing.err.find("/nonexistent/traj.yaml"), std::string::npos) << missing.err;
}

TEST(Cli, SampleOutsideTheWorkspaceNamesTimeAndLimbAndLeavesNoCsv) {
    const fs::path trajectory = scratch("far.yaml");
    std::ofstream(trajectory) << "duration: 0.1\ny: {harmonics: [{amplitude: 0.2, frequency: 5}]}\n";
    const fs::path output = scratch("far.csv");
    fs::remove(output);
    // --allow-limits tolerates stroke and force, never a pose outside the workspace.
    const CliRun r =
        run("inverse-dynamics --allow-limits --trajectory " + trajectory.string() + " --output " + output.string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("t = "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("pose out of reach: limb"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(output));
    EXPECT_FALSE(fs::exists(output.string() + ".partial"));
}

TEST(Cli, StrokeBeyondTheActuatorIsAnErrorUnlessAllowed) {
    const fs::path trajectory = scratch("wide.yaml");
    std::ofstream(trajectory) << "duration: 0.1\nx: {harmonics: [{amplitude: 0.03, frequency: 2}]}\n";
    const fs::path output = scratch("wide.csv");
    fs::remove(output);
    const CliRun strict = run("inverse-dynamics --trajectory " + trajectory.string() + " --output " + output.string());
    EXPECT_EQ(strict.exit_code, 1);
    EXPECT_NE(strict.err.find("joint range exceeded: limb"), std::string::npos) << strict.err;
    EXPECT_FALSE(fs::exists(output));
    const CliRun allowed =
        run("inverse-dynamics --allow-limits --trajectory " + trajectory.string() + " --output " + output.string());
    EXPECT_EQ(allowed.exit_code, 0) << allowed.err;
    EXPECT_NE(allowed.err.find("warning"), std::string::npos);
    EXPECT_TRUE(fs::exists(output));
}

TEST(Cli, PoseJsonCarriesJointsActuationMapAndInertia) {
    const CliRun r = run("pose 0.001 -0.003 0.02 --json");  // x, y, theta
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    // the library's general model of the default robot (the paper's, short form) gives the same
    // joint variables, inertia and actuation map
    const Model model(io::exampleRobot("paper-3prr"));
    Data data(model);
    ASSERT_TRUE(inverseDynamics(model, data, Pose(0.02, 0.001, -0.003), Twist::Zero(), Twist::Zero()).ok());
    ASSERT_EQ(json["limbs"].size(), 3u);
    ASSERT_EQ(json["actuators"].size(), 3u);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(json["actuators"][j]["u"].get<double>(), data.u(j), 1e-16);
    EXPECT_NEAR(json["I"][1][2].get<double>(), data.I(1, 2), 1e-12);
    // du = D^-1 H dp/dt (eqs. 5-7): row 1 of the map is [h_11, f_1x, f_1y] / d_1, with f_1 the
    // unit vector from A_1 to M_1, h_11 = (M_1 - C) x f_1 and d_1 = e_1 . f_1 = cos phi_A1
    const LimbData& limb = data.limb[0];
    const auto axis = [](const Twist& s) { return Vector2(-s(2), s(1)); };  // R screw [1; r_y; -r_x]
    const Vector2 e = limb.s[0].tail<2>(), A = axis(limb.s[1]), M = axis(limb.s[2]);
    const Vector2 f = (M - A).normalized(), C(0.001, -0.003);
    const double d = e.dot(f);
    // the columns in the pose's order x, y, theta
    EXPECT_NEAR(json["A"][0][0].get<double>(), f.x() / d, 1e-12);
    EXPECT_NEAR(json["A"][0][1].get<double>(), f.y() / d, 1e-12);
    EXPECT_NEAR(json["A"][0][2].get<double>(), cross(M - C, f) / d, 1e-12);
    EXPECT_EQ(json["pose"]["x"].get<double>(), 0.001);
    EXPECT_EQ(json["pose"]["theta"].get<double>(), 0.02);
    EXPECT_EQ(json["limbs"][0]["type"].get<std::string>(), "PRR");
    EXPECT_TRUE(json["within_limits"].get<bool>());
    const CliRun text = run("pose 0 0 0");
    ASSERT_EQ(text.exit_code, 0);
    EXPECT_NE(text.out.find("joint-space inertia"), std::string::npos);
    // the joints at home are zero up to rounding: never printed as -0.000000
    EXPECT_EQ(text.out.find("-0.000000"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("+0.000000 deg"), std::string::npos) << text.out;
    const CliRun outside = run("pose 0 -0.3 0");
    EXPECT_EQ(outside.exit_code, 1);
    EXPECT_NE(outside.err.find("out of reach: limb 1"), std::string::npos) << outside.err;
    // any robot: the redundant 4-RRR
    const CliRun rrr =
        run("pose 0.001 -0.003 0.02 --json --robot " + std::string(NOCDYN_SOURCE_DIR) + "/robots/4-rrr.yaml");
    ASSERT_EQ(rrr.exit_code, 0) << rrr.err;
    const auto four = nlohmann::json::parse(rrr.out);
    EXPECT_EQ(four["actuators"].size(), 4u);
    EXPECT_EQ(four["coordinates"].get<std::string>(), "platform");
}

TEST(Cli, GeneralRobotFilesRunInverseDynamicsAndTheEnvelope) {
    const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rpr.yaml";
    const CliRun r = run("inverse-dynamics --trajectory paper1 --duration 0.01 --robot " + robot);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
              "t,x,y,theta,u1,u2,u3,du1,du2,du3,ddu1,ddu2,ddu3,tau1,tau2,tau3,kinetic");
    const CliRun envelope = run("envelope --points 2 --figure '' --robot " + robot);
    ASSERT_EQ(envelope.exit_code, 0) << envelope.err;
    EXPECT_EQ(envelope.out.substr(0, envelope.out.find('\n')),
              "axis   f [Hz]    amplitude        limit      peak |tau|/effort  where");
    EXPECT_NE(envelope.out.find("actuator "), std::string::npos) << envelope.out;
}

TEST(Cli, CategoryColumnsHoldWordsAndQuietPrintsNothing) {
    // envelope.csv names the axis and the binding limit, workspace's grid its cells, in words
    const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rrr.yaml";
    const fs::path envelope = scratch("words-envelope.csv"), grid = scratch("words-grid.csv");
    const CliRun e = run("envelope --points 2 --figure '' --quiet --robot " + robot + " -o " + envelope.string());
    ASSERT_EQ(e.exit_code, 0) << e.err;
    EXPECT_EQ(e.out, "");
    const std::string text = slurp(envelope);
    EXPECT_EQ(
        text.substr(0, text.find('\n')),
        "axis,frequency,amplitude,limit,limb,joint,actuator,kinematic_amplitude,peak_effort_ratio,peak_u,peak_tau");
    const std::string first =
        text.substr(text.find('\n') + 1, text.find('\n', text.find('\n') + 1) - text.find('\n') - 1);
    EXPECT_EQ(first.substr(0, first.find(',')), "x") << first;  // the pose's order: x, y, theta
    for (const char* word : {"\ny,", "\ntheta,"}) EXPECT_NE(text.find(word), std::string::npos) << text;
    EXPECT_TRUE(text.find(",range,") != std::string::npos || text.find(",effort,") != std::string::npos ||
                text.find(",velocity,") != std::string::npos)
        << text;
    const CliRun w = run("workspace --resolution 21 --figure '' --quiet --robot " + robot + " -o " + grid.string());
    ASSERT_EQ(w.exit_code, 0) << w.err;
    EXPECT_EQ(w.out, "");
    const std::string cells = slurp(grid);
    EXPECT_NE(cells.find(",feasible\n"), std::string::npos);
    std::istringstream lines(cells);
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line, "x,y,cell");
    while (std::getline(lines, line)) {
        const std::string cell = line.substr(line.rfind(',') + 1);
        EXPECT_TRUE(cell == "feasible" || cell == "unreachable" || cell == "range" || cell == "singular") << line;
    }
    // --json: the summary for a script
    const CliRun json = run("workspace --resolution 21 --figure '' --json --robot " + robot);
    ASSERT_EQ(json.exit_code, 0) << json.err;
    const auto summary = nlohmann::json::parse(json.out);
    EXPECT_EQ(summary["robot"].get<std::string>(), "3-rrr");
    EXPECT_EQ(summary["resolution"].get<int>(), 21);
    EXPECT_GT(summary["area"].get<double>(), 0.0);
    const CliRun loud = run("workspace --resolution 21 --figure '' --robot " + robot);
    EXPECT_NE(loud.out.find("feasible region"), std::string::npos) << loud.out;
    // not a terminal: no progress line on stderr
    EXPECT_EQ(loud.err, "");
}

TEST(Cli, SimulateReplaysTheInverseDynamicsOfAnyRobot) {
    // inverse-dynamics -> simulate (cubic forces): each actuator back within 1e-6 of its peak travel
    for (const std::string name : {"paper-3prr", "3-rrr", "3-rpr", "4-rrr"}) {
        const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/" + name + ".yaml";
        const fs::path forces = scratch(name + "-forces.csv"), motion = scratch(name + "-motion.csv");
        ASSERT_EQ(run("inverse-dynamics --trajectory paper1 --duration 0.1 --robot " + robot + " -o " + forces.string())
                      .exit_code,
                  0);
        const CliRun r = run("simulate --forces " + forces.string() + " --robot " + robot + " -o " + motion.string());
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const io::Table in = io::readCsvFile(forces.string());
        const io::Table out = io::readCsvFile(motion.string());
        const int n = name == "4-rrr" ? 4 : 3;
        std::string header = "t,x,y,theta";
        for (const char* prefix : {"u", "du", "tau"}) {
            for (int a = 1; a <= n; ++a) header.append(",").append(prefix).append(std::to_string(a));
        }
        EXPECT_EQ(slurp(motion).substr(0, slurp(motion).find('\n')), header + ",kinetic");
        ASSERT_EQ(out.rows.size(), in.rows.size());
        for (int a = 1; a <= n; ++a) {
            const std::string column = std::string("u").append(std::to_string(a));
            const std::size_t ci = in.column(column), co = out.column(column);
            double peak = 0.0, error = 0.0;
            for (std::size_t k = 0; k < in.rows.size(); ++k) {
                EXPECT_DOUBLE_EQ(out.rows[k][0], in.rows[k][0]);
                peak = std::max(peak, std::abs(in.rows[k][ci] - in.rows[0][ci]));
                error = std::max(error, std::abs(out.rows[k][co] - in.rows[k][ci]));
            }
            EXPECT_LT(error, 1e-6 * peak) << name << " u" << a;
        }
    }
}

TEST(Cli, SimulateStopsAtASingularityNamingTimeAndLimbAndWritesOnlyWhenAskedTo) {
    const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/3-rrr.yaml";
    const fs::path forces = scratch("push.csv"), motion = scratch("motion.csv");
    std::ofstream(forces) << "t,tau1,tau2,tau3\n0,1,0,0\n1,1,0,0\n";
    fs::remove(motion);
    const CliRun r = run("simulate --forces " + forces.string() + " --robot " + robot + " -o " + motion.string());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("t = 0.17"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("limb 1"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(motion));
    const CliRun partial =
        run("simulate --partial --forces " + forces.string() + " --robot " + robot + " -o " + motion.string());
    EXPECT_EQ(partial.exit_code, 1);
    ASSERT_TRUE(fs::exists(motion));
    EXPECT_GT(io::readCsvFile(motion.string()).rows.size(), 1000u);
}

TEST(Cli, SimulateNamesWhatItCannotUse) {
    const std::string robot = std::string(NOCDYN_SOURCE_DIR) + "/robots/4-rrr.yaml";
    const fs::path forces = scratch("uneven.csv");
    std::ofstream(forces) << "t,tau1,tau2,tau3,tau4\n0,0,0,0,0\n0.1,0,0,0,0\n0.2,0,0,0,0\n0.35,0,0,0,0\n"
                             "0.4,0,0,0,0\n0.5,0,0,0,0\n";
    const CliRun cubic = run("simulate --forces " + forces.string() + " --robot " + robot);
    EXPECT_EQ(cubic.exit_code, 1);
    EXPECT_NE(cubic.err.find("uneven.csv: sample 4"), std::string::npos) << cubic.err;
    EXPECT_EQ(
        run("simulate --interpolation hold --rate 100 --forces " + forces.string() + " --robot " + robot).exit_code, 0);
    const fs::path three = scratch("three.csv");
    std::ofstream(three) << "t,tau1,tau2,tau3\n0,0,0,0\n1,0,0,0\n";
    const CliRun missing = run("simulate --forces " + three.string() + " --robot " + robot);
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_NE(missing.err.find("'tau4'"), std::string::npos) << missing.err;
    const fs::path u_only = scratch("u_only.csv");
    std::ofstream(u_only) << "t,tau1,tau2,tau3,tau4,u1,u2,u3,u4\n0,0,0,0,0,0,0,0,0\n1,0,0,0,0,0,0,0,0\n";
    // no pose: found from u by direct kinematics (u = 0 is the 4-RRR's home)
    const CliRun no_pose = run("simulate --forces " + u_only.string() + " --robot " + robot);
    EXPECT_EQ(no_pose.exit_code, 0) << no_pose.err;
    EXPECT_NE(no_pose.err.find("assembly mode"), std::string::npos) << no_pose.err;
    EXPECT_EQ(run("simulate --interpolation spline --forces " + three.string()).exit_code, 2);
}

TEST(Cli, HelpExplainsEveryCommand) {
    const CliRun r = run("--help");
    EXPECT_EQ(r.exit_code, 0);
    for (const char* command : {"pose", "inverse-dynamics", "reproduce"}) {
        EXPECT_NE(r.out.find(command), std::string::npos) << command;
    }
}

#if NOCDYN_ASAN()
// Under the sanitizers (10-20x slower, and most of reproduce is Simbody's plant at ~0.3-0.6 ms
// per tick in release) the closed loops run 0.02 s instead of 0.2 s and the identification
// experiment 0.05 s of data instead of 5 s: the same code, fewer ticks.
constexpr const char* kClosedLoop = " --closed-loop-duration 0.02 --identification-duration 0.05";
#else
// the identification experiment over 0.5 s of data instead of 5 s
constexpr const char* kClosedLoop = " --identification-duration 0.5";
#endif

TEST(Cli, ReproduceWritesCsvFiguresAndSummary) {
    const fs::path out = scratch("reproduce");
    fs::remove_all(out);
    const CliRun r = run("reproduce --out-dir " + out.string() + kClosedLoop);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* file :
         {"paper1.csv", "paper2.csv", "paper1_displacements.png", "paper1_displacements.svg", "paper1_forces.png",
          "paper2_forces.svg", "workspace.png", "workspace.svg", "summary.md"}) {
        ASSERT_TRUE(fs::exists(out / file)) << file;
        EXPECT_GT(fs::file_size(out / file), 1000u) << file;
    }
    const io::Table paper1 = io::readCsvFile((out / "paper1.csv").string());
    EXPECT_EQ(paper1.rows.size(), 2000u);
    // Figure 5b peaks: every force stays well under the 262 N peak force.
    double peak = 0.0;
    for (const auto& row : paper1.rows) {
        for (const char* c : {"tau1", "tau2", "tau3"}) peak = std::max(peak, std::abs(row[paper1.column(c)]));
    }
    EXPECT_GT(peak, 20.0);
    EXPECT_LT(peak, 262.0);
    // reproduce writes its tables in the layouts of the commands that write them alone
    const auto header = [](const std::vector<std::string>& names) {
        std::string line;
        for (const std::string& name : names) line += (line.empty() ? "" : ",") + name;
        return line;
    };
    const auto firstLine = [](const std::string& text) { return text.substr(0, text.find('\n')); };
    EXPECT_EQ(paper1.columns, io::columnNames(io::TableId::inverse_dynamics, {.actuators = 3}));
    EXPECT_EQ(firstLine(slurp(out / "envelope.csv")), header(io::columnNames(io::TableId::envelope)));
    EXPECT_EQ(io::readCsvFile((out / "control_paper1.csv").string()).columns,
              io::columnNames(io::TableId::closed_loop, {.actuators = 3}));
    const std::string summary = slurp(out / "summary.md");
    EXPECT_NE(summary.find("| paper1 | 1 |"), std::string::npos) << summary;
    EXPECT_NE(summary.find("262"), std::string::npos);
    EXPECT_NE(summary.find("## Workspace"), std::string::npos);
    EXPECT_NE(summary.find("has an area of"), std::string::npos);
    EXPECT_NE(slurp(out / "paper1_forces.svg").find("<svg"), std::string::npos);
    // the identification experiment: its files, and a table of finite estimates per case
    for (const char* file : {"designed_log.csv", "designed_forces.csv", "designed_friction_log.csv", "paper1_log.csv",
                             "paper2_log.csv", "forces.png", "forces.svg"}) {
        EXPECT_TRUE(fs::exists(out / "identification" / file)) << file;
    }
    const io::Table forces = io::readCsvFile((out / "identification" / "designed_forces.csv").string());
    ASSERT_FALSE(forces.rows.empty());
    EXPECT_EQ(forces.columns, io::columnNames(io::TableId::held_out_forces, {.actuators = 3}));
    EXPECT_EQ(io::readCsvFile((out / "identification" / "paper1_log.csv").string()).columns,
              io::columnNames(io::TableId::measurements, {.actuators = 3}));  // no rates: identify derives them
    const std::size_t section = summary.find("## Identification experiment");
    ASSERT_NE(section, std::string::npos) << summary;
    int rows = 0;
    const std::string mass_row = "| mass [kg] | ";
    for (std::size_t at = summary.find(mass_row, section); at != std::string::npos;
         at = summary.find(mass_row, at + 1)) {
        // | mass [kg] | truth | value ± s.d. | error | ...
        const std::size_t from = at + mass_row.size();
        std::istringstream cells(summary.substr(from, summary.find('\n', at) - from));
        double truth = 0.0, value = 0.0;
        std::string bar, pm;
        cells >> truth >> bar >> value >> pm;
        EXPECT_EQ(truth, 0.5);
        EXPECT_TRUE(std::isfinite(value) && value > 0.0) << summary.substr(at, 80);
        ++rows;
    }
    EXPECT_GE(rows, 1) << summary.substr(section);
    EXPECT_NE(summary.find("| designed excitation | "), std::string::npos);
}

TEST(Cli, ForwardKinematicsTakesAnyRobotFile) {
    const std::string robots = std::string(NOCDYN_SOURCE_DIR) + "/robots/";
    // the 3-RRR at u(home) = 0: home is a working mode, every pose with its limbs' branches
    CliRun r = run("forward-kinematics 0 0 0 --all-branches --json --robot " + robots + "3-rrr.yaml");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    ASSERT_GE(json["solutions"].size(), 1U);
    EXPECT_EQ(json["solutions_all_branches"].get<int>(), static_cast<int>(json["solutions"].size()));
    bool home = false;
    for (const auto& s : json["solutions"]) {
        EXPECT_EQ(s["branch"].size(), 3U);
        EXPECT_LE(s["u_error"].get<double>(), 1e-12);
        home =
            home || (std::abs(s["pose"]["theta"].get<double>()) < 1e-12 &&
                     std::abs(s["pose"]["x"].get<double>()) < 1e-12 && std::abs(s["pose"]["y"].get<double>()) < 1e-12);
    }
    EXPECT_TRUE(home) << r.out;
    // four values for the redundant 4-RRR
    r = run("forward-kinematics 0 0 0 0 --robot " + robots + "4-rrr.yaml");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("1. x = "), std::string::npos) << r.out;
    // the wrong number of values: one line, exit 2
    r = run("forward-kinematics 0 0 --robot " + robots + "3-rpr.yaml");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("has 3 actuators: give 3 values"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    // legs a metre longer: no assembly is not an error
    r = run("forward-kinematics 1 1 1 --robot " + robots + "3-rpr.yaml");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("real solutions: 0"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("cannot assemble"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace nocdyn::test
