#include "yaml_util.hpp"

#include <sstream>
#include <string_view>
#include <vector>

#include "file_util.hpp"
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
    std::string_view body = text;
    detail::stripByteOrderMark(body);
    std::vector<YAML::Node> documents;
    try {
        documents = YAML::LoadAll(std::string(body));
    } catch (const YAML::ParserException& e) {
        std::ostringstream msg;
        msg << source << ":" << e.mark.line + 1 << ": not valid YAML: " << e.msg;
        throw Error(msg.str());
    }
    if (documents.empty()) return YAML::Node();
    if (documents.size() > 1) {
        std::ostringstream msg;
        msg << source;
        if (documents[1].Mark().line >= 0) msg << ":" << documents[1].Mark().line + 1;
        msg << ": a second YAML document (after '---'); the file must hold exactly one";
        throw Error(msg.str());
    }
    return documents.front();
}

void requireMap(const Context& context, const YAML::Node& node,
                std::initializer_list<const char*> allowed) {
    if (!node.IsMap()) fail(context, node, "expected a mapping of keys to values");
    std::vector<std::pair<std::string, int>> seen;  // key, 1-based line
    for (const auto& entry : node) {
        if (!entry.first.IsScalar()) fail(context, entry.first, "expected a plain key");
        const std::string key = entry.first.Scalar();
        for (const auto& [other, line] : seen) {
            if (other == key) {
                fail(context / key, entry.first,
                     "duplicate key (first given on line " + std::to_string(line) + ")");
            }
        }
        seen.emplace_back(key, entry.first.Mark().line + 1);
        bool known = false;
        for (const char* name : allowed) known = known || key == name;
        if (!known) {
            std::string list;
            for (const char* name : allowed) list += (list.empty() ? "" : ", ") + std::string(name);
            fail(context / key, entry.first, "unknown key (expected one of: " + list + ")");
        }
    }
}

namespace {

double toNumber(const Context& context, const YAML::Node& node) {
    if (!node.IsScalar()) fail(context, node, "expected a number");
    const std::optional<double> value = parseDecimal(node.Scalar());
    if (!value) {
        fail(context, node, "expected a finite decimal number (e.g. 0.25 or 2.5e-3), got '" + node.Scalar() + "'");
    }
    return *value;
}

}  // namespace

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

void requireRange(const Context& context, const YAML::Node& map, const char* key, double value, double lo,
                  double hi, const char* unit) {
    if (value >= lo && value <= hi) return;
    const YAML::Node node = map[key];
    fail(context / key, node.IsDefined() ? node : map,
         "must be in [" + formatted(lo) + ", " + formatted(hi) + "] " + unit + ", got " + formatted(value));
}

std::string formatted(double value) {
    std::ostringstream out;
    out.precision(6);
    out << value;
    return out.str();
}

std::string readFile(const std::string& path, const char* what) {
    return readRegularFile(path, what, kMaxYamlBytes);
}

}  // namespace nocdyn::io::detail
