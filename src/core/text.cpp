#include "nocdyn/text.hpp"

#include <charconv>
#include <clocale>
#include <cstdarg>
#include <cstdio>
#include <locale.h>  // newlocale, uselocale (POSIX)

namespace nocdyn::text {

std::string shortest(double value) {
    char buffer[40];
    return {buffer, shortest(buffer, buffer + sizeof buffer, value)};
}

std::size_t shortest(char* first, char* last, double value) {
    const auto result = std::to_chars(first, last, value);
    return static_cast<std::size_t>(result.ptr - first);
}

namespace {

/// The "C" locale, made once for the process (newlocale is thread-safe; the handle is never
/// freed, as the process may format until its end).
locale_t cLocale() {
    static const locale_t c = newlocale(LC_ALL_MASK, "C", static_cast<locale_t>(nullptr));
    return c;
}

/// Selects the "C" locale for the calling thread while it lives.
class ThreadCLocale {
public:
    ThreadCLocale() : previous_(cLocale() ? uselocale(cLocale()) : static_cast<locale_t>(nullptr)) {}
    ~ThreadCLocale() {
        if (previous_) uselocale(previous_);
    }
    ThreadCLocale(const ThreadCLocale&) = delete;
    ThreadCLocale& operator=(const ThreadCLocale&) = delete;

private:
    locale_t previous_;
};

}  // namespace

std::string format(const char* pattern, ...) {
    const ThreadCLocale c_locale;
    char buffer[512];
    std::va_list args;
    va_start(args, pattern);
    const int n = std::vsnprintf(buffer, sizeof buffer, pattern, args);
    va_end(args);
    if (n < 0) return {};
    if (static_cast<std::size_t>(n) < sizeof buffer) return {buffer, static_cast<std::size_t>(n)};
    // Longer than the buffer (a long name in a row): format again into a string of its size.
    std::string out(static_cast<std::size_t>(n), '\0');
    va_start(args, pattern);
    std::vsnprintf(out.data(), out.size() + 1, pattern, args);
    va_end(args);
    return out;
}

std::string significant(double value, int digits) { return format("%.*g", digits, value); }

std::string number(double value) { return significant(value, 6); }

std::string precise(double value) { return significant(value, 10); }

std::string allDigits(double value) { return significant(value, 17); }

std::string seconds(double t) { return significant(t, 9); }

std::string sampleTime(double t) { return "t = " + seconds(t) + " s"; }

}  // namespace nocdyn::text
