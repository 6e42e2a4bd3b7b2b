// The JSON of the animation pages (animation.hpp, animation3d.hpp): numbers written by
// text::format, names through nlohmann::json, the whole made safe inside a <script> element.
// Internal to the render module.
#pragma once

#include <string>
#include <type_traits>
#include <vector>

#include "nocdyn/text.hpp"

namespace nocdyn::render::detail {

/// Writes a JSON array of numbers in the shortest %g form of `digits` significant digits
/// (integers as they are).
template <class Range>
void appendArray(std::string& out, const Range& values, int digits) {
    out += '[';
    std::string number;
    bool first = true;
    for (const auto v : values) {
        if (!first) out += ',';
        first = false;
        if constexpr (std::is_integral_v<std::decay_t<decltype(v)>>) {
            number = text::format("%lld", static_cast<long long>(v));
        } else {
            number = text::format("%.*g", digits, static_cast<double>(v));
        }
        out += number;
    }
    out += ']';
}

/// JSON text safe inside a <script> element: '<', '>' and '&' only occur in JSON strings,
/// where their \u escapes mean the same, so no "</script>" or "<!--" can appear.
std::string scriptSafe(const std::string& json);

/// The plots of u and tau, {"t":[..],"u":[{"name":"u1","lo":[..],"hi":[..]},..],"tau":[..]}:
/// min and max of every one of at most kMaxPlotBuckets buckets of samples, so that no peak is
/// lost. u and tau hold sample k's actuator a at k * n + a; peak_tau receives each actuator's
/// largest absolute force.
std::string plotsJson(const std::vector<double>& t, const std::vector<double>& u, const std::vector<double>& tau, int n,
                      std::vector<double>& peak_tau);

}  // namespace nocdyn::render::detail
