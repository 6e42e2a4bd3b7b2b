// CSV layouts of the results (tables.hpp).
#include "nocdyn/io/tables.hpp"

namespace nocdyn::io {

std::vector<std::string> numbered(const std::string& prefix, int count) {
    std::vector<std::string> out;
    for (int i = 1; i <= count; ++i) out.push_back(prefix + std::to_string(i));
    return out;
}

std::vector<std::string> inverseDynamicsColumns(int actuators) {
    std::vector<std::string> columns{"t", "x", "y", "theta"};
    for (const char* quantity : {"u", "du", "ddu", "tau"}) {
        for (std::string& name : numbered(quantity, actuators)) columns.push_back(std::move(name));
    }
    columns.emplace_back("kinetic");
    return columns;
}

void inverseDynamicsRow(const InverseDynamicsSample& s, std::vector<double>& row) {
    const auto n = static_cast<std::size_t>(s.u.size());
    row.resize(5 + 4 * n);
    row[0] = s.t;
    row[1] = s.p(1);
    row[2] = s.p(2);
    row[3] = s.p(0);
    std::size_t c = 4;
    for (const ActuatorVector* v : {&s.u, &s.du, &s.ddu, &s.tau}) {
        for (std::size_t a = 0; a < n; ++a) row[c++] = (*v)(static_cast<Eigen::Index>(a));
    }
    row[c] = s.kinetic;
}

std::vector<std::string> reactionColumns(int limbs) {
    std::vector<std::string> columns;
    for (int i = 1; i <= limbs; ++i) {
        for (int k = 1; k <= 3; ++k) {
            const std::string stem = "limb" + std::to_string(i) + "_j" + std::to_string(k) + "_";
            for (const char* part : {"fx", "fy", "m"}) columns.push_back(stem + part);
        }
    }
    return columns;
}

void appendReactions(const Reactions& reactions, int limbs, std::vector<double>& row) {
    for (int i = 0; i < limbs; ++i) {
        for (const Vector3& r : reactions.joint[static_cast<std::size_t>(i)]) row.insert(row.end(), {r(0), r(1), r(2)});
    }
}

Table toTable(const InverseDynamicsSeries& series, int actuators) {
    Table table;
    table.columns = inverseDynamicsColumns(actuators);
    table.rows.reserve(series.samples.size());
    std::vector<double> row;
    for (const InverseDynamicsSample& s : series.samples) {
        inverseDynamicsRow(s, row);
        table.rows.push_back(row);
    }
    return table;
}

}  // namespace nocdyn::io
