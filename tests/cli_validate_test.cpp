// nocdyn validate: the agreement table of the model with Simbody and MuJoCo, and a pose out of
// reach refused with the limb named.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "nocdyn/io/csv.hpp"

namespace nocdyn::test {
namespace {

int runCli(const std::string& arguments, std::string& err) {
    const std::string err_file = testing::TempDir() + "/validate_stderr.txt";
    const int status = std::system((std::string(NOCDYN_CLI) + " " + arguments + " >/dev/null 2>" + err_file).c_str());
    std::ifstream in(err_file);
    err.assign(std::istreambuf_iterator<char>(in), {});
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Validation, ValidateCommandReportsAgreementAndRejectsPosesOutOfReach) {
    std::string err;
    const std::string csv = testing::TempDir() + "/validate.csv";
    ASSERT_EQ(runCli("validate --trajectory paper2 --duration 0.05 --rate 1000 --output " + csv, err), 0) << err;
    EXPECT_NE(err.find("| Simbody | 1 |"), std::string::npos) << err;
    EXPECT_NE(err.find("| MuJoCo | 3 |"), std::string::npos) << err;
    const io::Table table = io::readCsvFile(csv);
    EXPECT_EQ(table.rows.size(), 50u);
    for (const char* column : {"simbody_tau1", "mujoco_tau3", "tau2", "u1"}) EXPECT_TRUE(table.has(column)) << column;
    for (const auto& row : table.rows) {
        EXPECT_NEAR(row[table.column("simbody_tau2")], row[table.column("tau2")], 1e-9 * 262);
    }

    const std::string far = testing::TempDir() + "/far.yaml";
    std::ofstream(far) << "duration: 0.1\ny: {harmonics: [{amplitude: 0.2, frequency: 5}]}\n";
    EXPECT_EQ(runCli("validate --trajectory " + far, err), 1);
    EXPECT_NE(err.find("pose out of reach: limb"), std::string::npos) << err;
}

}  // namespace
}  // namespace nocdyn::test
