// PEER AT2 records: the three header forms, the shipped El Centro record, and truncated or
// malformed files refused with their line; three-component records on a table's x, y, z.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/ground_motion3.hpp"

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

// --- three-component records ------------------------------------------------------------

TEST(GroundMotion3, ReadsEachComponentsOrientationFromTheSecondHeaderLine) {
    const auto d = [](const char* line) { return io::componentDirection(line); };
    ASSERT_TRUE(d("Imperial Valley-02, 5/19/1940, El Centro Array #9, 180"));
    EXPECT_FALSE(d("Imperial Valley-02, 5/19/1940, El Centro Array #9, 180")->vertical);
    EXPECT_EQ(d("Imperial Valley-02, 5/19/1940, El Centro Array #9, 180")->azimuth, 180.0);
    EXPECT_EQ(d("Northridge-05, 1/18/1994, Sylmar, 90")->azimuth, 90.0);
    EXPECT_EQ(d("X, 090 ")->azimuth, 90.0);
    EXPECT_EQ(d("CAPE MENDOCINO 04/25/92 1806, EUREKA - MYRTLE & WEST, 090 (CDMG STATION 89509)")->azimuth, 90.0);
    EXPECT_EQ(d("X, 360")->azimuth, 360.0);
    EXPECT_TRUE(d("Northridge-05, 1/18/1994, Sylmar, UP")->vertical);
    EXPECT_EQ(d("X, up")->sign, 1.0);
    EXPECT_EQ(d("X, DWN")->sign, -1.0);
    EXPECT_EQ(d("X, Down")->sign, -1.0);
    for (const char* bad :
         {"X, 400", "X, 1800", "X, -90", "X, 18O", "X,", "", "X, NS", "X, 90.5", "1559 points at equal"})
        EXPECT_FALSE(d(bad)) << bad;
}

std::string records3(const std::string& name) { return std::string(NOCDYN_SOURCE_DIR) + "/data/records3/" + name; }

std::vector<io::GroundMotionRecord> elCentro3() {
    return {io::readAt2File(records3("RSN6_IMPVALL.I_I-ELC180-hor1.AT2")),
            io::readAt2File(records3("RSN6_IMPVALL.I_I-ELC270-hor2.AT2")),
            io::readAt2File(records3("RSN6_IMPVALL.I_I-ELC-UP.AT2"))};
}

// El Centro 1940, Array #9: 180 (south), 270 (west), UP, of 5372, 5346, 5378 points. x at the
// first horizontal's azimuth (180) and y 90 degrees counter-clockwise from it seen from above
// (east): a_x = a_180, a_y = -a_270, a_z = a_UP, the shorter ones padded with zeros; any order.
TEST(GroundMotion3, ElCentroOnTheTableInAnyOrderWithItsShorterComponentsPadded) {
    const std::vector<io::GroundMotionRecord> c = elCentro3();
    std::vector<int> order = {0, 1, 2};
    do {
        const io::TableMotion m = io::combineComponents({c[order[0]], c[order[1]], c[order[2]]});
        EXPECT_EQ(m.name, "RSN6_IMPVALL.I_I-ELC");
        EXPECT_EQ(m.x_azimuth, 180.0);
        EXPECT_EQ(m.dt, 0.01);
        EXPECT_TRUE(m.has_vertical);
        ASSERT_EQ(m.ax.size(), 5378u);
        ASSERT_EQ(m.ay.size(), 5378u);
        ASSERT_EQ(m.az.size(), 5378u);
        EXPECT_EQ(m.sources, (std::vector<std::string>{c[0].source, c[1].source, c[2].source}));
        for (std::size_t k = 0; k < 5378; k += 97) {
            const double a180 = k < 5372 ? c[0].acceleration[k] : 0.0;
            const double a270 = k < 5346 ? c[1].acceleration[k] : 0.0;
            EXPECT_NEAR(m.ax[k], a180, 1e-15) << k;
            EXPECT_NEAR(m.ay[k], -a270, 1e-15) << k;
            EXPECT_EQ(m.az[k], c[2].acceleration[k]) << k;
        }
        EXPECT_EQ(m.ax[5377], 0.0);
        EXPECT_EQ(m.ay[5346], 0.0);
        ASSERT_EQ(m.notes.size(), 2u);
        EXPECT_NE(m.notes[0].find("RSN6_IMPVALL.I_I-ELC180-hor1.AT2 has 5372 samples, the longest 5378: padded with "
                                  "zeros after 53.71 s"),
                  std::string::npos)
            << m.notes[0];
        EXPECT_NE(m.notes[1].find("ELC270-hor2.AT2 has 5346 samples"), std::string::npos) << m.notes[1];
    } while (std::next_permutation(order.begin(), order.end()));
}

// A rotation keeps the horizontal acceleration's magnitude; x at 270 puts a_270 on x and a_180
// on y (south is 90 degrees counter-clockwise from west seen from above).
TEST(GroundMotion3, TheTablesXAzimuthRotatesTheHorizontalsRigidly) {
    const std::vector<io::GroundMotionRecord> c = elCentro3();
    const io::TableMotion m270 = io::combineComponents(c, 270.0);
    for (std::size_t k = 0; k < 5346; k += 89) {
        EXPECT_NEAR(m270.ax[k], c[1].acceleration[k], 1e-15);
        EXPECT_NEAR(m270.ay[k], c[0].acceleration[k], 1e-15);
    }
    for (const double beta : {0.0, 37.5, -120.0, 359.0}) {
        const io::TableMotion m = io::combineComponents(c, beta);
        for (std::size_t k = 0; k < 5346; k += 101) {
            const double a1 = c[0].acceleration[k], a2 = c[1].acceleration[k];
            EXPECT_NEAR(std::hypot(m.ax[k], m.ay[k]), std::hypot(a1, a2), 1e-14) << beta;
        }
    }
    EXPECT_THROW((void)io::combineComponents(c, 400.0), Error);
}

// Turning the table's x by +90 degrees of azimuth (clockwise seen from above) puts the new x
// where -y was and the new y where x was: x' = -y, y' = x, at any x azimuth; z is untouched.
TEST(GroundMotion3, TurningTheTablesXAzimuthBy90DegreesGivesXPrimeMinusYAndYPrimeX) {
    const std::vector<io::GroundMotionRecord> c = elCentro3();
    for (const double beta : {180.0, 0.0, 37.5, -120.0, 250.0}) {
        const io::TableMotion m = io::combineComponents(c, beta);
        const io::TableMotion turned = io::combineComponents({c[2], c[0], c[1]}, beta + 90.0);
        EXPECT_EQ(turned.x_azimuth, beta + 90.0);
        for (std::size_t k = 0; k < 5378; k += 83) {
            EXPECT_NEAR(turned.ax[k], -m.ay[k], 1e-14) << beta << " " << k;
            EXPECT_NEAR(turned.ay[k], m.ax[k], 1e-14) << beta << " " << k;
            EXPECT_EQ(turned.az[k], m.az[k]);
        }
    }
}

// Northridge 1994 at Sylmar: 090 (east) and 360 (north). x east, y north (90 degrees
// counter-clockwise from east): a_x = a_090, a_y = a_360; a DWN vertical is reversed.
TEST(GroundMotion3, NorthridgeEastAndNorthAndADownwardVerticalReversed) {
    io::GroundMotionRecord h1 = io::readAt2File(records3("RSN1690_NORTH151_SYL090-hor1.AT2"));
    io::GroundMotionRecord h2 = io::readAt2File(records3("RSN1690_NORTH151_SYL360-hor2.AT2"));
    io::GroundMotionRecord v = io::readAt2File(records3("RSN1690_NORTH151_SYL-UP.AT2"));
    const io::TableMotion m = io::combineComponents({v, h2, h1});
    EXPECT_EQ(m.name, "RSN1690_NORTH151_SYL");
    EXPECT_EQ(m.x_azimuth, 90.0);
    EXPECT_TRUE(m.notes.empty());
    for (std::size_t k = 0; k < 1000; k += 37) {
        EXPECT_NEAR(m.ax[k], h1.acceleration[k], 1e-15);
        EXPECT_NEAR(m.ay[k], h2.acceleration[k], 1e-15);
        EXPECT_EQ(m.az[k], v.acceleration[k]);
    }
    v.event = "Northridge-05, 1/18/1994, Sylmar - County Hospital Grounds, DWN";
    const io::TableMotion down = io::combineComponents({h1, h2, v});
    EXPECT_EQ(down.az[500], -v.acceleration[500]);
    // two horizontals alone: a two-DOF table's record, z zero
    const io::TableMotion flat = io::combineComponents({h1, h2});
    EXPECT_FALSE(flat.has_vertical);
    EXPECT_EQ(flat.az, std::vector<double>(1000, 0.0));
}

void expectCombineError(const std::vector<io::GroundMotionRecord>& c, std::initializer_list<const char*> fragments) {
    try {
        (void)io::combineComponents(c);
        ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
        for (const char* f : fragments) EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
    }
}

TEST(GroundMotion3, RefusesComponentsThatDoNotMakeOneRecordNamingTheFile) {
    const std::vector<io::GroundMotionRecord> c = elCentro3();
    expectCombineError({c[0], c[2]}, {"two horizontal components, found 1", "ELC180-hor1.AT2"});
    expectCombineError({c[0], c[1], c[2], c[2]}, {"ELC-UP.AT2: a second vertical component"});
    expectCombineError({c[0], c[0], c[2]}, {"ELC180-hor1.AT2: azimuth 180 is not at 90 degrees from", "orthogonal"});
    io::GroundMotionRecord other_step = c[1];
    other_step.dt = 0.02;
    expectCombineError({c[0], other_step}, {"ELC270-hor2.AT2: time step 0.02 s differs from", "0.01 s"});
    const io::GroundMotionRecord old = io::readAt2File(std::string(NOCDYN_SOURCE_DIR) + "/data/elcentro_1940_ns.AT2");
    expectCombineError(
        {old, c[1]},
        {"elcentro_1940_ns.AT2:2: the component's orientation is not at the end of the line", "1559 points at equal"});
}

TEST(GroundMotion3, ComponentFilesAreGroupedByTheirSharedName) {
    EXPECT_EQ(io::componentGroup("/x/RSN6_IMPVALL.I_I-ELC180-hor1.AT2"), "RSN6_IMPVALL.I_I-ELC");
    EXPECT_EQ(io::componentGroup("RSN6_IMPVALL.I_I-ELC-UP.AT2"), "RSN6_IMPVALL.I_I-ELC");
    EXPECT_EQ(io::componentGroup("quake_090.at2"), "quake");
    EXPECT_EQ(io::componentGroup("quake-DWN.AT2"), "quake");
    EXPECT_EQ(io::componentGroup("180.AT2"), "180");  // nothing left: the stem itself
    const std::vector<std::string> files = {"d/RSN6_IMPVALL.I_I-ELC270-hor2.AT2", "d/RSN1690_NORTH151_SYL-UP.AT2",
                                            "d/RSN6_IMPVALL.I_I-ELC-UP.AT2",      "d/RSN1690_NORTH151_SYL360-hor2.AT2",
                                            "d/RSN6_IMPVALL.I_I-ELC180-hor1.AT2", "d/RSN1690_NORTH151_SYL090-hor1.AT2"};
    const auto groups = io::groupComponents(files);
    ASSERT_EQ(groups.size(), 2u);
    EXPECT_EQ(groups[0].first, "RSN1690_NORTH151_SYL");
    EXPECT_EQ(groups[0].second,
              (std::vector<std::string>{"d/RSN1690_NORTH151_SYL-UP.AT2", "d/RSN1690_NORTH151_SYL090-hor1.AT2",
                                        "d/RSN1690_NORTH151_SYL360-hor2.AT2"}));
    EXPECT_EQ(groups[1].first, "RSN6_IMPVALL.I_I-ELC");
    EXPECT_EQ(groups[1].second.size(), 3u);
}

}  // namespace
}  // namespace nocdyn::test
