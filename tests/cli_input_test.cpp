// The `nocdyn` binary against hostile or careless input: every numeric argument finite and in
// its range (exit 2, the accepted range named), special and oversized files refused (exit 1),
// and every loop bounded: each run here is killed after a time limit, so a hang fails the test.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

/// Seconds any one run may take before it counts as a hang.
constexpr int kTimeLimit = 60;

struct CliRun {
    int exit_code = -1;
    std::string out, err;
};

std::string testUnique(const std::string& name) {
    return std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" + name;
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(testing::TempDir()) / "nocdyn_cli_input_test";
    fs::create_directories(dir);
    return dir / testUnique(name);
}

/// Runs nocdyn with `arguments` under `timeout` (exit 124 when it had to be killed).
CliRun run(const std::string& arguments) {
    const fs::path err_file = scratch("stderr.txt");
    const std::string command = "timeout " + std::to_string(kTimeLimit) + " " + std::string(NOCDYN_CLI) + " " +
                                arguments + " 2>" + err_file.string();
    CliRun result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.out.append(buffer, n);
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(err_file);
    std::ostringstream text;
    text << in.rdbuf();
    result.err = text.str();
    return result;
}

/// Expects exit status `code` and one line on stderr holding every fragment.
void expectRefused(const std::string& arguments, int code, std::initializer_list<const char*> fragments) {
    const CliRun r = run(arguments);
    EXPECT_EQ(r.exit_code, code) << arguments << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << arguments;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << arguments << ": one line\n" << r.err;
    for (const char* fragment : fragments) {
        EXPECT_NE(r.err.find(fragment), std::string::npos) << arguments << "\n" << r.err << "missing: " << fragment;
    }
}

TEST(CliInput, NonFiniteNumbersAreMalformedArguments) {
    expectRefused("forward-kinematics nan 0 0", 2, {"finite", "[-1000, 1000] m", "nan"});
    expectRefused("pose 0 inf 0", 2, {"finite"});
    expectRefused("pose 0x1p-3 0 0", 2, {"finite"});
    expectRefused("control --trajectory paper1 --noise-u nan", 2, {"--noise-u", "[0, 1] m"});
    expectRefused("simulate --forces /dev/null --atol nan", 2, {"--atol", "[1e-15, 0.01]"});
    expectRefused("inverse-dynamics --trajectory paper1 --rate nan", 2, {"--rate", "[1, 1e+08] Hz"});
    expectRefused("inverse-dynamics --trajectory paper1 --duration -1", 2, {"--duration"});
    expectRefused("control --trajectory paper1 --payload-mass -1", 2, {"--payload-mass", "[0, 1e+06] kg"});
}

TEST(CliInput, OutOfRangeOptionsNameTheAcceptedRange) {
    expectRefused("simulate --forces /dev/null --atol 1e-22", 2, {"--atol", "[1e-15, 0.01]"});
    expectRefused("envelope --max-frequency 1e300", 2, {"--max-frequency", "[0.001, 10000] Hz"});
    expectRefused("envelope --points 100000000", 2, {"--points", "1000"});
    expectRefused("envelope --points 0", 2, {"--points"});
    expectRefused("envelope --min-frequency 50 --max-frequency 10", 2, {"--max-frequency", "--min-frequency"});
}

TEST(CliInput, SpecialFilesAreRefusedAtOnce) {
    expectRefused("simulate --forces /dev/zero", 1, {"/dev/zero", "not a regular file"});
    expectRefused("inverse-dynamics --trajectory /dev/urandom", 1, {"/dev/urandom", "not a regular file"});
    expectRefused("pose 0 0 0 --robot /dev/zero", 1, {"/dev/zero", "not a regular file"});
}

TEST(CliInput, RangeErrorsInTheRobotFileNameTheLine) {
    const fs::path robot = scratch("heavy.yaml");
    std::ofstream(robot) << "geometry: {base_side: 0.4, platform_side: 0.11, link_length: 0.15915, link_com: 0.08}\n"
                            "slider: {mass: 1}\nlink: {mass: 1, inertia: 1e-3}\n"
                            "platform: {mass: 1, inertia: 1e308}\n"
                            "actuator: {stroke: 0.02, peak_force: 100}\n";
    expectRefused("pose 0 0 0 --robot " + robot.string(), 1, {"heavy.yaml:4: platform.inertia", "1e+308"});
}

TEST(CliInput, NonFinitePoseIsNotCalledAMeasurement) {
    const fs::path trajectory = scratch("huge.yaml");
    // finite but absurd accelerations give non-finite forces: named as such, not "peak force exceeded"
    std::ofstream(trajectory) << "duration: 0.01\nx: {harmonics: [{amplitude: 1e-3, frequency: 1e6}]}\n";
    const CliRun r = run("inverse-dynamics --trajectory " + trajectory.string() + " --rate 1000");
    EXPECT_NE(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find("by nan mm"), std::string::npos) << r.err;
}

TEST(CliInput, SimulationWithTheTightestTolerancesFinishesInTime) {
    // the round-trip CSV of inverse-dynamics, replayed with the tightest accepted tolerances: the
    // integrator takes more and smaller steps (14 instead of 6 over 2 ms) and still finishes
    const fs::path forces = scratch("paper1.csv");
    const CliRun id = run("inverse-dynamics --trajectory paper1 --duration 0.002 -o " + forces.string());
    ASSERT_EQ(id.exit_code, 0) << id.err;
    const CliRun r = run("simulate --forces " + forces.string() + " --atol 1e-15 --rtol 1e-14");
    EXPECT_NE(r.exit_code, 124) << "simulate did not finish within " << kTimeLimit << " s";
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("steps accepted"), std::string::npos) << r.err;
    // a header and the 2 ms at the output rate (10 kHz)
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 21) << r.out;
}

TEST(CliInput, LeavingTheWorkspaceInSimulationIsNamedAsSuch) {
    // a large constant force pushes slider 1 until its limb cannot reach the platform
    const fs::path forces = scratch("push.csv");
    std::ofstream(forces) << "t,tau1,tau2,tau3\n0,2000,0,0\n1,2000,0,0\n";
    const CliRun r = run("simulate --forces " + forces.string() + " --rate 1000");
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("t = "), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("lost the assembly mode"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace nocdyn::test
