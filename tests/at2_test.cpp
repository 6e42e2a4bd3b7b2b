// PEER AT2 records: the three header forms, the shipped El Centro record, and truncated or
// malformed files refused with their line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

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

TEST(At2, ReadsTheNumbersFirstHeaderFormAndIgnoresExtraValues) {
    const io::GroundMotionRecord r = io::parseAt2(kHead + "4 0.00500 NPTS, DT\n1 2 3 4 5 6\n7\n", "c.AT2");
    EXPECT_DOUBLE_EQ(r.dt, 0.005);
    ASSERT_EQ(r.acceleration.size(), 4u);
    EXPECT_DOUBLE_EQ(r.acceleration[3], 4 * 9.80665);
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
