// Helpers shared by the YAML readers: strict maps (unknown keys are errors) and numbers
// with the file, line and field named in every error.
#pragma once

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <string>

#include "nocdyn/io/short_form.hpp"

namespace nocdyn::io::detail {

/// Where a field sits: source (file) name and dotted path, e.g. "geometry.link_length".
struct Context {
    const std::string& source;
    std::string field;
    [[nodiscard]] Context operator/(const std::string& key) const {
        return {source, field.empty() ? key : field + "." + key};
    }
};

/// Throws nocdyn::Error "SOURCE:LINE: FIELD: reason" (LINE 1-based, omitted when unknown).
[[noreturn]] void fail(const Context& context, const YAML::Node& node, const std::string& reason);

/// Loads YAML text, turning parser errors into nocdyn::Error with the line.
[[nodiscard]] YAML::Node loadDocument(const std::string& text, const std::string& source);

/// Requires a mapping whose keys are all in `allowed`.
void requireMap(const Context& context, const YAML::Node& node, std::initializer_list<const char*> allowed);

/// The finite number a scalar node holds.
[[nodiscard]] double toNumber(const Context& context, const YAML::Node& node);

/// A required finite number at node[key].
[[nodiscard]] double requireNumber(const Context& context, const YAML::Node& map, const char* key);

/// An optional finite number at node[key], else `fallback`.
[[nodiscard]] double optionalNumber(const Context& context, const YAML::Node& map, const char* key, double fallback);

/// The 1-based file line of a node, 0 when it has none.
[[nodiscard]] int lineOf(const YAML::Node& node);

/// An optional boolean at map[key] (false when absent); anything but true or false fails.
[[nodiscard]] bool flag(const Context& context, const YAML::Node& map, const char* key);

/// Fails "FIELD: must be in [lo, hi] UNIT, got V" at map[key] unless lo <= value <= hi.
void requireRange(const Context& context, const YAML::Node& map, const char* key, double value, double lo, double hi,
                  const char* unit);

/// Reads a whole regular file of at most kMaxYamlBytes (4 MiB); throws nocdyn::Error when it
/// cannot, naming the file and why (missing, not a regular file, too large).
[[nodiscard]] std::string readFile(const std::string& path, const char* what);

/// The paper's 3-PRR short form (robot_yaml.hpp) from its parsed root, expressions resolved.
[[nodiscard]] RobotParameters parseShortForm(const YAML::Node& root, const std::string& source);

}  // namespace nocdyn::io::detail
