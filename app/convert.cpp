#include "app/convert.hpp"

#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn::app {

void validate(const ConvertOptions& options) {
    if (options.robot.path.empty() && !options.robot.description)
        throw OptionError("robot", "a robot file is required");
}

ConvertResult runConvert(const ConvertOptions& options, Observer& /*observer*/) {
    validate(options);
    const RobotDescription robot = loadRobot(options.robot);
    const Model model(robot);  // the home posture must be regular, as for every command
    ConvertResult out;
    out.robot = robot.name;
    out.limbs = model.limbs;
    out.actuators = model.actuators;
    const std::string source = options.robot.description ? std::string("<nocdyn.Robot>") : options.robot.path;
    out.text = "# " + io::terminalText(robot.name) + ": " + std::to_string(model.limbs) + " limbs (";
    for (int j = 0; j < model.limbs; ++j) {
        if (j > 0) out.text += ' ';
        out.text += robot.limbs[static_cast<std::size_t>(j)].type();
    }
    out.text +=
        "), " + std::to_string(model.actuators) + " actuators; general form of " + io::terminalText(source) + "\n";
    out.text += io::descriptionToYaml(robot);
    return out;
}

}  // namespace nocdyn::app
