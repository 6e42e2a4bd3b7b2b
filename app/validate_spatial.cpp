// `validate` of a spatial robot (validate_spatial.hpp).
#include "app/validate_spatial.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/inverse_dynamics_spatial.hpp"
#include "app/table.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial_trajectory.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/validation/agreement.hpp"
#include "nocdyn/validation/simbody_spatial.hpp"

namespace nocdyn::app {

std::vector<std::string> spatialValidateColumns(const spatial::Model& model) {
    std::vector<std::string> columns{"t"};
    for (const std::string& c : model.coordinates()) columns.push_back(c);
    for (const char* prefix : {"u", "tau", "simbody_tau", "simbody_dtau"}) {
        for (int a = 1; a <= model.actuators; ++a) columns.push_back(prefix + std::to_string(a));
    }
    return columns;
}

ValidateResult runSpatialValidate(const ValidateOptions& options, Observer& observer) {
    validate(static_cast<const SamplingOptions&>(options));
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

    // Simbody's along the same path: p, dp, ddp of the trajectory at every row's t
    std::vector<Eigen::VectorXd> p(samples), dp(samples), ddp(samples);
    spatial::TaskVector pk, dpk, ddpk;
    for (std::size_t k = 0; k < samples; ++k) {
        trajectory.evaluate(at(k, 0), pk, dpk, ddpk);
        p[k] = pk;
        dp[k] = dpk;
        ddp[k] = ddpk;
    }
    validation::SimbodySpatialMechanism engine(description);
    Eigen::MatrixXd theirs;
    try {
        theirs = engine.actuatorForces(p, dp, ddp);
    } catch (const Error& e) {
        // the engine numbers its samples from 0: say at which times they are
        throw Error(std::string(e.what()) + " (sample k is at t = k / " + text::precise(options.rate) + " Hz)");
    }
    stopIfRequested(observer);

    validation::EngineAgreement simbody;
    simbody.engine = "Simbody";
    simbody.max_abs.assign(static_cast<std::size_t>(n), 0.0);
    simbody.max_rel_peak.assign(static_cast<std::size_t>(n), 0.0);
    std::vector<double> peak(static_cast<std::size_t>(n), 0.0);
    ValidateResult out;
    out.robot = model.name;
    out.trajectory = trajectory.name;
    out.samples = samples;
    out.table.columns = spatialValidateColumns(model);
    out.table.rows.reserve(samples);
    for (std::size_t k = 0; k < samples; ++k) {
        std::vector<double> row;
        row.reserve(out.table.columns.size());
        for (int c = 0; c < 1 + d; ++c) row.push_back(at(k, c));
        for (int a = 0; a < n; ++a) row.push_back(at(k, u_column + a));
        for (int a = 0; a < n; ++a) row.push_back(at(k, tau_column + a));
        for (int a = 0; a < n; ++a) row.push_back(theirs(static_cast<Eigen::Index>(k), a));
        for (int a = 0; a < n; ++a) {
            const double tau = at(k, tau_column + a), engine = theirs(static_cast<Eigen::Index>(k), a);
            if (!std::isfinite(engine)) {
                throw Error(text::sampleTime(at(k, 0)) +
                            ": Simbody's spatial model gives a non-finite force of "
                            "actuator " +
                            std::to_string(a + 1));
            }
            row.push_back(engine - tau);
            const auto aa = static_cast<std::size_t>(a);
            peak[aa] = std::max(peak[aa], std::abs(tau));
            simbody.max_abs[aa] = std::max(simbody.max_abs[aa], std::abs(engine - tau));
        }
        out.table.rows.push_back(std::move(row));
    }
    for (std::size_t a = 0; a < peak.size(); ++a)
        simbody.max_rel_peak[a] = peak[a] > 0.0 ? simbody.max_abs[a] / peak[a] : simbody.max_abs[a];
    char line[200];
    std::snprintf(line, sizeof line,
                  "\nLargest difference over the actuators, relative to our peak abs(tau): Simbody %.3e.\n",
                  simbody.worstRelative());
    out.agreement = validation::agreementRows({&simbody}) + line +
                    "MuJoCo's models are planar for now: a spatial robot is compared with Simbody only.\n";
    return out;
}

}  // namespace nocdyn::app
