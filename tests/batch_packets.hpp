// A test of the batch run on packets of four samples and on packets of eight (eight where the
// CPU has AVX-512: elsewhere both runs take four, and the test's `lanes` property says so).
#pragma once

#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "nocdyn/batch.hpp"

namespace nocdyn {

/// The parameter's name in GoogleTest's output (and ctest's test names).
inline void PrintTo(BatchPackets packets, std::ostream* os) {
    *os << (packets == BatchPackets::eight ? "eight" : packets == BatchPackets::four ? "four" : "automatic");
}

}  // namespace nocdyn

namespace nocdyn::test {

class BatchPacketsTest : public ::testing::TestWithParam<BatchPackets> {
protected:
    void SetUp() override {
        lanes = setBatchPackets(GetParam());
        RecordProperty("lanes", lanes);
    }
    void TearDown() override { setBatchPackets(BatchPackets::automatic); }
    int lanes = 0;
};

inline std::string packetsName(const ::testing::TestParamInfo<BatchPackets>& info) {
    return info.param == BatchPackets::eight ? "eight_lanes" : "four_lanes";
}

}  // namespace nocdyn::test

/// Instantiates the BatchPacketsTest-derived suite `suite` for four and eight lanes.
#define NOCDYN_BATCH_PACKETS(suite)                                                                          \
    INSTANTIATE_TEST_SUITE_P(Packets, suite,                                                                 \
                             ::testing::Values(::nocdyn::BatchPackets::four, ::nocdyn::BatchPackets::eight), \
                             ::nocdyn::test::packetsName)
