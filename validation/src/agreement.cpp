// Our model against the independent engines for any robot (agreement.hpp).
#include "nocdyn/validation/agreement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "nocdyn/tables/tables.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/validation/mujoco_mechanism.hpp"
#include "nocdyn/validation/simbody_mechanism.hpp"

namespace nocdyn::validation {

namespace {

EngineAgreement agreement(const std::string& engine, const EngineComparison& c,
                          const std::vector<MechanismSample>& theirs) {
    EngineAgreement result;
    result.engine = engine;
    const auto n = static_cast<std::size_t>(c.actuators);
    result.max_abs.assign(n, 0.0);
    result.max_rel_peak.assign(n, 0.0);
    std::vector<double> peak(n, 0.0);
    for (std::size_t k = 0; k < c.ours.samples.size(); ++k) {
        const InverseDynamicsSample& ours = c.ours.samples[k];
        for (std::size_t a = 0; a < n; ++a) {
            const auto i = static_cast<Eigen::Index>(a);
            peak[a] = std::max(peak[a], std::abs(ours.tau(i)));
            result.max_abs[a] = std::max(result.max_abs[a], std::abs(theirs[k].tau(i) - ours.tau(i)));
            result.max_u_abs = std::max(result.max_u_abs, std::abs(theirs[k].u(i) - ours.u(i)));
        }
    }
    for (std::size_t a = 0; a < n; ++a)
        result.max_rel_peak[a] = peak[a] > 0 ? result.max_abs[a] / peak[a] : result.max_abs[a];
    return result;
}

}  // namespace

double EngineAgreement::worstRelative() const {
    return max_rel_peak.empty() ? 0.0 : *std::max_element(max_rel_peak.begin(), max_rel_peak.end());
}

EngineComparison compareWithEngines(const RobotDescription& robot, const PoseTrajectory& trajectory,
                                    const std::vector<double>& times) {
    EngineComparison c;
    const Model model(robot);
    c.actuators = model.actuators;
    c.ours = sampleInverseDynamics(model, trajectory, times, LimitPolicy::record);
    c.simbody = SimbodyMechanism(robot).inverseDynamics(trajectory, times);
    c.mujoco = MujocoMechanism(robot).inverseDynamics(trajectory, times);
    c.simbody_agreement = agreement("Simbody", c, c.simbody);
    c.mujoco_agreement = agreement("MuJoCo", c, c.mujoco);
    return c;
}

io::Table toTable(const EngineComparison& c) {
    const int n = c.actuators;
    io::Table table;
    table.columns = io::columnNames(io::TableId::validation, {.actuators = n});
    for (std::size_t k = 0; k < c.ours.samples.size(); ++k) {
        const InverseDynamicsSample& ours = c.ours.samples[k];
        std::vector<double> row{ours.t};
        const auto append = [&](const auto& v) {
            for (int a = 0; a < n; ++a) row.push_back(v(a));
        };
        append(ours.u);
        append(ours.tau);
        for (const auto* engine : {&c.simbody, &c.mujoco}) {
            append((*engine)[k].u);
            append((*engine)[k].tau);
        }
        for (const auto* engine : {&c.simbody, &c.mujoco}) {
            for (int a = 0; a < n; ++a) row.push_back((*engine)[k].tau(a) - ours.tau(a));
        }
        table.rows.push_back(std::move(row));
    }
    return table;
}

std::string agreementRows(const std::vector<const EngineAgreement*>& engines) {
    std::string text =
        "| engine | actuator | max abs(tau - tau_engine) [N or N m] | relative to our peak abs(tau) |\n"
        "| --- | --- | --- | --- |\n";
    char row[200];
    for (const EngineAgreement* a : engines) {
        for (std::size_t j = 0; j < a->max_abs.size(); ++j) {
            std::snprintf(row, sizeof row, "| %s | %zu | %.3e | %.3e |\n", a->engine.c_str(), j + 1, a->max_abs[j],
                          a->max_rel_peak[j]);
            text += row;
        }
    }
    return text;
}

std::string agreementTable(const EngineComparison& c) {
    char row[200];
    std::snprintf(row, sizeof row, "\nLargest actuator-variable difference: Simbody %.3e, MuJoCo %.3e (m or rad).\n",
                  c.simbody_agreement.max_u_abs, c.mujoco_agreement.max_u_abs);
    return agreementRows({&c.simbody_agreement, &c.mujoco_agreement}) + row;
}

}  // namespace nocdyn::validation
