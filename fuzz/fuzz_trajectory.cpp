// libFuzzer harness of the trajectory-file reader: any text either becomes a trajectory whose
// pose, velocity and acceleration are finite at a few instants, or is refused with
// nocdyn::Error. Anything else is a finding.
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
        trajectory = nocdyn::io::parseTrajectory(text, "fuzz.yaml");
    } catch (const nocdyn::Error&) {
        return 0;
    }
    const double end = trajectory.duration ? *trajectory.duration : 0.2;
    for (const double t : {0.0, 1e-4, 0.5 * end, end}) {
        nocdyn::Pose p, dp, ddp;
        trajectory.evaluate(t, p, dp, ddp);
        if (!(p.allFinite() && dp.allFinite() && ddp.allFinite())) std::abort();
    }
    return 0;
}
