// PEER AT2 records: the three header forms, the shipped El Centro record, and truncated or
// malformed files refused with their line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"

namespace nocdyn::test {
namespace {

const std::string kHead =
    "PEER NGA STRONG MOTION DATABASE RECORD\nEVENT, DATE, STATION\nACCELERATION TIME SERIES IN UNITS OF G\n";

TEST(At2, ReadsTheNptsDtSecHeaderForm) {
    const io::GroundMotionRecord r = io::parseAt2(kHead + "NPTS=  3, DT=   .0100 SEC\n 0.1 -0.2\n  0.3\n", "a.AT2");
    EXPECT_EQ(r.title, "PEER NGA STRONG MOTION DATABASE RECORD");
    EXPECT_DOUBLE_EQ(r.dt, 0.01);
    ASSERT_EQ(r.acceleration.size(), 3u);
    EXPECT_DOUBLE_EQ(r.acceleration[1], -0.2 * 9.80665);
    EXPECT_DOUBLE_EQ(r.duration(), 0.02);
}

TEST(At2, ReadsTheLowerCaseDtHeaderFormWithoutUnit) {
    const io::GroundMotionRecord r = io::parseAt2(kHead + "NPTS=   2, dt=  .02000\r\n1E-3 2.5e-2\r\n", "b.AT2");
    EXPECT_DOUBLE_EQ(r.dt, 0.02);
    ASSERT_EQ(r.acceleration.size(), 2u);
    EXPECT_DOUBLE_EQ(r.acceleration[1], 0.025 * 9.80665);
}

TEST(At2, ReadsTheNumbersFirstHeaderFormAndRefusesValuesBeyondNpts) {
    const io::GroundMotionRecord r = io::parseAt2(kHead + "4 0.00500 NPTS, DT\n1 2 3 4\n", "c.AT2");
    EXPECT_DOUBLE_EQ(r.dt, 0.005);
    ASSERT_EQ(r.acceleration.size(), 4u);
    EXPECT_DOUBLE_EQ(r.acceleration[3], 4 * 9.80665);
    EXPECT_THROW((void)io::parseAt2(kHead + "4 0.00500 NPTS, DT\n1 2 3 4 5 6\n7\n", "c.AT2"), Error);
}

TEST(At2, ShippedElCentroRecordHas1559PointsAt20msAndItsKnownPeak) {
    const io::GroundMotionRecord r = io::readAt2File(std::string(NOCDYN_SOURCE_DIR) + "/data/elcentro_1940_ns.AT2");
    EXPECT_EQ(r.acceleration.size(), 1559u);
    EXPECT_DOUBLE_EQ(r.dt, 0.02);
    EXPECT_DOUBLE_EQ(r.acceleration[0], 0.0063 * 9.80665);
    double peak = 0.0;
    for (double a : r.acceleration) peak = std::max(peak, std::abs(a));
    EXPECT_NEAR(peak / 9.80665, 0.3194, 0.003);  // the El Centro N-S peak, about 0.32 g
}

// One record in each line ending (LF, CR LF, CR CR LF, lone CR), in the three header forms,
// with Fortran D exponents and values glued by their signs: all read as the same numbers.
TEST(At2, EveryLineEndingHeaderFormAndFortranSpellingReadsTheSameValues) {
    const std::vector<double> expected = {0.1234e-2, -0.5678e-3, 1.0e-3, -2.5e-2, 0.3};
    const std::string plain = "  .1234E-02  -.5678E-03\n 1.0E-03 -2.5E-02\n 0.3\n";
    const std::string fortran = ".1234D-02-.5678D-03\n1.0d-03-2.5E-02\n+0.3\n";
    const std::vector<std::string> headers = {"NPTS=  5, DT= .0100 SEC", "NPTS=     5, dt=  .01000",
                                              "5 0.01000 NPTS, DT"};
    for (const std::string& header : headers) {
        for (const std::string& data : {plain, fortran}) {
            for (const char* eol : {"\n", "\r\n", "\r\r\n", "\r"}) {
                std::string text = kHead + header + "\n" + data;
                std::string converted;
                for (char c : text) {
                    if (c == '\n') {
                        converted += eol;
                    } else {
                        converted += c;
                    }
                }
                const io::GroundMotionRecord r = io::parseAt2(converted, "v.AT2");
                EXPECT_DOUBLE_EQ(r.dt, 0.01) << header;
                ASSERT_EQ(r.acceleration.size(), expected.size()) << header << " " << data;
                for (std::size_t i = 0; i < expected.size(); ++i) {
                    EXPECT_DOUBLE_EQ(r.acceleration[i], expected[i] * 9.80665) << header << " " << data << " " << i;
                }
                EXPECT_EQ(r.title, "PEER NGA STRONG MOTION DATABASE RECORD");
            }
        }
    }
}

TEST(At2, TheSharedRecordsReadTheSameAfterACrCrLfConversion) {
    // Borah Peak: the "NPTS= N, dt= STEP" header form
    const std::string path = std::string(NOCDYN_SOURCE_DIR) + "/data/borahpeak_1983_cem_000.AT2";
    std::ifstream file(path, std::ios::binary);
    if (!file) GTEST_SKIP() << "no " << path;
    const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    std::string crcrlf;
    for (char c : text) {
        if (c == '\n') {
            crcrlf += "\r\r\n";
        } else {
            crcrlf += c;
        }
    }
    const io::GroundMotionRecord a = io::parseAt2(text, "a.AT2");
    const io::GroundMotionRecord b = io::parseAt2(crcrlf, "b.AT2");
    ASSERT_EQ(a.acceleration.size(), 4800u);
    EXPECT_DOUBLE_EQ(a.dt, 0.005);
    EXPECT_EQ(a.acceleration, b.acceleration);
    EXPECT_DOUBLE_EQ(a.acceleration[0], 0.1449237e-4 * 9.80665);
}

TEST(At2, RefusesAGluedValueThatIsNotANumberNamingItsLineAndPlace) {
    try {
        (void)io::parseAt2(kHead + "NPTS= 3, DT= .01\n1.0E-02-x.5E-03 3\n", "g.AT2");
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("g.AT2:5: value 2 '-x.5E-03'"), std::string::npos) << e.what();
    }
}

void expectAt2Error(const std::string& text, std::initializer_list<const char*> fragments) {
    try {
        (void)io::parseAt2(text, "r.AT2");
        ADD_FAILURE() << "accepted:\n" << text;
    } catch (const Error& e) {
        for (const char* f : fragments) EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
    }
}

TEST(At2, RefusesTruncatedAndMalformedRecordsNamingTheLine) {
    expectAt2Error(kHead + "NPTS=  5, DT= .01 SEC\n1 2\n3\n", {"r.AT2:6:", "after 3 of the NPTS = 5"});
    expectAt2Error("title\nevent\n", {"r.AT2:2:", "header cut short"});
    expectAt2Error(kHead + "POINTS= 5, DT= .01\n1 2 3 4 5\n", {"r.AT2:4:", "NPTS"});
    expectAt2Error(kHead + "NPTS= 2.5, DT= .01\n1 2 3\n", {"r.AT2:4:", "NPTS '2.5'"});
    expectAt2Error(kHead + "NPTS= 2, DT= 0\n1 2\n", {"r.AT2:4:", "DT '0'"});
    expectAt2Error(kHead + "NPTS= 3, DT= .01\n1\n2 nan 3\n", {"r.AT2:6:", "value 3 'nan'"});
    expectAt2Error(kHead + "NPTS= 3, DT= .01\n1 1e300 3\n", {"r.AT2:5:", "beyond"});
    expectAt2Error(kHead + "NPTS= 99999999999, DT= .01\n1\n", {"r.AT2:4:", "NPTS"});
}

}  // namespace
}  // namespace nocdyn::test
