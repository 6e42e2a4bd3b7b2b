// CSV layouts of the results (tables.hpp).
#include "nocdyn/tables/tables.hpp"

#include "nocdyn/io/layouts.hpp"

namespace nocdyn::tables {

// the io layer's tables, files and quoting, below this one
using io::columnNames;
using io::Table;
using io::TableId;

std::vector<std::string> numbered(const std::string& prefix, int count) {
    std::vector<std::string> out;
    for (int i = 1; i <= count; ++i) out.push_back(prefix + std::to_string(i));
    return out;
}

std::vector<std::string> inverseDynamicsColumns(int actuators, int task_dimension) {
    return columnNames(TableId::inverse_dynamics, {.actuators = actuators, .task_dimension = task_dimension});
}

void inverseDynamicsRow(const InverseDynamicsSample& s, std::vector<double>& row, int task_dimension) {
    const auto n = static_cast<std::size_t>(s.u.size());
    const bool theta = task_dimension == 3;  // a two-DOF robot's pose is [x, y]
    row.resize((theta ? 5 : 4) + 4 * n);
    row[0] = s.t;
    row[1] = s.p(1);
    row[2] = s.p(2);
    std::size_t c = 3;
    if (theta) row[c++] = s.p(0);
    for (const ActuatorVector* v : {&s.u, &s.du, &s.ddu, &s.tau}) {
        for (std::size_t a = 0; a < n; ++a) row[c++] = (*v)(static_cast<Eigen::Index>(a));
    }
    row[c] = s.kinetic;
}

std::vector<std::string> reactionColumns(int limbs) { return columnNames(TableId::reactions, {.limbs = limbs}); }

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

Table toTable(const PoseLoopResult& result, int task_dimension) {
    Table table;
    table.columns =
        columnNames(TableId::closed_loop, {.actuators = result.actuators, .task_dimension = task_dimension});
    table.rows.reserve(result.t.size());
    for (std::size_t k = 0; k < result.t.size(); ++k) {
        const Pose& d = result.p_d[k];  // (theta, x, y)
        const Pose& p = result.p[k];
        // x, y, then theta (none for a two-DOF robot) of the desired pose, the pose and the error
        const bool theta = task_dimension == 3;
        std::vector<double> row{result.t[k], d(1), d(2)};
        if (theta) row.push_back(d(0));
        row.insert(row.end(), {p(1), p(2)});
        if (theta) row.push_back(p(0));
        row.insert(row.end(), {d(1) - p(1), d(2) - p(2)});
        if (theta) row.push_back(d(0) - p(0));
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
    table.columns = columnNames(TableId::measurements, {.actuators = static_cast<int>(n), .optional = rates});
    if (measurements.held_forces) {
        // forces held from each sample to the next say so in their name: tau{a}_held
        for (std::string& name : table.columns) {
            if (name.starts_with("tau")) name += "_held";
        }
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

Table toTable(const std::vector<EnvelopePoint>& points, const EnvelopeResonance& resonance) {
    Table table;
    // axis and limit are written as words (EnvelopeAxis and EnvelopeLimit in order)
    table.categories = {{"theta", "x", "y"}, {}, {}, {"range", "velocity", "effort", "workspace", "none", "resonance"}};
    table.columns = columnNames(TableId::envelope, {.optional = resonance.known});
    for (const EnvelopePoint& p : points) {
        std::vector<double> row{static_cast<double>(p.axis),
                                p.frequency,
                                p.amplitude,
                                static_cast<double>(p.limit),
                                static_cast<double>(p.limb + 1),
                                static_cast<double>(p.joint + 1),
                                static_cast<double>(p.actuator + 1),
                                p.kinematic_amplitude,
                                p.peak_effort_ratio,
                                p.peak_u,
                                p.peak_tau};
        if (resonance.known) row.push_back(resonance.frequency);
        table.rows.push_back(std::move(row));
    }
    return table;
}

}  // namespace nocdyn::tables
