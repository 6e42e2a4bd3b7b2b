// Calibration files (calibration.hpp).
#include "nocdyn/io/calibration.hpp"

#include <cstdio>

#include "nocdyn/error.hpp"
#include "yaml_util.hpp"

namespace nocdyn::io {

using detail::Context;

namespace {

constexpr std::size_t kMaxBaseParameters = 1000;

std::string roundTrip(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return buffer;
}

/// A single-quoted YAML scalar (quotes doubled).
std::string quoted(const std::string& text) {
    std::string out = "'";
    for (const char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
    return out + "'";
}

}  // namespace

std::string calibrationToYaml(const Model& model, const BaseResult& result, const std::string& comment) {
    std::string text = comment + "robot: " + quoted(model.description.name) + "\nbase_parameters:\n";
    for (std::size_t k = 0; k < result.beta.size(); ++k) {
        const Estimate& e = result.beta[k];
        text += "  - {parameter: " + quoted(parameterName(model, result.calibration.independent[k])) +
                ", value: " + roundTrip(e.value) + ", stddev: " + roundTrip(e.stddev) +
                ", robot_file: " + roundTrip(e.prior) + ", unit: " + quoted(e.unit) + ", name: " + quoted(e.name) +
                "}\n";
    }
    return text;
}

Calibration parseCalibration(const std::string& text, const std::string& source, const Model& model) {
    const YAML::Node root = detail::loadDocument(text, source);
    const Context top{source, ""};
    detail::requireMap(top, root, {"robot", "base_parameters"});
    const YAML::Node list = root["base_parameters"];
    if (!list.IsDefined() || !list.IsSequence() || list.size() == 0)
        detail::fail(top / "base_parameters", list, "expected a non-empty list of base parameters");
    if (list.size() > kMaxBaseParameters)
        detail::fail(top / "base_parameters", list, "more than " + std::to_string(kMaxBaseParameters) + " items");
    Calibration calibration;
    calibration.beta.resize(static_cast<Eigen::Index>(list.size()));
    const int P = parameterCount(model);
    for (std::size_t k = 0; k < list.size(); ++k) {
        const Context item = top / ("base_parameters[" + std::to_string(k) + "]");
        const YAML::Node node = list[k];
        detail::requireMap(item, node, {"parameter", "value", "stddev", "robot_file", "unit", "name"});
        const YAML::Node name = node["parameter"];
        if (!name.IsDefined() || !name.IsScalar()) detail::fail(item / "parameter", node, "expected a parameter name");
        int index = -1;
        for (int c = 0; c < P && index < 0; ++c) {
            if (parameterName(model, c) == name.Scalar()) index = c;
        }
        if (index < 0) {
            detail::fail(item / "parameter", name,
                         "'" + name.Scalar() + "' is not a parameter of robot '" + model.description.name +
                             "' (see nocdyn regressor)");
        }
        calibration.independent.push_back(index);
        calibration.beta(static_cast<Eigen::Index>(k)) = detail::requireNumber(item, node, "value");
    }
    return calibration;
}

Calibration loadCalibration(const std::string& path, const Model& model) {
    return parseCalibration(detail::readFile(path, "calibration file"), path, model);
}

}  // namespace nocdyn::io
