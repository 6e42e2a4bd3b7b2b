// Output files (io/output.hpp) and the streaming CSV writer: all or nothing, never through a
// planted link, special files written straight through, every number read back exactly.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/output.hpp"
#include "skip.hpp"

namespace nocdyn::test {
namespace {

namespace fs = std::filesystem;

/// An empty directory private to the running test.
fs::path freshDirectory() {
    const fs::path dir = fs::path(testing::TempDir()) / "nocdyn_output_test" /
                         testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::size_t entries(const fs::path& dir) {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(OutputFile, CreateNewFileRefusesAPlantedLinkAndLeavesItsTargetAlone) {
    const fs::path dir = freshDirectory();
    std::ofstream(dir / "victim.txt") << "keep";
    fs::create_symlink(dir / "victim.txt", dir / "planted");
    fs::create_symlink(dir / "would-be-created", dir / "dangling");
    EXPECT_THROW((void)io::createNewFile((dir / "planted").string()), Error);
    EXPECT_THROW((void)io::createNewFile((dir / "dangling").string()), Error);
    EXPECT_EQ(slurp(dir / "victim.txt"), "keep");
    EXPECT_FALSE(fs::exists(dir / "would-be-created"));
    const int fd = io::createNewFile((dir / "new").string());
    EXPECT_GE(fd, 0);
    ::close(fd);
    EXPECT_THROW((void)io::createNewFile((dir / "new").string()), Error);
}

TEST(OutputFile, PlantedPartialNameIsNotFollowed) {
    const fs::path dir = freshDirectory();
    std::ofstream(dir / "victim.txt") << "keep";
    fs::create_symlink(dir / "victim.txt", dir / "out.csv.partial");
    io::writeCsvFile((dir / "out.csv").string(), io::Table{{"t"}, {{1.5}}});
    EXPECT_EQ(slurp(dir / "victim.txt"), "keep");
    EXPECT_EQ(slurp(dir / "out.csv"), "t\n1.5\n");
    EXPECT_EQ(entries(dir), 3u);  // victim, the planted link, out.csv: no temporary file left
}

TEST(OutputFile, TargetThatLinksToARegularFileIsReplacedNotWrittenThrough) {
    const fs::path dir = freshDirectory();
    std::ofstream(dir / "victim.txt") << "keep";
    fs::create_symlink(dir / "victim.txt", dir / "out.csv");
    io::writeTextFile((dir / "out.csv").string(), "new\n");
    EXPECT_EQ(slurp(dir / "victim.txt"), "keep");
    EXPECT_FALSE(fs::is_symlink(dir / "out.csv"));
    EXPECT_EQ(slurp(dir / "out.csv"), "new\n");
}

TEST(OutputFile, FifoIsWrittenStraightThroughAndStaysAFifo) {
    const fs::path dir = freshDirectory();
    const fs::path fifo = dir / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Held open for reading and writing, so that neither side blocks (the text fits the pipe).
    const int fd = ::open(fifo.c_str(), O_RDWR | O_NONBLOCK);
    ASSERT_GE(fd, 0);
    io::writeTextFile(fifo.string(), "through the pipe\n");
    char buffer[64] = {};
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    ::close(fd);
    EXPECT_EQ(std::string(buffer, static_cast<std::size_t>(std::max<ssize_t>(n, 0))), "through the pipe\n");
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_EQ(entries(dir), 1u);
}

TEST(OutputFile, FullDeviceFailsWithTheReason) {
    if (!fs::is_character_file("/dev/full")) NOCDYN_SKIP_OR_FAIL_IN_CI("no /dev/full");
    try {
        io::writeTextFile("/dev/full", std::string(1 << 20, 'x'));
        ADD_FAILURE() << "a write to /dev/full succeeded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("No space left"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(OutputFile, WithoutCommitNothingIsLeftAndTheOldFileIsKept) {
    const fs::path dir = freshDirectory();
    std::ofstream(dir / "out.csv") << "old\n";
    {
        io::OutputFile out((dir / "out.csv").string());
        out.write(std::string(200000, 'x'));  // more than the buffer: some reached the temporary file
        EXPECT_EQ(entries(dir), 2u);
    }
    EXPECT_EQ(slurp(dir / "out.csv"), "old\n");
    EXPECT_EQ(entries(dir), 1u);
}

TEST(OutputFile, ReplacingAFileKeepsItsPermissions) {
    const fs::path dir = freshDirectory();
    std::ofstream(dir / "out.csv") << "old\n";
    fs::permissions(dir / "out.csv", fs::perms::owner_read | fs::perms::owner_write);
    io::writeTextFile((dir / "out.csv").string(), "new\n");
    EXPECT_EQ(fs::status(dir / "out.csv").permissions(), fs::perms::owner_read | fs::perms::owner_write);
}

TEST(CsvWriter, ShortestFormReadsBackAsTheSameDouble) {
    const fs::path dir = freshDirectory();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-300, 300);
    io::Table table{{"a", "b", "c"}, {}};
    table.rows.push_back({0.0, -0.0, std::numeric_limits<double>::max()});
    table.rows.push_back({std::numeric_limits<double>::min(), -std::numeric_limits<double>::min(), 0.1});
    table.rows.push_back({1.0 / 3.0, 2.0 / 3.0, 1e23});
    for (int k = 0; k < 3000; ++k) {
        table.rows.push_back({std::ldexp(mantissa(rng), exponent(rng)), mantissa(rng), std::ldexp(mantissa(rng), 60)});
    }
    io::writeCsvFile((dir / "t.csv").string(), table);
    const io::Table back = io::readCsvFile((dir / "t.csv").string());
    ASSERT_EQ(back.rows.size(), table.rows.size());
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        for (std::size_t c = 0; c < 3; ++c) {
            ASSERT_EQ(back.rows[r][c], table.rows[r][c]) << "row " << r << " column " << c;
            ASSERT_EQ(std::signbit(back.rows[r][c]), std::signbit(table.rows[r][c])) << "row " << r;
        }
    }
    // Shortest form: 0.1 is written as "0.1", not 0.10000000000000001.
    EXPECT_NE(slurp(dir / "t.csv").find(",0.1\n"), std::string::npos);
}

TEST(CsvWriter, NonFiniteNumberIsRefusedNamingRowAndColumnAndNoFileIsLeft) {
    const fs::path dir = freshDirectory();
    for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
        try {
            io::writeCsvFile((dir / "t.csv").string(), io::Table{{"t", "tau2"}, {{0.0, 1.0}, {0.1, bad}}});
            ADD_FAILURE() << "wrote " << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("row 2, column 'tau2'"), std::string::npos) << e.what();
        }
        EXPECT_EQ(entries(dir), 0u);
    }
}

std::vector<std::vector<double>> sampleRows(std::size_t count) {
    std::vector<std::vector<double>> rows;
    for (std::size_t k = 0; k < count; ++k) {
        const double t = static_cast<double>(k) * 1e-4;
        rows.push_back({t, std::sin(t), std::cos(3.0 * t) * 1e-7, 1.0 / (1.0 + t)});
    }
    return rows;
}

TEST(CsvWriter, SecondThreadWritesTheSameBytes) {
    const fs::path dir = freshDirectory();
    const auto rows = sampleRows(5000);  // several blocks and a partial one
    for (const bool background : {false, true}) {
        io::OutputFile out((dir / (background ? "background.csv" : "direct.csv")).string());
        io::CsvWriter csv(out, {"t", "a", "b", "c"}, background);
        for (const auto& row : rows) csv.row(row);
        csv.finish();
        out.commit();
    }
    const std::string direct = slurp(dir / "direct.csv");
    EXPECT_EQ(slurp(dir / "background.csv"), direct);
    EXPECT_EQ(std::count(direct.begin(), direct.end(), '\n'), 5001);
}

TEST(CsvWriter, SecondThreadsFailedWriteReachesTheCaller) {
    if (!fs::is_character_file("/dev/full")) NOCDYN_SKIP_OR_FAIL_IN_CI("no /dev/full");
    io::OutputFile out("/dev/full");
    try {
        io::CsvWriter csv(out, {"t", "a", "b", "c"}, true);
        for (const auto& row : sampleRows(50000)) csv.row(row);
        csv.finish();
        ADD_FAILURE() << "50000 rows went to /dev/full";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("No space left"), std::string::npos) << e.what();
    }
}

TEST(CsvWriter, DroppedWithoutFinishLeavesNoFile) {
    const fs::path dir = freshDirectory();
    {
        io::OutputFile out((dir / "out.csv").string());
        io::CsvWriter csv(out, {"t", "a", "b", "c"}, true);
        for (const auto& row : sampleRows(5000)) csv.row(row);
    }
    EXPECT_EQ(entries(dir), 0u);
}

}  // namespace
}  // namespace nocdyn::test
