// CSV tables (see csv.hpp).
#include "nocdyn/io/csv.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include "file_util.hpp"
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

void writeCsv(std::ostream& out, const Table& table) {
    for (std::size_t k = 0; k < table.columns.size(); ++k) out << (k ? "," : "") << table.columns[k];
    out << '\n';
    char cell[32];
    for (const auto& row : table.rows) {
        for (std::size_t k = 0; k < row.size(); ++k) {
            std::snprintf(cell, sizeof cell, "%.17g", row[k]);
            if (k) out << ',';
            out << cell;
        }
        out << '\n';
    }
}

namespace {

template <typename Writer>
void writeAtomically(const std::string& path, Writer&& write) {
    const std::filesystem::path target(path);
    const std::filesystem::path temporary = target.string() + ".partial";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) throw Error("cannot write '" + path + "'");
        write(out);
        out.flush();
        if (!out) {
            out.close();
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw Error("cannot write '" + path + "'");
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, target, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw Error("cannot write '" + path + "'");
    }
}

}  // namespace

void writeCsvFile(const std::string& path, const Table& table) {
    writeAtomically(path, [&](std::ostream& out) { writeCsv(out, table); });
}

void writeTextFile(const std::string& path, const std::string& text) {
    writeAtomically(path, [&](std::ostream& out) { out << text; });
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

Table parseCsv(std::string_view text, const std::string& source) {
    detail::stripByteOrderMark(text);
    Table table;
    std::vector<std::string_view> cells;
    std::size_t line_number = 0;
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
        if (table.columns.empty()) {
            if (cells.size() > kMaxCsvColumns) {
                throw Error(at(line_number) + std::to_string(cells.size()) + " columns, at most " +
                            std::to_string(kMaxCsvColumns) + " accepted");
            }
            for (const std::string_view c : cells) {
                const std::string name(c);
                if (name.empty()) throw Error(at(line_number) + "empty column name in the header");
                if (table.has(name)) throw Error(at(line_number) + "column '" + name + "' appears twice in the header");
                table.columns.push_back(name);
            }
            continue;
        }
        if (cells.size() != table.columns.size()) {
            throw Error(at(line_number) + "expected " + std::to_string(table.columns.size()) + " values, found " +
                        std::to_string(cells.size()));
        }
        if (table.rows.size() >= kMaxCsvRows) {
            throw Error(at(line_number) + "more than " + std::to_string(kMaxCsvRows) + " rows");
        }
        std::vector<double> row(cells.size());
        for (std::size_t k = 0; k < cells.size(); ++k) {
            const std::optional<double> value = detail::parseDecimal(cells[k]);
            if (!value) {
                throw Error(at(line_number) + "column '" + table.columns[k] + "': '" + std::string(cells[k]) + "' " +
                            detail::numberProblem(cells[k]));
            }
            row[k] = *value;
        }
        table.rows.push_back(std::move(row));
        table.lines.push_back(line_number);
    }
    if (table.columns.empty()) throw Error("CSV file '" + source + "' is empty");
    return table;
}

Table readCsvFile(const std::string& path) {
    const std::string text = detail::readRegularFile(path, "CSV file", detail::kMaxCsvBytes);
    return parseCsv(text, path);
}

}  // namespace nocdyn::io
