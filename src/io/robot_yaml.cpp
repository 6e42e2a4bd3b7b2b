// Robot files (see robot_yaml.hpp).
#include "nocdyn/io/robot_yaml.hpp"

#include <filesystem>
#include <sstream>

#include "nocdyn/error.hpp"
#include "expression.hpp"
#include "yaml_util.hpp"

namespace nocdyn::io {

RobotParameters parseRobot(const std::string& text, const std::string& source) {
    const YAML::Node root = detail::loadDocument(text, source);
    detail::ExpressionEvaluator evaluator;
    (void)detail::declareParameters(root, source, {}, evaluator);
    const detail::ExpressionScope expressions(evaluator);
    return detail::parseShortForm(root, source);
}

RobotParameters detail::parseShortForm(const YAML::Node& root, const std::string& source) {
    const Context top{source, ""};
    detail::requireMap(top, root, {"name", "geometry", "slider", "link", "platform", "actuator", "limits"});

    RobotParameters robot;
    robot.name = std::filesystem::path(source).stem().string();
    if (const YAML::Node name = root["name"]; name.IsDefined()) {
        if (!name.IsScalar() || name.Scalar().empty()) detail::fail(top / "name", name, "expected a non-empty string");
        robot.name = name.Scalar();
    }
    auto section = [&](const char* key, std::initializer_list<const char*> allowed) {
        const YAML::Node node = root[key];
        if (!node.IsDefined()) detail::fail(top / key, root, "required section is missing");
        detail::requireMap(top / key, node, allowed);
        return node;
    };
    const YAML::Node geometry = section("geometry", {"base_side", "platform_side", "link_length", "link_com"});
    robot.base_side = detail::requireNumber(top / "geometry", geometry, "base_side");
    robot.platform_side = detail::requireNumber(top / "geometry", geometry, "platform_side");
    robot.link_length = detail::requireNumber(top / "geometry", geometry, "link_length");
    robot.link_com = detail::requireNumber(top / "geometry", geometry, "link_com");
    const YAML::Node slider = section("slider", {"mass"});
    robot.slider_mass = detail::requireNumber(top / "slider", slider, "mass");
    const YAML::Node link = section("link", {"mass", "inertia"});
    robot.link_mass = detail::requireNumber(top / "link", link, "mass");
    robot.link_inertia = detail::requireNumber(top / "link", link, "inertia");
    const YAML::Node platform = section("platform", {"mass", "inertia"});
    robot.platform_mass = detail::requireNumber(top / "platform", platform, "mass");
    robot.platform_inertia = detail::requireNumber(top / "platform", platform, "inertia");
    const YAML::Node actuator = section("actuator", {"stroke", "peak_force"});
    robot.stroke = detail::requireNumber(top / "actuator", actuator, "stroke");
    robot.peak_force = detail::requireNumber(top / "actuator", actuator, "peak_force");
    if (const YAML::Node limits = root["limits"]; limits.IsDefined()) {
        detail::requireMap(top / "limits", limits, {"max_condition"});
        robot.max_condition = detail::optionalNumber(top / "limits", limits, "max_condition", robot.max_condition);
    }
    try {
        validate(robot);
    } catch (const ParameterError& e) {
        // name the file's line of the field at fault: "geometry.link_com" -> root[geometry][link_com]
        const std::string& field = e.field();
        const auto dot = field.find('.');
        const YAML::Node node = root[field.substr(0, dot)][field.substr(dot + 1)];
        detail::fail(top / field, node, e.reason());
    }
    return robot;
}

RobotParameters loadRobot(const std::string& path) { return parseRobot(detail::readFile(path, "robot file"), path); }

std::string robotToYaml(const RobotParameters& robot) {
    std::ostringstream out;
    out.precision(17);
    out << "name: " << robot.name << "\n"
        << "geometry:\n"
        << "  base_side: " << robot.base_side << "      # b [m]\n"
        << "  platform_side: " << robot.platform_side << "  # a [m]\n"
        << "  link_length: " << robot.link_length << "    # l [m]\n"
        << "  link_com: " << robot.link_com << "       # l_c, from A_j to the link's c.o.m. [m]\n"
        << "slider: {mass: " << robot.slider_mass << "}\n"
        << "link: {mass: " << robot.link_mass << ", inertia: " << robot.link_inertia << "}\n"
        << "platform: {mass: " << robot.platform_mass << ", inertia: " << robot.platform_inertia << "}\n"
        << "actuator: {stroke: " << robot.stroke << ", peak_force: " << robot.peak_force << "}\n"
        << "limits: {max_condition: " << robot.max_condition << "}\n";
    return out.str();
}

}  // namespace nocdyn::io
