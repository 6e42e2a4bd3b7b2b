// libFuzzer harness of the robot-file reader: any text either becomes parameters from which a
// Model is built and whose inverse dynamics at the reference posture are finite, or is
// refused with nocdyn::Error. Anything else (a crash, another exception, a sanitizer report,
// a non-finite number) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_yaml.hpp"
#include "nocdyn/prr3/dynamics.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(bytes), size);
    nocdyn::RobotParameters robot;
    try {
        robot = nocdyn::io::parseRobot(text, "fuzz.yaml");
    } catch (const nocdyn::Error&) {
        return 0;
    }
    // Accepted parameters must give a model (validate() has passed) with finite dynamics.
    const nocdyn::prr3::Model model(robot);
    nocdyn::prr3::Data data;
    const nocdyn::Status status = nocdyn::prr3::inverseDynamics(
        model, data, nocdyn::Pose::Zero(), nocdyn::Twist(0.1, 0.01, -0.01), nocdyn::Twist(1.0, 0.1, 0.1));
    if (status && !(data.I.allFinite() && data.C.allFinite() && data.tau.allFinite())) std::abort();
    // The file written back reads back to the same numbers.
    if (nocdyn::io::parseRobot(nocdyn::io::robotToYaml(robot), "back.yaml").link_length != robot.link_length) {
        std::abort();
    }
    return 0;
}
