// Calibration files (calibration.hpp).
#include "nocdyn/tables/calibration.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "nocdyn/io/escape.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"
#include "../io/yaml_util.hpp"

namespace nocdyn::tables {

// the io layer's tables, files and quoting, below this one
using io::yamlQuoted;

using io::detail::Context;

namespace {

constexpr std::size_t kMaxBaseParameters = 1000;

std::string quoted(const std::string& text) { return yamlQuoted(text); }

}  // namespace

std::string calibrationToYaml(const Model& model, const BaseResult& result, const std::string& comment) {
    std::string text = comment + "robot: " + quoted(model.description.name) + "\nbase_parameters:\n";
    for (std::size_t k = 0; k < result.beta.size(); ++k) {
        const Estimate& e = result.beta[k];
        text += "  - {parameter: " + quoted(parameterName(model, result.calibration.independent[k])) +
                ", value: " + text::allDigits(e.value) + ", stddev: " + text::allDigits(e.stddev) +
                ", robot_file: " + text::allDigits(e.prior) + ", unit: " + quoted(e.unit) +
                ", name: " + quoted(e.name) + "}\n";
    }
    return text;
}

Calibration parseCalibration(const std::string& text, const std::string& source, const Model& model) {
    const YAML::Node root = io::detail::loadDocument(text, source);
    const Context top{source, ""};
    io::detail::requireMap(top, root, {"robot", "base_parameters"});
    const YAML::Node list = root["base_parameters"];
    if (!list.IsDefined() || !list.IsSequence() || list.size() == 0)
        io::detail::fail(top / "base_parameters", list, "expected a non-empty list of base parameters");
    if (list.size() > kMaxBaseParameters)
        io::detail::fail(top / "base_parameters", list, "more than " + std::to_string(kMaxBaseParameters) + " items");
    Calibration calibration;
    calibration.beta.resize(static_cast<Eigen::Index>(list.size()));
    const int P = parameterCount(model);
    for (std::size_t k = 0; k < list.size(); ++k) {
        const Context item = top / ("base_parameters[" + std::to_string(k) + "]");
        const YAML::Node node = list[k];
        io::detail::requireMap(item, node, {"parameter", "value", "stddev", "robot_file", "unit", "name"});
        const YAML::Node name = node["parameter"];
        if (!name.IsDefined() || !name.IsScalar())
            io::detail::fail(item / "parameter", node, "expected a parameter name");
        int index = -1;
        for (int c = 0; c < P && index < 0; ++c) {
            if (parameterName(model, c) == name.Scalar()) index = c;
        }
        if (index < 0) {
            io::detail::fail(item / "parameter", name,
                             "'" + name.Scalar() + "' is not a parameter of robot '" + model.description.name +
                                 "' (see nocdyn regressor)");
        }
        calibration.independent.push_back(index);
        calibration.beta(static_cast<Eigen::Index>(k)) = io::detail::requireNumber(item, node, "value");
    }
    return calibration;
}

Calibration loadCalibration(const std::string& path, const Model& model) {
    return parseCalibration(io::detail::readFile(path, "calibration file"), path, model);
}

namespace {

/// [lower, upper] at map[key] (absent: unbounded; ~ for an open side), lower >= `least` when
/// given (strictly above it when `strict`).
Bounds readBounds(const Context& context, const YAML::Node& map, const char* key, double least, bool strict,
                  const char* unit) {
    Bounds bounds;
    const YAML::Node node = map[key];
    if (!node.IsDefined()) return bounds;
    const Context field = context / key;
    if (!node.IsSequence() || node.size() != 2)
        io::detail::fail(field, node, "expected [lower, upper] in " + std::string(unit) + " (~ for an open side)");
    if (!node[0].IsNull()) bounds.lower = io::detail::toNumber(field / "lower", node[0]);
    if (!node[1].IsNull()) bounds.upper = io::detail::toNumber(field / "upper", node[1]);
    const auto allowed = [&](double v) { return strict ? v > least : v >= least; };
    const std::string limit = std::string(strict ? "> " : ">= ") + text::number(least) + " " + unit;
    if (std::isfinite(bounds.lower) && !allowed(bounds.lower))
        io::detail::fail(field / "lower", node[0], "must be " + limit + ", got " + text::number(bounds.lower));
    if (std::isfinite(bounds.upper) && !allowed(bounds.upper))
        io::detail::fail(field / "upper", node[1], "must be " + limit + ", got " + text::number(bounds.upper));
    if (bounds.lower > bounds.upper) {
        io::detail::fail(field, node,
                         "lower bound " + text::number(bounds.lower) + " is above upper bound " +
                             text::number(bounds.upper) + " " + unit);
    }
    return bounds;
}

}  // namespace

PayloadPrior parsePayloadPrior(const std::string& text, const std::string& source) {
    const YAML::Node root = io::detail::loadDocument(text, source);
    const Context top{source, ""};
    io::detail::requireMap(top, root, {"payload"});
    const YAML::Node payload = root["payload"];
    if (!payload.IsDefined())
        io::detail::fail(top / "payload", root, "required: the bounds on the payload's parameters");
    const Context context = top / "payload";
    io::detail::requireMap(context, payload, {"mass", "com_x", "com_y", "inertia"});
    PayloadPrior prior;
    prior.mass = readBounds(context, payload, "mass", 0.0, true, "kg");
    const double inf = std::numeric_limits<double>::infinity();
    prior.com_x = readBounds(context, payload, "com_x", -inf, false, "m");
    prior.com_y = readBounds(context, payload, "com_y", -inf, false, "m");
    prior.inertia = readBounds(context, payload, "inertia", 0.0, false, "kg m^2");
    return prior;
}

PayloadPrior loadPayloadPrior(const std::string& path) {
    return parsePayloadPrior(io::detail::readFile(path, "prior file"), path);
}

}  // namespace nocdyn::tables
