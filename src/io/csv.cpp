// CSV tables (see csv.hpp).
#include "nocdyn/io/csv.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include "nocdyn/error.hpp"

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

/// Shortest decimal form that reads back as the same double (std::to_chars, no precision).
std::size_t formatNumber(char* first, char* last, double value) {
    const auto result = std::to_chars(first, last, value);
    return static_cast<std::size_t>(result.ptr - first);
}

}  // namespace

void writeCsv(std::ostream& out, const Table& table) {
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

CsvWriter::CsvWriter(OutputFile& out, std::vector<std::string> columns) : out_(out), columns_(std::move(columns)) {
    std::string header;
    for (std::size_t k = 0; k < columns_.size(); ++k) header += (k ? "," : "") + columns_[k];
    out_.write(header + "\n");
}

void CsvWriter::row(std::span<const double> values) {
    ++rows_;
    if (values.size() != columns_.size()) {
        throw Error("cannot write '" + out_.path() + "': row " + std::to_string(rows_) + " has " +
                    std::to_string(values.size()) + " values for " + std::to_string(columns_.size()) + " columns");
    }
    char* const start = out_.reserve(values.size() * (kMaxNumberChars + 1));
    char* cursor = start;
    for (std::size_t k = 0; k < values.size(); ++k) {
        if (!std::isfinite(values[k])) {
            throw Error("cannot write '" + out_.path() + "': row " + std::to_string(rows_) + ", column '" +
                        columns_[k] + "' is not a finite number");
        }
        if (k) *cursor++ = ',';
        cursor += formatNumber(cursor, cursor + kMaxNumberChars, values[k]);
    }
    *cursor++ = '\n';
    out_.commitReserved(static_cast<std::size_t>(cursor - start));
}

void writeCsvFile(const std::string& path, const Table& table) {
    OutputFile out(path);
    writeCsv(out, table);
    out.commit();
}

void writeCsv(OutputFile& out, const Table& table) {
    CsvWriter csv(out, table.columns);
    for (const auto& row : table.rows) csv.row(row);
}

void writeTextFile(const std::string& path, const std::string& text) {
    OutputFile out(path);
    out.write(text);
    out.commit();
}

namespace {

std::vector<std::string> splitLine(const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream in(line);
    while (std::getline(in, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    return cells;
}

std::string trim(const std::string& s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return {};
    const auto last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
}

}  // namespace

Table readCsvFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error("cannot open CSV file '" + path + "'");
    Table table;
    std::string line;
    std::size_t line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        if (trim(line).empty()) continue;
        std::vector<std::string> cells = splitLine(line);
        if (table.columns.empty()) {
            for (auto& c : cells) table.columns.push_back(trim(c));
            continue;
        }
        if (cells.size() != table.columns.size()) {
            throw Error(path + ":" + std::to_string(line_number) + ": expected " +
                        std::to_string(table.columns.size()) + " values, found " +
                        std::to_string(cells.size()));
        }
        std::vector<double> row;
        row.reserve(cells.size());
        for (std::size_t k = 0; k < cells.size(); ++k) {
            const std::string text = trim(cells[k]);
            char* end = nullptr;
            errno = 0;
            const double value = std::strtod(text.c_str(), &end);
            if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value)) {
                throw Error(path + ":" + std::to_string(line_number) + ": column '" + table.columns[k] +
                            "': '" + text + "' is not a finite number");
            }
            row.push_back(value);
        }
        table.rows.push_back(std::move(row));
    }
    if (table.columns.empty()) throw Error("CSV file '" + path + "' is empty");
    return table;
}

}  // namespace nocdyn::io
