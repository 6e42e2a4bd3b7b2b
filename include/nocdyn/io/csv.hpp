// CSV tables of numbers: header line of column names, then rows written with 17
// significant digits so that doubles round-trip.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace nocdyn::io {

struct Table {
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;

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

/// Reads a numeric CSV table. Throws nocdyn::Error "FILE:LINE: reason" for a missing
/// file, a ragged row, or a cell that is not a finite number.
[[nodiscard]] Table readCsvFile(const std::string& path);

/// Writes text to a file atomically. Throws nocdyn::Error.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace nocdyn::io
