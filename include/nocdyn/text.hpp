// Numbers as text: the one formatter of the library, the command line and the reports.
//
// Every number a person or a program reads goes through here, so that it is the same in a
// summary, a message, a table, a figure's data file or a report, whatever the process's C
// locale: Python's locale.setlocale (or a host program) may set a decimal comma, and printf
// would then write 0,5 into a gnuplot data file or a summary. Both forms are independent of it:
//   - shortest: the shortest decimal that reads back as the same double (std::to_chars);
//   - format: printf's conversions (%.4g, %8.3f, %+.2e, %d, %s ...) in the "C" locale, chosen
//     for the calling thread alone (POSIX uselocale), so other threads are not disturbed.
#pragma once

#include <cstddef>
#include <string>

/// GCC/Clang check a format pattern against its arguments at compile time.
#define NOCDYN_PRINTF_FORMAT(pattern, first) __attribute__((format(printf, pattern, first)))

namespace nocdyn::text {

/// The shortest decimal that reads back as exactly `value` ("0.1", "1e-07", "inf", "nan").
[[nodiscard]] std::string shortest(double value);

/// The same into [first, last); the number of characters written (at most 32 are needed).
std::size_t shortest(char* first, char* last, double value);

/// `digits` significant digits, printf's %.<digits>g ("0.1", "1e-07", "12.35" at four).
[[nodiscard]] std::string significant(double value, int digits);

/// The named precisions, so that one kind of number reads the same wherever it is printed:
/// six significant digits (%g), a number in a message or a summary;
[[nodiscard]] std::string number(double value);
/// ten (%.10g), a value echoed back from the user's file, where six would not tell two apart;
[[nodiscard]] std::string precise(double value);
/// seventeen (%.17g), every digit of a double, for a file that is read back;
[[nodiscard]] std::string allDigits(double value);
/// nine (%.9g), a time [s]: samples at 10 kHz are told apart over 10^4 s.
[[nodiscard]] std::string seconds(double t);
/// "t = 0.0123 s": the sample time at the head of a message (seconds(t)).
[[nodiscard]] std::string sampleTime(double t);

/// printf-style formatting in the "C" locale, whatever the process's locale: a decimal point,
/// never a comma. The pattern is the program's own, never read from input.
[[nodiscard]] std::string format(const char* pattern, ...) NOCDYN_PRINTF_FORMAT(1, 2);

}  // namespace nocdyn::text
