// CSV tables (see csv.hpp).
#include "nocdyn/io/csv.hpp"

#include <algorithm>

#include <cerrno>
#include <charconv>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include "file_util.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::io {

std::size_t Table::column(const std::string& name) const {
    for (std::size_t k = 0; k < columns.size(); ++k) {
        if (columns[k] == name) return k;
    }
    throw Error("CSV table has no column '" + name + "'");
}

bool Table::has(const std::string& name) const {
    for (const std::string& c : columns) {
        if (c == name) return true;
    }
    return false;
}

namespace {

/// Shortest decimal form that reads back as the same double.
std::size_t formatNumber(char* first, char* last, double value) { return text::shortest(first, last, value); }

bool hasCategories(const Table& table) {
    for (const auto& names : table.categories) {
        if (!names.empty()) return true;
    }
    return false;
}

/// The whole table as text, category columns as their words (throws for a non-finite number or
/// a code with no name).
std::string formatWithCategories(const Table& table) {
    std::string text;
    for (std::size_t k = 0; k < table.columns.size(); ++k) text += (k ? "," : "") + table.columns[k];
    text += '\n';
    char cell[kMaxNumberChars];
    for (const auto& row : table.rows) {
        for (std::size_t k = 0; k < row.size(); ++k) {
            if (k) text += ',';
            const double value = row[k];
            if (!std::isfinite(value)) {
                throw Error("CSV column " + table.columns[k] + ": a non-finite number cannot be written");
            }
            if (k < table.categories.size() && !table.categories[k].empty()) {
                const auto& names = table.categories[k];
                if (value < 0.0 || value >= static_cast<double>(names.size()) || value != std::floor(value)) {
                    throw Error("CSV column " + table.columns[k] + ": no name for category " + std::to_string(value));
                }
                text += names[static_cast<std::size_t>(value)];
            } else {
                text.append(cell, formatNumber(cell, cell + sizeof cell, value));
            }
        }
        text += '\n';
    }
    return text;
}

}  // namespace

void writeCsv(std::ostream& out, const Table& table) {
    if (hasCategories(table)) {
        out << formatWithCategories(table);
        return;
    }
    for (std::size_t k = 0; k < table.columns.size(); ++k) out << (k ? "," : "") << table.columns[k];
    out << '\n';
    char cell[kMaxNumberChars];
    for (const auto& row : table.rows) {
        for (std::size_t k = 0; k < row.size(); ++k) {
            if (k) out << ',';
            out.write(cell, static_cast<std::streamsize>(formatNumber(cell, cell + sizeof cell, row[k])));
        }
        out << '\n';
    }
}

/// The second thread of a background CsvWriter and the blocks of rows handed to it.
struct CsvWriter::Worker {
    static constexpr std::size_t kBlockRows = 1024;
    std::thread thread;
    std::mutex mutex;
    std::condition_variable changed;
    std::vector<double> filling;  ///< rows being added by the caller
    std::vector<double> pending;  ///< rows being formatted by the worker
    bool has_work = false;        ///< `pending` holds rows not yet written
    bool stop = false;
    std::exception_ptr error;  ///< the worker's first failure, rethrown to the caller
};

CsvWriter::CsvWriter(OutputFile& out, std::vector<std::string> columns, bool background)
    : out_(out), columns_(std::move(columns)) {
    std::string header;
    for (std::size_t k = 0; k < columns_.size(); ++k) header += (k ? "," : "") + columns_[k];
    out_.write(header + "\n");
    if (!background) return;
    worker_ = std::make_unique<Worker>();
    worker_->filling.reserve(Worker::kBlockRows * columns_.size());
    worker_->pending.reserve(Worker::kBlockRows * columns_.size());
    worker_->thread = std::thread([this] {
        Worker& w = *worker_;
        std::unique_lock lock(w.mutex);
        while (true) {
            w.changed.wait(lock, [&] { return w.has_work || w.stop; });
            if (!w.has_work) return;
            lock.unlock();
            try {
                if (!w.error) format(w.pending);
            } catch (...) {
                w.error = std::current_exception();
            }
            lock.lock();
            w.pending.clear();
            w.has_work = false;
            w.changed.notify_all();
        }
    });
}

CsvWriter::~CsvWriter() {
    if (!worker_) return;
    {
        const std::lock_guard lock(worker_->mutex);
        worker_->stop = true;
    }
    worker_->changed.notify_all();
    worker_->thread.join();
}

void CsvWriter::format(const std::vector<double>& values) {
    const std::size_t n = columns_.size();
    for (std::size_t first = 0; first < values.size(); first += n) {
        char* const start = out_.reserve(n * (kMaxNumberChars + 1));
        char* cursor = start;
        for (std::size_t k = 0; k < n; ++k) {
            if (k) *cursor++ = ',';
            cursor += formatNumber(cursor, cursor + kMaxNumberChars, values[first + k]);
        }
        *cursor++ = '\n';
        out_.commitReserved(static_cast<std::size_t>(cursor - start));
    }
}

void CsvWriter::handOff() {
    Worker& w = *worker_;
    std::unique_lock lock(w.mutex);
    w.changed.wait(lock, [&] { return !w.has_work; });
    if (w.error) std::rethrow_exception(w.error);
    std::swap(w.filling, w.pending);
    w.has_work = !w.pending.empty();
    lock.unlock();
    w.changed.notify_all();
}

void CsvWriter::row(std::span<const double> values) {
    ++rows_;
    if (values.size() != columns_.size()) {
        throw Error("cannot write '" + out_.path() + "': row " + std::to_string(rows_) + " has " +
                    std::to_string(values.size()) + " values for " + std::to_string(columns_.size()) + " columns");
    }
    for (std::size_t k = 0; k < values.size(); ++k) {
        if (!std::isfinite(values[k])) {
            throw Error("cannot write '" + out_.path() + "': row " + std::to_string(rows_) + ", column '" +
                        columns_[k] + "' is not a finite number");
        }
    }
    if (!worker_) {
        row_.assign(values.begin(), values.end());
        format(row_);
        return;
    }
    worker_->filling.insert(worker_->filling.end(), values.begin(), values.end());
    if (worker_->filling.size() == Worker::kBlockRows * columns_.size()) handOff();
}

void CsvWriter::finish() {
    if (!worker_) return;
    handOff();  // the last, partial block
    handOff();  // waits until it is written; rethrows the worker's failure
}

void writeCsvFile(const std::string& path, const Table& table) {
    OutputFile out(path);
    writeCsv(out, table);
    out.commit();
}

void writeCsv(OutputFile& out, const Table& table) {
    if (hasCategories(table)) {
        out.write(formatWithCategories(table));
        return;
    }
    CsvWriter csv(out, table.columns);
    for (const auto& row : table.rows) csv.row(row);
    csv.finish();
}

void writeTextFile(const std::string& path, const std::string& text) {
    OutputFile out(path);
    out.write(text);
    out.commit();
}

namespace {

std::string_view trim(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    const auto last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
}

/// The cells of one line, split at every comma (a trailing comma makes an empty last cell).
void splitLine(std::string_view line, std::vector<std::string_view>& cells) {
    cells.clear();
    for (;;) {
        const auto comma = line.find(',');
        cells.push_back(trim(line.substr(0, comma)));
        if (comma == std::string_view::npos) return;
        line.remove_prefix(comma + 1);
    }
}

}  // namespace

void parseCsvRows(std::string_view text, const std::string& source,
                  const std::function<void(const std::vector<std::string>& columns)>& header,
                  const CsvRowHandler& row_handler) {
    detail::stripByteOrderMark(text);
    std::vector<std::string> columns;
    std::vector<std::string_view> cells;
    std::vector<double> row;
    std::size_t line_number = 0, rows = 0;
    auto at = [&](std::size_t line) { return source + ":" + std::to_string(line) + ": "; };
    while (!text.empty()) {
        const auto newline = text.find('\n');
        const std::string_view line = text.substr(0, newline);
        text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
        ++line_number;
        if (line.size() > kMaxCsvLineBytes) {
            throw Error(at(line_number) + "line longer than " + std::to_string(kMaxCsvLineBytes) + " bytes");
        }
        if (trim(line).empty()) continue;
        splitLine(line, cells);
        if (columns.empty()) {
            if (cells.size() > kMaxCsvColumns) {
                throw Error(at(line_number) + std::to_string(cells.size()) + " columns, at most " +
                            std::to_string(kMaxCsvColumns) + " accepted");
            }
            for (const std::string_view c : cells) {
                const std::string name(c);
                if (name.empty()) throw Error(at(line_number) + "empty column name in the header");
                if (std::find(columns.begin(), columns.end(), name) != columns.end())
                    throw Error(at(line_number) + "column '" + name + "' appears twice in the header");
                columns.push_back(name);
            }
            header(columns);
            continue;
        }
        if (cells.size() != columns.size()) {
            throw Error(at(line_number) + "expected " + std::to_string(columns.size()) + " values, found " +
                        std::to_string(cells.size()));
        }
        if (rows >= kMaxCsvRows) {
            throw Error(at(line_number) + "more than " + std::to_string(kMaxCsvRows) + " rows");
        }
        row.resize(cells.size());
        for (std::size_t k = 0; k < cells.size(); ++k) {
            const std::optional<double> value = detail::parseDecimal(cells[k]);
            if (!value) {
                throw Error(at(line_number) + "column '" + columns[k] + "': '" + std::string(cells[k]) + "' " +
                            detail::numberProblem(cells[k]));
            }
            row[k] = *value;
        }
        ++rows;
        row_handler(row, line_number);
    }
    if (columns.empty()) throw Error("CSV file '" + source + "' is empty");
}

Table parseCsv(std::string_view text, const std::string& source) {
    Table table;
    parseCsvRows(
        text, source, [&](const std::vector<std::string>& columns) { table.columns = columns; },
        [&](std::span<const double> values, std::size_t line) {
            table.rows.emplace_back(values.begin(), values.end());
            table.lines.push_back(line);
        });
    return table;
}

void readCsvFileRows(const std::string& path,
                     const std::function<void(const std::vector<std::string>& columns)>& header,
                     const CsvRowHandler& row) {
    const std::string text = detail::readRegularFile(path, "CSV file", detail::kMaxCsvBytes);
    parseCsvRows(text, path, header, row);
}

Table readCsvFile(const std::string& path) {
    const std::string text = detail::readRegularFile(path, "CSV file", detail::kMaxCsvBytes);
    return parseCsv(text, path);
}

}  // namespace nocdyn::io
