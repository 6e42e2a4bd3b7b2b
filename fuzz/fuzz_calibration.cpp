// libFuzzer harness of the calibration-file reader (identify --calibration): any text either
// becomes a calibration of the paper's prototype, one finite value per base column, each column a
// standard parameter of that robot, or is refused with nocdyn::Error. Anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "nocdyn/error.hpp"
#include "nocdyn/tables/calibration.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/io/short_form.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    static const nocdyn::Model model{nocdyn::io::expand(nocdyn::io::RobotParameters{})};
    const std::string text(reinterpret_cast<const char*>(bytes), size);
    nocdyn::Calibration calibration;
    try {
        calibration = nocdyn::tables::parseCalibration(text, "fuzz.yaml", model);
    } catch (const nocdyn::Error&) {
        return 0;
    }
    if (calibration.independent.empty() ||
        static_cast<std::size_t>(calibration.beta.size()) != calibration.independent.size() ||
        !calibration.beta.allFinite())
        std::abort();
    for (const int c : calibration.independent) {
        if (c < 0 || c >= nocdyn::parameterCount(model)) std::abort();
    }
    return 0;
}
