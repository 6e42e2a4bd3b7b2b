// Arithmetic expressions in robot files: numbers, named parameters, + - * / ^, parentheses,
// sin cos tan asin acos atan atan2 sqrt abs min max and the constant pi (angles in radians),
// evaluated by muParser with every other function, constant and operator of its default set
// left out. Nothing is compiled or executed beyond muParser's own bytecode of these.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "nocdyn/io/robot_file.hpp"

namespace nocdyn::io::detail {

/// Whether `name` can name a parameter: a letter or '_' then letters, digits or '_', at most
/// 64 characters, and not a function's name or pi.
[[nodiscard]] bool isParameterName(const std::string& name);

/// Evaluates expressions over a set of named values.
class ExpressionEvaluator {
public:
    ExpressionEvaluator();
    ~ExpressionEvaluator();
    ExpressionEvaluator(const ExpressionEvaluator&) = delete;
    ExpressionEvaluator& operator=(const ExpressionEvaluator&) = delete;

    /// Defines (or redefines) a named value.
    void define(const std::string& name, double value);
    /// Whether `name` is defined.
    [[nodiscard]] bool defines(const std::string& name) const;
    /// The value of `text`, or the reason it has none ("unknown name 'r'", "the result is not
    /// finite", muParser's message for a syntax error).
    [[nodiscard]] double evaluate(const std::string& text, std::string& problem) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Evaluates the `parameters:` section of a robot file's root mapping into `evaluator` (in
/// order; a value may use the parameters above it), with `overrides` replacing declared values,
/// and removes the section. Throws nocdyn::Error "SOURCE:LINE: parameters.NAME: ..." and for an
/// override of a name the file does not declare. Returns the parameters with their final
/// values (empty when the file declares none).
ParameterSet declareParameters(YAML::Node root, const std::string& source, const ParameterSet& overrides,
                               ExpressionEvaluator& evaluator);

/// While it lives, the number reader (toNumber) of this thread evaluates a scalar that is not a
/// plain number as an expression over `evaluator`'s parameters; an error names the file, line,
/// field and the expression. A single word or malformed number (nan, inf, 0x10) is left to the
/// number reader's own message.
class ExpressionScope {
public:
    explicit ExpressionScope(const ExpressionEvaluator& evaluator);
    ~ExpressionScope();
    ExpressionScope(const ExpressionScope&) = delete;
    ExpressionScope& operator=(const ExpressionScope&) = delete;

private:
    const ExpressionEvaluator* previous_;
};

/// The evaluator of the innermost ExpressionScope of this thread, or nullptr.
[[nodiscard]] const ExpressionEvaluator* activeExpressions();

/// Whether the number reader should evaluate `text` as an expression (it is not one word or
/// malformed number).
[[nodiscard]] bool looksLikeExpression(const std::string& text);

}  // namespace nocdyn::io::detail
