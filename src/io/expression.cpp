// Arithmetic expressions in robot files (expression.hpp).
#include "expression.hpp"

#include <muParser.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <map>
#include <numbers>
#include <string_view>
#include <vector>

#include "file_util.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"
#include "yaml_util.hpp"

namespace nocdyn::io::detail {

namespace {

constexpr std::size_t kMaxNameLength = 64;
/// Longest expression accepted [characters].
constexpr std::size_t kMaxExpressionLength = 4096;
/// Most parameters a file may declare.
constexpr std::size_t kMaxParameters = 1000;

constexpr std::array<std::string_view, 13> kFunctions = {"sin",  "cos", "tan", "asin", "acos", "atan", "atan2",
                                                         "sqrt", "abs", "min", "max",  "pi",   ""};

bool isNameStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool isNameChar(char c) { return isNameStart(c) || (c >= '0' && c <= '9'); }

/// A value as a message shows it: nan without a sign (x86 gives sqrt(-1) the sign bit).
std::string shown(double value) { return std::isnan(value) ? std::string("nan") : text::shortest(value); }

/// The first sub-expression of the current evaluation whose value is not finite, written with
/// its operands' values ("sqrt(-1)", "1 / 0"); empty while every value so far is finite. A
/// later function (max, min, 1/x) could otherwise hide it: max(0, sqrt(-1)) or 1/(1/0).
thread_local std::string first_non_finite;

double checked(double value, const char* name, std::initializer_list<double> arguments) {
    if (!std::isfinite(value) && first_non_finite.empty()) {
        first_non_finite = name;
        first_non_finite += '(';
        bool first = true;
        for (const double a : arguments) {
            if (!first) first_non_finite += ", ";
            first_non_finite += shown(a);
            first = false;
        }
        first_non_finite += ") = " + shown(value);
    }
    return value;
}

double checkedBinary(double value, double a, const char* op, double b) {
    if (!std::isfinite(value) && first_non_finite.empty())
        first_non_finite = shown(a) + " " + op + " " + shown(b) + " = " + shown(value);
    return value;
}

}  // namespace

bool isParameterName(const std::string& name) {
    if (name.empty() || name.size() > kMaxNameLength || !isNameStart(name.front())) return false;
    for (const char c : name) {
        if (!isNameChar(c)) return false;
    }
    for (const std::string_view reserved : kFunctions) {
        if (!reserved.empty() && name == reserved) return false;
    }
    return true;
}

struct ExpressionEvaluator::Impl {
    mu::Parser parser;
    std::map<std::string, double> values;  // node-based: the addresses muParser holds stay valid
};

ExpressionEvaluator::ExpressionEvaluator() : impl_(std::make_unique<Impl>()) {
    mu::Parser& p = impl_->parser;
    // muParser's defaults (exp, log, sum, _e, ...) out; only the documented set back in
    p.ClearFun();
    p.ClearConst();
    p.ClearPostfixOprt();
    p.ClearInfixOprt();
    p.ClearOprt();
    // + - * / ^ as our own operators, so that every intermediate value is checked
    p.EnableBuiltInOprt(false);
    p.DefineOprt(
        "+", +[](double a, double b) { return checkedBinary(a + b, a, "+", b); }, mu::prADD_SUB);
    p.DefineOprt(
        "-", +[](double a, double b) { return checkedBinary(a - b, a, "-", b); }, mu::prADD_SUB);
    p.DefineOprt(
        "*", +[](double a, double b) { return checkedBinary(a * b, a, "*", b); }, mu::prMUL_DIV);
    p.DefineOprt(
        "/", +[](double a, double b) { return checkedBinary(a / b, a, "/", b); }, mu::prMUL_DIV);
    p.DefineOprt(
        "^", +[](double a, double b) { return checkedBinary(std::pow(a, b), a, "^", b); }, mu::prPOW, mu::oaRIGHT);
    p.DefineInfixOprt(
        "-", +[](double x) { return -x; });
    p.DefineInfixOprt(
        "+", +[](double x) { return x; });
    p.DefineFun(
        "sin", +[](double x) { return checked(std::sin(x), "sin", {x}); });
    p.DefineFun(
        "cos", +[](double x) { return checked(std::cos(x), "cos", {x}); });
    p.DefineFun(
        "tan", +[](double x) { return checked(std::tan(x), "tan", {x}); });
    p.DefineFun(
        "asin", +[](double x) { return checked(std::asin(x), "asin", {x}); });
    p.DefineFun(
        "acos", +[](double x) { return checked(std::acos(x), "acos", {x}); });
    p.DefineFun(
        "atan", +[](double x) { return checked(std::atan(x), "atan", {x}); });
    p.DefineFun(
        "atan2", +[](double y, double x) {
            return checked(std::atan2(y, x), "atan2", {y, x});
        });
    p.DefineFun(
        "sqrt", +[](double x) { return checked(std::sqrt(x), "sqrt", {x}); });
    p.DefineFun(
        "abs", +[](double x) { return checked(std::abs(x), "abs", {x}); });
    p.DefineFun(
        "min", +[](double a, double b) {
            return checked(std::min(a, b), "min", {a, b});
        });
    p.DefineFun(
        "max", +[](double a, double b) {
            return checked(std::max(a, b), "max", {a, b});
        });
    p.DefineConst("pi", std::numbers::pi);
}

ExpressionEvaluator::~ExpressionEvaluator() = default;

void ExpressionEvaluator::define(const std::string& name, double value) {
    auto [it, inserted] = impl_->values.insert_or_assign(name, value);
    if (inserted) impl_->parser.DefineVar(name, &it->second);
}

bool ExpressionEvaluator::defines(const std::string& name) const { return impl_->values.count(name) != 0; }

double ExpressionEvaluator::evaluate(const std::string& text, std::string& problem) const {
    problem.clear();
    if (text.size() > kMaxExpressionLength) {
        problem = "longer than " + std::to_string(kMaxExpressionLength) + " characters";
        return 0.0;
    }
    // Only the documented grammar reaches muParser: its comparison, logical, assignment and
    // ternary operators (and any name not defined here) are refused first. A comma is allowed
    // only between a function's arguments: muParser would read "1,75257" as a list and keep
    // its last value, so a decimal comma would silently become 75257.
    std::vector<bool> call_parentheses;  // per open parenthesis: whether it follows a function
    bool after_function = false;
    for (std::size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (c == '(') {
            call_parentheses.push_back(after_function);
        } else if (c == ')') {
            if (!call_parentheses.empty()) call_parentheses.pop_back();
        } else if (c == ',' && (call_parentheses.empty() || !call_parentheses.back())) {
            problem = "a comma outside a function's argument list (write decimals with a point: 1.5, not 1,5)";
            return 0.0;
        }
        if (c != ' ' && c != '\t') after_function = false;
        if (isNameStart(c)) {
            std::size_t end = i;
            while (end < text.size() && isNameChar(text[end])) ++end;
            const std::string name = text.substr(i, end - i);
            bool known = impl_->values.count(name) != 0;
            for (const std::string_view f : kFunctions) known = known || (!f.empty() && name == f);
            after_function = std::find(kFunctions.begin(), kFunctions.end(), name) != kFunctions.end() && name != "pi";
            if (!known) {
                problem = "unknown name '" + name +
                          "' (not a parameter, pi or one of the functions sin cos tan "
                          "asin acos atan atan2 sqrt abs min max)";
                return 0.0;
            }
            i = end;
            continue;
        }
        if (c >= '0' && c <= '9') {  // a number, its exponent included (1.5e-3)
            while (i < text.size() &&
                   (isNameChar(text[i]) || text[i] == '.' ||
                    ((text[i] == '-' || text[i] == '+') && (text[i - 1] == 'e' || text[i - 1] == 'E'))))
                ++i;
            continue;
        }
        if (std::string_view(" \t.+-*/^(),").find(c) == std::string_view::npos) {
            problem = std::string("character '") + (c >= 32 && c < 127 ? std::string(1, c) : std::string("?")) +
                      "' is not part of an expression (numbers, parameters, + - * / ^, parentheses, functions)";
            return 0.0;
        }
        ++i;
    }
    double value = 0.0;
    first_non_finite.clear();
    try {
        impl_->parser.SetExpr(text);
        value = impl_->parser.Eval();
    } catch (const mu::Parser::exception_type& e) {
        // muParser calls a sign with nothing after it ("+", "1*-") an internal error
        problem = e.GetCode() == mu::ecINTERNAL_ERROR
                      ? std::string("the expression ends with a sign that has no number after it")
                      : e.GetMsg();
        return 0.0;
    }
    if (!first_non_finite.empty()) {
        problem = "the sub-expression " + first_non_finite + " is not finite";
        return 0.0;
    }
    if (!std::isfinite(value)) problem = "the result is not finite (" + text::shortest(value) + ")";
    return value;
}

namespace {
thread_local const ExpressionEvaluator* active_evaluator = nullptr;
}  // namespace

ExpressionScope::ExpressionScope(const ExpressionEvaluator& evaluator) : previous_(active_evaluator) {
    active_evaluator = &evaluator;
}

ExpressionScope::~ExpressionScope() { active_evaluator = previous_; }

const ExpressionEvaluator* activeExpressions() { return active_evaluator; }

bool looksLikeExpression(const std::string& text) {
    return !std::all_of(text.begin(), text.end(), [](char c) { return isNameChar(c) || c == '.'; }) ||
           (active_evaluator != nullptr && active_evaluator->defines(text));
}

ParameterSet declareParameters(YAML::Node root, const std::string& source, const ParameterSet& overrides,
                               ExpressionEvaluator& evaluator) {
    ParameterSet declared;
    const Context top{source, ""};
    if (root.IsMap()) {
        if (const YAML::Node section = root["parameters"]; section.IsDefined()) {
            const Context here = top / "parameters";
            if (!section.IsMap()) fail(here, section, "expected a mapping of parameter names to values");
            if (section.size() > kMaxParameters)
                fail(here, section, "more than " + std::to_string(kMaxParameters) + " parameters");
            for (const auto& entry : section) {
                const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : std::string();
                if (!isParameterName(name)) {
                    fail(here, entry.first,
                         "'" + name +
                             "' cannot name a parameter (a letter or _ then letters, digits or _; not a "
                             "function's name or pi)");
                }
                for (const Parameter& other : declared) {
                    if (other.name == name) fail(here / name, entry.first, "declared twice");
                }
                if (!entry.second.IsScalar()) fail(here / name, entry.second, "expected a number or an expression");
                double value = 0.0;
                if (const auto plain = parseDecimal(entry.second.Scalar())) {
                    value = *plain;
                } else {
                    std::string problem;
                    value = evaluator.evaluate(entry.second.Scalar(), problem);
                    if (!problem.empty())
                        fail(here / name, entry.second, "expression '" + entry.second.Scalar() + "': " + problem);
                }
                for (const Parameter& o : overrides) {
                    if (o.name == name) value = o.value;
                }
                evaluator.define(name, value);
                declared.push_back({name, value});
            }
            root.remove("parameters");
        }
    }
    for (const Parameter& o : overrides) {
        bool found = false;
        for (const Parameter& d : declared) found = found || d.name == o.name;
        if (!found) {
            std::string list;
            for (const Parameter& d : declared) list += (list.empty() ? "" : ", ") + d.name;
            throw Error(source + ": parameter '" + o.name + "' is set but the file declares " +
                        (list.empty() ? std::string("no parameters") : "only: " + list));
        }
        if (!std::isfinite(o.value)) throw Error(source + ": parameter '" + o.name + "' is set to a non-finite value");
    }
    return declared;
}

}  // namespace nocdyn::io::detail
