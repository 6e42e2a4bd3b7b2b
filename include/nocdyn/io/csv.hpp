// CSV tables of numbers: header line of column names, then rows of numbers, each written in
// the shortest decimal form that reads back as the same double (std::to_chars), so that doubles
// round-trip. Files are written through io::OutputFile (output.hpp): all or nothing.
#pragma once

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "nocdyn/io/output.hpp"

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
    /// Columns that hold categories: for column k with names, cell value c (an integer code) is
    /// written as the word categories[k][c] ("effort", not 2), so that a person reads the file.
    /// Empty (the default) or an empty entry: the column is written as numbers. Written only;
    /// the reader takes numbers.
    std::vector<std::vector<std::string>> categories = {};

    /// Index of a column; throws nocdyn::Error naming the column when it is absent.
    [[nodiscard]] std::size_t column(const std::string& name) const;
    /// Whether a column exists.
    [[nodiscard]] bool has(const std::string& name) const;
};

/// Room for one number: the shortest form of a double takes at most 24 characters
/// ("-2.2250738585072014e-308").
inline constexpr std::size_t kMaxNumberChars = 32;

/// Writes a table to a stream.
void writeCsv(std::ostream& out, const Table& table);

/// Writes a table to an output (throws nocdyn::Error for a non-finite number or a failed write).
void writeCsv(OutputFile& out, const Table& table);

/// Streams a CSV table row by row: the header when constructed, then one line per row().
/// Memory does not grow with the number of rows; row() does not allocate. With `background`,
/// rows are formatted and written by a second thread, a block of 1024 rows at a time, while
/// the caller computes the next ones. Call finish() before committing the output; a
/// CsvWriter dropped without it (an exception on the way) just stops.
class CsvWriter {
public:
    CsvWriter(OutputFile& out, std::vector<std::string> columns, bool background = false);
    ~CsvWriter();
    CsvWriter(const CsvWriter&) = delete;
    CsvWriter& operator=(const CsvWriter&) = delete;

    /// Appends a row. Throws nocdyn::Error naming the row and column for a value that is not
    /// finite (nothing non-finite is ever written), for a wrong number of values, or (with
    /// `background`) for the second thread's failure to write an earlier block.
    void row(std::span<const double> values);
    /// Writes out every row appended so far; throws nocdyn::Error when a write failed.
    void finish();
    /// Rows appended so far.
    [[nodiscard]] std::size_t rows() const { return rows_; }

private:
    struct Worker;
    void format(const std::vector<double>& values);  ///< whole rows, into out_
    void handOff();

    OutputFile& out_;
    std::vector<std::string> columns_;
    std::size_t rows_ = 0;
    std::vector<double> row_;  ///< the row being formatted, without `background`
    std::unique_ptr<Worker> worker_;
};

/// Writes a table to a file atomically (OutputFile: exclusive temporary file, then rename): on
/// failure no partial file is left behind. Throws nocdyn::Error.
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

/// One row of a CSV file as the row-by-row reader hands it over: the values (valid during
/// the call only) and the row's 1-based line in the file.
using CsvRowHandler = std::function<void(std::span<const double> values, std::size_t line)>;

/// parseCsv without the table: the header's columns go to `header` before the first row, then
/// each row to `row`, so that the caller keeps only what it needs (memory does not grow with
/// the rows here). The same checks and errors as parseCsv.
void parseCsvRows(std::string_view text, const std::string& source,
                  const std::function<void(const std::vector<std::string>& columns)>& header, const CsvRowHandler& row);

/// parseCsvRows on a regular file of at most 256 MiB (as readCsvFile).
void readCsvFileRows(const std::string& path,
                     const std::function<void(const std::vector<std::string>& columns)>& header,
                     const CsvRowHandler& row);

/// Writes text to a file atomically (OutputFile). Throws nocdyn::Error.
void writeTextFile(const std::string& path, const std::string& text);

}  // namespace nocdyn::io
