// libFuzzer harness of the PEER AT2 reader: any text either becomes a record of finite
// accelerations with a positive time step, or is refused with nocdyn::Error; the component's
// orientation read from its second line is an azimuth within 0-360 or a vertical of sign +-1.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "nocdyn/error.hpp"
#include "nocdyn/io/at2.hpp"
#include "nocdyn/io/ground_motion3.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(bytes), size);
    try {
        const nocdyn::io::GroundMotionRecord record = nocdyn::io::parseAt2(text, "fuzz.AT2");
        if (!(record.dt > 0.0) || record.acceleration.empty()) std::abort();
        for (const double a : record.acceleration) {
            if (!std::isfinite(a)) std::abort();
        }
        if (const auto d = nocdyn::io::componentDirection(record.event)) {
            if (d->vertical ? std::abs(d->sign) != 1.0 : !(d->azimuth >= 0.0 && d->azimuth <= 360.0)) std::abort();
        }
    } catch (const nocdyn::Error&) {
    }
    return 0;
}
