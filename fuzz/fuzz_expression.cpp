// libFuzzer harness of the expression evaluator of parametric robot files (expression.hpp): any
// text is either a finite value, the same at a second evaluation, or refused with a reason; an
// accepted expression holds no comma outside a function's argument list. Anything else (a crash,
// NaN or inf accepted, a decimal comma read as a list) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "expression.hpp"

namespace {

/// Whether `text` has a comma outside the parentheses of a call (a parenthesis right after a
/// name, blanks between allowed).
bool commaOutsideCall(const std::string& text) {
    std::vector<bool> call;  // per open parenthesis: whether a name stands right before it
    bool in_name = false;    // the last non-blank character ends a name
    for (const char c : text) {
        if (c == '(') call.push_back(in_name);
        if (c == ')' && !call.empty()) call.pop_back();
        if (c == ',' && (call.empty() || !call.back())) return true;
        const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
        const bool digit = c >= '0' && c <= '9';
        if (c != ' ' && c != '\t') in_name = letter || (digit && in_name);
    }
    return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* bytes, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(bytes), size);
    static nocdyn::io::detail::ExpressionEvaluator* evaluator = [] {
        auto* e = new nocdyn::io::detail::ExpressionEvaluator();
        e->define("a", 1.5);
        e->define("b", -2.0);
        e->define("zero", 0.0);
        e->define("big", 1e300);
        return e;
    }();
    std::string problem;
    const double value = evaluator->evaluate(text, problem);
    if (!problem.empty()) return 0;
    if (!std::isfinite(value)) std::abort();
    if (commaOutsideCall(text)) std::abort();
    std::string again;
    const double second = evaluator->evaluate(text, again);
    if (!again.empty() || second != value) std::abort();
    return 0;
}
