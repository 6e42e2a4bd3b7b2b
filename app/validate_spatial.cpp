// `validate` of a spatial robot (validate_spatial.hpp).
#include "app/validate_spatial.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/inverse_dynamics_spatial.hpp"
#include "app/options.hpp"
#include "app/table.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial_trajectory.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/validation/agreement.hpp"
#include "nocdyn/validation/mujoco_spatial.hpp"
#include "nocdyn/validation/simbody_spatial.hpp"

namespace nocdyn::app {

std::vector<std::string> spatialValidateEngines(ValidateEngine engine) {
    if (engine == ValidateEngine::both)
        return {std::string(nameOf(ValidateEngine::simbody)), std::string(nameOf(ValidateEngine::mujoco))};
    return {std::string(nameOf(engine))};
}

std::vector<std::string> spatialValidateColumns(const spatial::Model& model, const std::vector<std::string>& engines) {
    std::vector<std::string> columns{"t"};
    for (const std::string& c : model.coordinates()) columns.push_back(c);
    std::vector<std::string> prefixes{"u", "tau"};
    for (const std::string& e : engines) prefixes.push_back(e + "_tau");
    for (const std::string& e : engines) prefixes.push_back(e + "_dtau");
    for (const std::string& prefix : prefixes) {
        for (int a = 1; a <= model.actuators; ++a) columns.push_back(prefix + std::to_string(a));
    }
    return columns;
}

namespace {

/// One engine's actuator forces along the samples (one row each).
Eigen::MatrixXd engineForces(const std::string& engine, const SpatialRobotDescription& description,
                             const std::vector<Eigen::VectorXd>& p, const std::vector<Eigen::VectorXd>& dp,
                             const std::vector<Eigen::VectorXd>& ddp, double rate) {
    try {
        if (engine == "mujoco") return validation::MujocoSpatialMechanism(description).actuatorForces(p, dp, ddp);
        return validation::SimbodySpatialMechanism(description).actuatorForces(p, dp, ddp);
    } catch (const OptionError&) {
        throw;
    } catch (const Error& e) {
        // the engines number their samples from 0: say at which times they are
        throw Error(std::string(e.what()) + " (sample k is at t = k / " + text::precise(rate) + " Hz)");
    }
}

}  // namespace

ValidateResult runSpatialValidate(const ValidateOptions& options, Observer& observer) {
    validate(static_cast<const SamplingOptions&>(options));
    const std::vector<std::string> engines = spatialValidateEngines(options.engine);
    if (options.trajectory.empty() && !options.given_trajectory) {
        throw OptionError("trajectory",
                          "give the spatial robot's trajectory file (keyed x, y, z and, for motion full, roll, "
                          "pitch, yaw; or a CSV of samples)");
    }
    const SpatialRobotDescription description = io::loadSpatialRobotDescription(options.robot.path, options.robot.set);
    const spatial::Model model(description);
    const spatial::Trajectory trajectory = spatialTrajectoryOf(options, model.task_dimension);

    // nocdyn's rows as inverse-dynamics computes them: t, p, u, du, ddu, tau, kinetic
    TableCollector ours;
    const InverseDynamicsResult computed =
        runSpatialInverseDynamics(model, trajectory, options, /*allow_limits=*/true, ours, observer);
    stopIfRequested(observer);
    const int d = model.task_dimension, n = model.actuators;
    const std::size_t width = ours.names().size(), samples = computed.samples;
    const std::vector<double>& values = ours.values();
    const auto at = [&](std::size_t k, int column) { return values[k * width + static_cast<std::size_t>(column)]; };
    const int u_column = 1 + d, tau_column = 1 + d + 3 * n;

    // the engines' along the same path: p, dp, ddp of the trajectory at every row's t
    std::vector<Eigen::VectorXd> p(samples), dp(samples), ddp(samples);
    spatial::TaskVector pk, dpk, ddpk;
    for (std::size_t k = 0; k < samples; ++k) {
        trajectory.evaluate(at(k, 0), pk, dpk, ddpk);
        p[k] = pk;
        dp[k] = dpk;
        ddp[k] = ddpk;
    }
    std::vector<Eigen::MatrixXd> theirs;
    std::vector<validation::EngineAgreement> agreements(engines.size());
    for (std::size_t e = 0; e < engines.size(); ++e) {
        theirs.push_back(engineForces(engines[e], description, p, dp, ddp, options.rate));
        stopIfRequested(observer);
        agreements[e].engine = engines[e] == "mujoco" ? "MuJoCo" : "Simbody";
        agreements[e].max_abs.assign(static_cast<std::size_t>(n), 0.0);
        agreements[e].max_rel_peak.assign(static_cast<std::size_t>(n), 0.0);
    }

    std::vector<double> peak(static_cast<std::size_t>(n), 0.0);
    ValidateResult out;
    out.robot = model.name;
    out.trajectory = trajectory.name;
    out.samples = samples;
    out.table.columns = spatialValidateColumns(model, engines);
    out.table.rows.reserve(samples);
    for (std::size_t k = 0; k < samples; ++k) {
        std::vector<double> row;
        row.reserve(out.table.columns.size());
        for (int c = 0; c < 1 + d; ++c) row.push_back(at(k, c));
        for (int a = 0; a < n; ++a) row.push_back(at(k, u_column + a));
        for (int a = 0; a < n; ++a) {
            const double tau = at(k, tau_column + a);
            row.push_back(tau);
            peak[static_cast<std::size_t>(a)] = std::max(peak[static_cast<std::size_t>(a)], std::abs(tau));
        }
        for (std::size_t e = 0; e < engines.size(); ++e) {
            for (int a = 0; a < n; ++a) {
                const double engine = theirs[e](static_cast<Eigen::Index>(k), a);
                if (!std::isfinite(engine)) {
                    throw Error(text::sampleTime(at(k, 0)) + ": " + agreements[e].engine +
                                "'s spatial model gives a non-finite force of actuator " + std::to_string(a + 1));
                }
                row.push_back(engine);
            }
        }
        for (std::size_t e = 0; e < engines.size(); ++e) {
            for (int a = 0; a < n; ++a) {
                const double difference = theirs[e](static_cast<Eigen::Index>(k), a) - at(k, tau_column + a);
                row.push_back(difference);
                double& worst = agreements[e].max_abs[static_cast<std::size_t>(a)];
                worst = std::max(worst, std::abs(difference));
            }
        }
        out.table.rows.push_back(std::move(row));
    }
    std::vector<const validation::EngineAgreement*> rows;
    std::string worst;
    for (validation::EngineAgreement& agreement : agreements) {
        for (std::size_t a = 0; a < peak.size(); ++a) {
            agreement.max_rel_peak[a] = peak[a] > 0.0 ? agreement.max_abs[a] / peak[a] : agreement.max_abs[a];
        }
        rows.push_back(&agreement);
        char value[64];
        std::snprintf(value, sizeof value, "%.3e", agreement.worstRelative());
        worst += (worst.empty() ? " " : ", ") + agreement.engine + " " + value;
    }
    out.agreement = validation::agreementRows(rows) +
                    "\nLargest difference over the actuators, relative to our peak abs(tau):" + worst + ".\n";
    return out;
}

}  // namespace nocdyn::app
