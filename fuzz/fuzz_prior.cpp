// libFuzzer harness of the payload prior-file reader (identify --prior): any text either becomes
// bounds that are ordered and never NaN, a mass bound only where positive and an inertia bound
// only where non-negative, or is refused with nocdyn::Error. Anything else is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "nocdyn/error.hpp"
#include "nocdyn/tables/calibration.hpp"

namespace {

bool ordered(const nocdyn::Bounds& b) { return !std::isnan(b.lower) && !std::isnan(b.upper) && b.lower <= b.upper; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(bytes), size);
    nocdyn::PayloadPrior prior;
    try {
        prior = nocdyn::tables::parsePayloadPrior(text, "fuzz.yaml");
    } catch (const nocdyn::Error&) {
        return 0;
    }
    for (const nocdyn::Bounds* b : {&prior.mass, &prior.com_x, &prior.com_y, &prior.inertia}) {
        if (!ordered(*b)) std::abort();
    }
    const auto open = [](double v) { return std::isinf(v); };
    if (!(open(prior.mass.lower) || prior.mass.lower > 0.0) || !(open(prior.mass.upper) || prior.mass.upper > 0.0))
        std::abort();
    if (!(open(prior.inertia.lower) || prior.inertia.lower >= 0.0) ||
        !(open(prior.inertia.upper) || prior.inertia.upper >= 0.0))
        std::abort();
    return 0;
}
