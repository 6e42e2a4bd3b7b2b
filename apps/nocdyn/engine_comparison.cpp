#include "engine_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "nocdyn/description.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/validation/mujoco_robot.hpp"
#include "nocdyn/validation/simbody_robot.hpp"

namespace nocdyn::cli {

namespace {

EngineAgreement agreement(const std::string& engine, const InverseDynamicsSeries& ours,
                          const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& tau) {
    EngineAgreement result;
    result.engine = engine;
    std::array<double, 3> peak{};
    for (std::size_t k = 0; k < ours.samples.size(); ++k) {
        const InverseDynamicsSample& s = ours.samples[k];
        for (int j = 0; j < 3; ++j) {
            peak[j] = std::max(peak[j], std::abs(s.tau(j)));
            result.max_abs[j] = std::max(result.max_abs[j], std::abs(tau[k](j) - s.tau(j)));
            result.max_u_abs = std::max(result.max_u_abs, std::abs(u[k](j) - s.u(j)));
        }
    }
    for (int j = 0; j < 3; ++j) result.max_rel_peak[j] = peak[j] > 0 ? result.max_abs[j] / peak[j] : result.max_abs[j];
    return result;
}

}  // namespace

EngineComparison compareWithEngines(const RobotParameters& robot, const PoseTrajectory& trajectory,
                                    const std::vector<double>& times) {
    EngineComparison comparison;
    const Model model(expand(robot));
    comparison.ours = sampleInverseDynamics(model, trajectory, times, LimitPolicy::record);

    validation::SimbodyRobot simbody(robot);
    for (const auto& sample : simbody.inverseDynamics(trajectory, times)) {
        comparison.simbody_u.push_back(sample.u);
        comparison.simbody_tau.push_back(sample.tau);
    }
    validation::MujocoRobot mujoco(robot);
    for (const auto& sample : mujoco.inverseDynamics(trajectory, times)) {
        comparison.mujoco_u.push_back(sample.u);
        comparison.mujoco_tau.push_back(sample.tau);
    }
    comparison.simbody = agreement("Simbody", comparison.ours, comparison.simbody_u, comparison.simbody_tau);
    comparison.mujoco = agreement("MuJoCo", comparison.ours, comparison.mujoco_u, comparison.mujoco_tau);
    return comparison;
}

io::Table toTable(const EngineComparison& c) {
    io::Table table;
    table.columns = {"t"};
    for (const char* prefix : {"", "simbody_", "mujoco_"}) {
        for (const char* quantity : {"u", "tau"}) {
            for (int j = 1; j <= 3; ++j) table.columns.push_back(std::string(prefix) + quantity + std::to_string(j));
        }
    }
    for (const char* prefix : {"simbody_", "mujoco_"}) {
        for (int j = 1; j <= 3; ++j) table.columns.push_back(std::string(prefix) + "dtau" + std::to_string(j));
    }
    for (std::size_t k = 0; k < c.ours.samples.size(); ++k) {
        const InverseDynamicsSample& s = c.ours.samples[k];
        std::vector<double> row{s.t};
        for (const ActuatorVector* set : {&s.u, &s.tau}) {
            for (int j = 0; j < 3; ++j) row.push_back((*set)(j));
        }
        for (const auto* set : {&c.simbody_u, &c.simbody_tau, &c.mujoco_u, &c.mujoco_tau}) {
            for (int j = 0; j < 3; ++j) row.push_back((*set)[k](j));
        }
        for (const auto* set : {&c.simbody_tau, &c.mujoco_tau}) {
            for (int j = 0; j < 3; ++j) row.push_back((*set)[k](j) - s.tau(j));
        }
        table.rows.push_back(std::move(row));
    }
    return table;
}

std::string agreementTable(const EngineComparison& c) {
    std::string text =
        "| engine | actuator | max abs(tau - tau_engine) [N] | relative to our peak abs(tau) |\n| --- | --- | --- | "
        "--- |\n";
    char row[160];
    for (const EngineAgreement* a : {&c.simbody, &c.mujoco}) {
        for (int j = 0; j < 3; ++j) {
            std::snprintf(row, sizeof row, "| %s | %d | %.3e | %.3e |\n", a->engine.c_str(), j + 1, a->max_abs[j],
                          a->max_rel_peak[j]);
            text += row;
        }
    }
    std::snprintf(row, sizeof row, "\nLargest slider-displacement difference: Simbody %.3e m, MuJoCo %.3e m.\n",
                  c.simbody.max_u_abs, c.mujoco.max_u_abs);
    return text + row;
}

}  // namespace nocdyn::cli
