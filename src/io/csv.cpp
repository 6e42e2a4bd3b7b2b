// CSV tables (see csv.hpp).
#include "nocdyn/io/csv.hpp"

#include <cerrno>
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
