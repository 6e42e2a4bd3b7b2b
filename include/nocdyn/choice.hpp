// A choice among named values: an `enum class` and its one table of names. Each such enum E
// declares, in its own namespace, `constexpr std::span<const Choice<E>> choices(E)` listing
// every value once with the word a user writes for it; the command line's accepted words, the
// Python package's accepted strings, the messages and the files all read that table.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace nocdyn {

/// One value of an enum and its name.
template <class E>
struct Choice {
    E value;
    std::string_view name;
};

/// The name of `value` in its table (empty for a value not listed).
template <class E>
[[nodiscard]] constexpr std::string_view nameOf(E value) {
    for (const Choice<E>& choice : choices(E{})) {
        if (choice.value == value) return choice.name;
    }
    return {};
}

/// The value named `name`, if the table lists it.
template <class E>
[[nodiscard]] constexpr std::optional<E> choiceNamed(std::string_view name) {
    for (const Choice<E>& choice : choices(E{})) {
        if (choice.name == name) return choice.value;
    }
    return std::nullopt;
}

/// Every name of E, in the table's order.
template <class E>
[[nodiscard]] std::vector<std::string> choiceNames() {
    std::vector<std::string> out;
    for (const Choice<E>& choice : choices(E{})) out.emplace_back(choice.name);
    return out;
}

/// The names as a reader reads them: "a, b or c".
template <class E>
[[nodiscard]] std::string choiceList() {
    const std::vector<std::string> names = choiceNames<E>();
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
        out += names[i];
    }
    return out;
}

}  // namespace nocdyn
