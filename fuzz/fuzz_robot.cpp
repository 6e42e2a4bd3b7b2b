// libFuzzer harness of the robot-file reader (the short form): any text either becomes
// parameters whose expansion builds a Model with finite inverse dynamics at home, or is
// refused with nocdyn::Error. Anything else (a crash, another exception, a sanitizer report,
// a non-finite number) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "nocdyn/description.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(bytes), size);
    nocdyn::io::RobotParameters robot;
    try {
        robot = nocdyn::io::parseRobot(text, "fuzz.yaml");
    } catch (const nocdyn::Error&) {
        return 0;
    }
    // Accepted parameters must give a model (validate() has passed; a throw here is a finding)
    // with finite dynamics.
    const nocdyn::Model model(nocdyn::io::expand(robot));
    nocdyn::Data data(model);
    const nocdyn::Status status =
        nocdyn::inverseDynamics(model, data, model.home, nocdyn::Twist(0.1, 0.01, -0.01), nocdyn::Twist(1.0, 0.1, 0.1));
    if (status && !(data.I.allFinite() && data.C.allFinite() && data.tau.allFinite())) std::abort();
    // The file written back reads back to the same numbers.
    if (nocdyn::io::parseRobot(nocdyn::io::robotToYaml(robot), "back.yaml").link_length != robot.link_length) {
        std::abort();
    }
    return 0;
}
