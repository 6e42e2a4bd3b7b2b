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
    /// The value of `text`, or the reason it has none ("unknown name 'r'", "the result is not
    /// finite", muParser's message for a syntax error).
    [[nodiscard]] double evaluate(const std::string& text, std::string& problem) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Evaluates the `parameters:` section of a robot file's root mapping (in order; a value may
/// use the parameters above it), with `overrides` replacing declared values, removes the
/// section, and replaces every scalar holding an expression by its value in shortest
/// round-trip decimal form. Scalars under `name` and `type`, plain numbers, true and false
/// are left alone, as is a single unknown word (the number reader reports it). Throws
/// nocdyn::Error "SOURCE:LINE: FIELD: expression 'TEXT': reason". Returns the parameters with
/// their final values (empty when the file declares none).
ParameterSet resolveExpressions(YAML::Node root, const std::string& source, const ParameterSet& overrides);

}  // namespace nocdyn::io::detail
