// libFuzzer harness of the sampled-trajectory (CSV) reader: any text either becomes a
// trajectory whose pose, velocity and acceleration are finite at a few instants, or is refused
// with nocdyn::Error.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "nocdyn/error.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(bytes), size);
    nocdyn::PoseTrajectory trajectory;
    try {
        trajectory = nocdyn::io::parseTrajectoryCsv(text, "fuzz.csv");
    } catch (const nocdyn::Error&) {
        return 0;
    }
    const double end = trajectory.duration ? *trajectory.duration : 0.2;
    for (const double t : {-1.0, 0.0, 0.5 * end, end, end + 1.0}) {
        nocdyn::Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        if (!(p.allFinite() && dp.allFinite() && ddp.allFinite())) std::abort();
    }
    return 0;
}
