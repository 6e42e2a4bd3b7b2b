#include "yaml_util.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "nocdyn/error.hpp"

namespace nocdyn::io::detail {

void fail(const Context& context, const YAML::Node& node, const std::string& reason) {
    std::ostringstream msg;
    msg << context.source;
    if (node.IsDefined() && node.Mark().line >= 0) msg << ":" << node.Mark().line + 1;
    msg << ": ";
    if (!context.field.empty()) msg << context.field << ": ";
    msg << reason;
    throw Error(msg.str());
}

YAML::Node loadDocument(const std::string& text, const std::string& source) {
    try {
        return YAML::Load(text);
    } catch (const YAML::ParserException& e) {
        std::ostringstream msg;
        msg << source << ":" << e.mark.line + 1 << ": not valid YAML: " << e.msg;
        throw Error(msg.str());
    }
}

void requireMap(const Context& context, const YAML::Node& node,
                std::initializer_list<const char*> allowed) {
    if (!node.IsMap()) fail(context, node, "expected a mapping of keys to values");
    for (const auto& entry : node) {
        const std::string key = entry.first.Scalar();
        bool known = false;
        for (const char* name : allowed) known = known || key == name;
        if (!known) {
            std::string list;
            for (const char* name : allowed) list += (list.empty() ? "" : ", ") + std::string(name);
            fail(context / key, entry.first, "unknown key (expected one of: " + list + ")");
        }
    }
}

double toNumber(const Context& context, const YAML::Node& node) {
    if (!node.IsScalar()) fail(context, node, "expected a number");
    double value = 0.0;
    try {
        value = node.as<double>();
    } catch (const YAML::Exception&) {
        fail(context, node, "expected a number, got '" + node.Scalar() + "'");
    }
    if (!std::isfinite(value)) fail(context, node, "expected a finite number, got '" + node.Scalar() + "'");
    return value;
}

double requireNumber(const Context& context, const YAML::Node& map, const char* key) {
    const YAML::Node node = map[key];
    if (!node.IsDefined() || node.IsNull()) fail(context / key, map, "required number is missing");
    return toNumber(context / key, node);
}

double optionalNumber(const Context& context, const YAML::Node& map, const char* key,
                      double fallback) {
    const YAML::Node node = map[key];
    if (!node.IsDefined()) return fallback;
    return toNumber(context / key, node);
}

std::string readFile(const std::string& path, const char* what) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(std::string("cannot open ") + what + " '" + path + "'");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error(std::string("cannot read ") + what + " '" + path + "'");
    return text.str();
}

}  // namespace nocdyn::io::detail
