// Force signals from CSV (forces.hpp): the columns t,tau1..taun read into a ForceSignal.
#include "nocdyn/tables/forces.hpp"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "nocdyn/error.hpp"

namespace nocdyn::tables {

// the io layer's tables, files and quoting, below this one
using io::readCsvFileRows;
using io::Table;

namespace {

/// A column tauK with K beyond the robot's actuators holds forces the robot would not apply:
/// refused, never ignored.
void requireNoExtraForces(const std::vector<std::string>& columns, int actuators, const std::string& source) {
    for (const std::string& c : columns) {
        if (c.size() < 4 || c.compare(0, 3, "tau") != 0) continue;
        if (c.find_first_not_of("0123456789", 3) != std::string::npos || c[3] == '0') continue;
        if (c.size() > 6 || std::stoi(c.substr(3)) > actuators) {
            std::ostringstream out;
            out << source << ": column '" << c << "': the robot has " << actuators << " actuators (forces tau1..tau"
                << actuators << ")";
            throw Error(out.str());
        }
    }
}

}  // namespace

ForceSignal forcesFromCsvFile(const std::string& path, int actuators, Interpolation interpolation, Table& first) {
    std::vector<std::size_t> column;
    std::vector<double> times, tau;
    first = Table{};
    readCsvFileRows(
        path,
        [&](const std::vector<std::string>& columns) {
            first.columns = columns;
            for (int a = 0; a <= actuators; ++a) {
                const std::string name = a == 0 ? std::string("t") : "tau" + std::to_string(a);
                const auto it = std::find(columns.begin(), columns.end(), name);
                if (it == columns.end()) {
                    std::ostringstream out;
                    out << path << ": missing column '" << name << "' (the robot has " << actuators
                        << " actuators: t,tau1..tau" << actuators << ")";
                    throw Error(out.str());
                }
                column.push_back(static_cast<std::size_t>(it - columns.begin()));
            }
            requireNoExtraForces(columns, actuators, path);
        },
        [&](std::span<const double> row, std::size_t line) {
            if (first.rows.empty()) {
                first.rows.emplace_back(row.begin(), row.end());
                first.lines.push_back(line);
            }
            const double t = row[column[0]];
            if (!times.empty() && !(t > times.back())) {
                std::ostringstream out;
                out.precision(17);
                out << path << ":" << line << ": column 't': t = " << t
                    << " s does not increase (previous row: " << times.back() << " s)";
                throw Error(out.str());
            }
            times.push_back(t);
            for (int a = 0; a < actuators; ++a) tau.push_back(row[column[static_cast<std::size_t>(a) + 1]]);
        });
    if (times.empty()) throw Error(path + ": no rows");
    return {std::move(times), std::move(tau), actuators, interpolation, path};
}

ForceSignal forcesFromTable(const Table& table, int actuators, Interpolation interpolation, const std::string& source) {
    std::vector<std::size_t> column;
    for (int a = 0; a <= actuators; ++a) {
        const std::string name = a == 0 ? std::string("t") : "tau" + std::to_string(a);
        if (!table.has(name)) {
            std::ostringstream out;
            out << source << ": missing column '" << name << "' (the robot has " << actuators
                << " actuators: t,tau1..tau" << actuators << ")";
            throw Error(out.str());
        }
        column.push_back(table.column(name));
    }
    requireNoExtraForces(table.columns, actuators, source);
    if (table.rows.empty()) throw Error(source + ": no rows");
    std::vector<double> times;
    std::vector<ActuatorVector> tau;
    times.reserve(table.rows.size());
    tau.reserve(table.rows.size());
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const auto& row = table.rows[r];
        const double t = row[column[0]];
        if (!times.empty() && !(t > times.back())) {
            std::ostringstream out;
            out.precision(17);
            out << source << ":";
            if (r < table.lines.size())
                out << table.lines[r];
            else
                out << " row " << r + 1;
            out << ": column 't': t = " << t << " s does not increase (previous row: " << times.back() << " s)";
            throw Error(out.str());
        }
        times.push_back(t);
        ActuatorVector f(actuators);
        for (int a = 0; a < actuators; ++a) f(a) = row[column[static_cast<std::size_t>(a) + 1]];
        tau.push_back(f);
    }
    return {std::move(times), tau, interpolation, source};
}

}  // namespace nocdyn::tables
