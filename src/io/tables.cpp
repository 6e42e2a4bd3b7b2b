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

Table toTable(const PoseLoopResult& result) {
    Table table;
    table.columns = {"t", "theta_d", "x_d", "y_d", "theta", "x", "y", "e_theta", "e_x", "e_y"};
    for (const char* suffix : {"", "_d"}) {
        for (int a = 1; a <= result.actuators; ++a)
            table.columns.push_back(std::string("u").append(std::to_string(a)).append(suffix));
    }
    for (int a = 1; a <= result.actuators; ++a) table.columns.push_back(std::string("tau").append(std::to_string(a)));
    table.rows.reserve(result.t.size());
    for (std::size_t k = 0; k < result.t.size(); ++k) {
        const Pose& d = result.p_d[k];
        const Pose& p = result.p[k];
        std::vector<double> row{result.t[k], d(0), d(1), d(2), p(0), p(1), p(2), d(0) - p(0), d(1) - p(1), d(2) - p(2)};
        for (const auto* v : {&result.u, &result.u_d, &result.tau}) {
            for (int a = 0; a < result.actuators; ++a) row.push_back((*v)[k](a));
        }
        table.rows.push_back(std::move(row));
    }
    return table;
}

Table toTable(const Measurements& measurements) {
    Table table;
    const auto n = measurements.u.cols();
    const bool rates = measurements.du.size() > 0 && measurements.ddu.size() > 0;
    table.columns = {"t"};
    const auto append = [&](const char* quantity) {
        for (std::string& name : numbered(quantity, static_cast<int>(n))) table.columns.push_back(std::move(name));
    };
    append("u");
    append("tau");
    if (rates) {
        append("du");
        append("ddu");
    }
    for (std::size_t k = 0; k < measurements.t.size(); ++k) {
        const auto kk = static_cast<Eigen::Index>(k);
        std::vector<double> row{measurements.t[k]};
        for (Eigen::Index a = 0; a < n; ++a) row.push_back(measurements.u(kk, a));
        for (Eigen::Index a = 0; a < n; ++a) row.push_back(measurements.tau(kk, a));
        if (rates) {
            for (Eigen::Index a = 0; a < n; ++a) row.push_back(measurements.du(kk, a));
            for (Eigen::Index a = 0; a < n; ++a) row.push_back(measurements.ddu(kk, a));
        }
        table.rows.push_back(std::move(row));
    }
    return table;
}

}  // namespace nocdyn::io
