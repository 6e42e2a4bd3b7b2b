// Reading input files safely: regular files only (a device, FIFO or directory is refused
// before it is read), a size cap, and strict numbers. Shared by the YAML and CSV readers.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace nocdyn::io::detail {

/// Largest robot or trajectory file read [bytes].
inline constexpr std::size_t kMaxYamlBytes = std::size_t{4} << 20;  // 4 MiB
/// Largest CSV file read [bytes].
inline constexpr std::size_t kMaxCsvBytes = std::size_t{256} << 20;  // 256 MiB

/// The whole content of the regular file at `path` (symlinks to regular files are followed).
/// Throws nocdyn::Error "cannot open WHAT 'PATH': reason", "... is not a regular file" or
/// "... is larger than the N MiB accepted" without reading more than max_bytes + 1 bytes.
[[nodiscard]] std::string readRegularFile(const std::string& path, const char* what, std::size_t max_bytes);

/// Removes a leading UTF-8 byte order mark (EF BB BF); returns whether there was one.
bool stripByteOrderMark(std::string_view& text);

/// A decimal floating-point number: optional sign, digits with an optional '.', an optional
/// exponent; nothing else (no hex, no inf or nan, no surrounding spaces). std::nullopt when the
/// text is not such a number or is beyond the range of a double (above 1.8e308, or nonzero
/// below the smallest subnormal, 4.9e-324). Subnormal values are kept.
[[nodiscard]] std::optional<double> parseDecimal(std::string_view text);

/// Whether `text` follows parseDecimal's grammar (whatever its magnitude).
[[nodiscard]] bool isDecimal(std::string_view text);

/// Why parseDecimal refused `text`, for messages: "is not a finite decimal number (...)" or
/// "is beyond the range of a double (...)".
[[nodiscard]] std::string numberProblem(std::string_view text);

}  // namespace nocdyn::io::detail
