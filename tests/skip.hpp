// Skipping a test for a missing tool or device: allowed on a developer's machine, a failure in
// CI (CI=true, as .ci/run sets it), where a skipped test would let a missing tool pass unseen.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string_view>

namespace nocdyn::test {

/// True under CI=true.
inline bool inContinuousIntegration() {
    const char* ci = std::getenv("CI");
    return ci != nullptr && std::string_view(ci) == "true";
}

}  // namespace nocdyn::test

/// Skips the test for `reason` (a missing tool or device), or fails it naming the reason under
/// CI=true.
#define NOCDYN_SKIP_OR_FAIL_IN_CI(reason)                                                   \
    do {                                                                                    \
        if (::nocdyn::test::inContinuousIntegration()) {                                    \
            GTEST_FAIL() << (reason) << " (CI=true: a test that would skip fails instead)"; \
        } else {                                                                            \
            GTEST_SKIP() << (reason);                                                       \
        }                                                                                   \
    } while (false)
