#include "yaml_util.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include <sstream>
#include <string_view>
#include <vector>

#include "expression.hpp"
#include "file_util.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

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

namespace {

/// Parser events that only note where each document starts.
class DocumentStarts : public YAML::EventHandler {
public:
    std::vector<YAML::Mark> starts;
    void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
    void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {}
    void OnMapEnd() override {}
};

[[noreturn]] void failParse(const std::string& source, const YAML::ParserException& e) {
    std::ostringstream msg;
    msg << source << ":" << e.mark.line + 1 << ": not valid YAML: " << e.msg;
    throw Error(msg.str());
}

}  // namespace

YAML::Node loadDocument(const std::string& text, const std::string& source) {
    std::string_view body = text;
    detail::stripByteOrderMark(body);
    const std::string yaml(body);
    YAML::Node root;
    try {
        root = YAML::Load(yaml);  // the first document only
    } catch (const YAML::ParserException& e) {
        failParse(source, e);
    }
    // Whatever follows the first document is an error, not ignored. The parser is asked for
    // two documents at most: yaml-cpp 0.7's LoadAll loops forever on some input (a lone ',').
    std::istringstream stream(yaml);
    YAML::Parser parser(stream);
    DocumentStarts events;
    try {
        if (parser.HandleNextDocument(events) && parser.HandleNextDocument(events)) {
            std::ostringstream msg;
            msg << source;
            if (events.starts.size() > 1 && events.starts[1].line >= 0) msg << ":" << events.starts[1].line + 1;
            msg << ": a second YAML document, or content after the first; the file must hold exactly one";
            throw Error(msg.str());
        }
    } catch (const YAML::ParserException& e) {
        failParse(source, e);
    }
    return root;
}

void requireMap(const Context& context, const YAML::Node& node, std::initializer_list<const char*> allowed) {
    if (!node.IsMap()) fail(context, node, "expected a mapping of keys to values");
    std::vector<std::pair<std::string, int>> seen;  // key, 1-based line
    for (const auto& entry : node) {
        if (!entry.first.IsScalar()) fail(context, entry.first, "expected a plain key");
        const std::string key = entry.first.Scalar();
        for (const auto& [other, line] : seen) {
            if (other == key) {
                fail(context / key, entry.first, "duplicate key (first given on line " + std::to_string(line) + ")");
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

double toNumber(const Context& context, const YAML::Node& node) {
    if (!node.IsScalar()) fail(context, node, "expected a number");
    const std::optional<double> value = parseDecimal(node.Scalar());
    if (!value) {
        // in a parametric robot file, an expression of its parameters (expression.hpp)
        if (const ExpressionEvaluator* expressions = activeExpressions();
            expressions != nullptr && !isDecimal(node.Scalar()) && looksLikeExpression(node.Scalar())) {
            std::string problem;
            const double result = expressions->evaluate(node.Scalar(), problem);
            if (!problem.empty()) fail(context, node, "expression '" + node.Scalar() + "': " + problem);
            return result;
        }
        fail(context, node, "'" + node.Scalar() + "' " + numberProblem(node.Scalar()));
    }
    return *value;
}

double requireNumber(const Context& context, const YAML::Node& map, const char* key) {
    const YAML::Node node = map[key];
    if (!node.IsDefined() || node.IsNull()) fail(context / key, map, "required number is missing");
    return toNumber(context / key, node);
}

double optionalNumber(const Context& context, const YAML::Node& map, const char* key, double fallback) {
    const YAML::Node node = map[key];
    if (!node.IsDefined()) return fallback;
    return toNumber(context / key, node);
}

void requireRange(const Context& context, const YAML::Node& map, const char* key, double value, double lo, double hi,
                  const char* unit) {
    if (value >= lo && value <= hi) return;
    const YAML::Node node = map[key];
    fail(context / key, node.IsDefined() ? node : map,
         "must be in [" + text::number(lo) + ", " + text::number(hi) + "] " + unit + ", got " + text::number(value));
}

std::string readFile(const std::string& path, const char* what) { return readRegularFile(path, what, kMaxYamlBytes); }

int lineOf(const YAML::Node& node) { return node.IsDefined() && node.Mark().line >= 0 ? node.Mark().line + 1 : 0; }

bool flag(const Context& context, const YAML::Node& map, const char* key) {
    const YAML::Node node = map[key];
    if (!node.IsDefined()) return false;
    if (node.IsScalar()) {
        const std::string& s = node.Scalar();
        if (s == "true") return true;
        if (s == "false") return false;
    }
    fail(context / key, node, "expected true or false");
}

}  // namespace nocdyn::io::detail
