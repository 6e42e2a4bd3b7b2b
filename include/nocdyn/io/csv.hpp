// CSV tables of numbers: header line of column names, then rows written with 17
// significant digits so that doubles round-trip.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace nocdyn::io {

/// Limits of the CSV reader (the file itself is capped at 256 MiB).
inline constexpr std::size_t kMaxCsvColumns = 256;
inline constexpr std::size_t kMaxCsvRows = 10'000'000;
inline constexpr std::size_t kMaxCsvLineBytes = 65536;

struct Table {
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;
    /// 1-based line of each row in the file it was read from (empty for a table built in code).
    std::vector<std::size_t> lines = {};

    /// Index of a column; throws nocdyn::Error naming the column when it is absent.
    [[nodiscard]] std::size_t column(const std::string& name) const;
    /// Whether a column exists.
    [[nodiscard]] bool has(const std::string& name) const;
};

/// Writes a table to a stream.
void writeCsv(std::ostream& out, const Table& table);

/// Writes a table to a file atomically (temporary file, then rename): on failure no
/// partial file is left behind. Throws nocdyn::Error.
void writeCsvFile(const std::string& path, const Table& table);

/// Reads a numeric CSV table from a regular file of at most 256 MiB. Throws nocdyn::Error
/// "FILE:LINE: reason" for a missing, special or oversized file and for what parseCsv refuses.
[[nodiscard]] Table readCsvFile(const std::string& path);

/// Parses CSV text (`source` names it in errors): a header of distinct non-empty column names,
/// then rows of exactly as many finite decimal numbers (no hex, inf or nan). A leading UTF-8
/// byte order mark is skipped; blank lines are skipped but counted, so that every error names
/// the text's real line. At most kMaxCsvColumns columns, kMaxCsvRows rows and lines of
/// kMaxCsvLineBytes bytes. Throws nocdyn::Error "SOURCE:LINE: reason".
[[nodiscard]] Table parseCsv(std::string_view text, const std::string& source);

/// Writes text to a file atomically. Throws nocdyn::Error.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace nocdyn::io
