// A command's table handed over row by row: the command line formats each row as it comes
// (memory does not grow with the sample count), Python and tests keep them in one array.
#pragma once

#include <span>
#include <string>
#include <vector>

namespace nocdyn::app {

/// Receives a table: its columns once, then its rows in order.
class TableSink {
public:
    TableSink() = default;
    TableSink(const TableSink&) = default;
    TableSink& operator=(const TableSink&) = default;
    TableSink(TableSink&&) = default;
    TableSink& operator=(TableSink&&) = default;
    virtual ~TableSink() = default;
    virtual void columns(const std::vector<std::string>& names) = 0;
    /// One row, as many values as columns.
    virtual void row(std::span<const double> values) = 0;
};

/// Keeps the whole table: names, and the values row after row (row-major, C order).
class TableCollector final : public TableSink {
public:
    void columns(const std::vector<std::string>& names) override { names_ = names; }
    void row(std::span<const double> values) override { values_.insert(values_.end(), values.begin(), values.end()); }

    [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
    [[nodiscard]] std::size_t rows() const { return names_.empty() ? 0 : values_.size() / names_.size(); }
    /// The values row after row; moved out for a zero-copy hand-over.
    [[nodiscard]] std::vector<double>& values() { return values_; }

private:
    std::vector<std::string> names_;
    std::vector<double> values_;
};

}  // namespace nocdyn::app
