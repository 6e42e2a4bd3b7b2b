#include "app/simulate_spatial.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/QR>

#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/spatial_simulator.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/tables/forces.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

/// Largest accepted relative residual of du = A_p dp when the first row gives du1..dun.
constexpr double kRateTolerance = 1e-9;

std::string joined(const std::vector<std::string>& names, const char* separator) {
    std::string out;
    for (const std::string& name : names) {
        if (!out.empty()) out += separator;
        out += name;
    }
    return out;
}

struct SpatialStart {
    spatial::TaskVector p, dp;
    std::string origin;
};

/// dp from the actuator rates: du = A_task [v; w] at the pose in `data`, w = Omega dEuler
/// (R = Rz(yaw) Ry(pitch) Rx(roll): w = roll' Rz Ry e_x + pitch' Rz e_y + yaw' e_z).
spatial::TaskVector poseRateFromActuators(const spatial::Model& model, const spatial::Data& data,
                                          const Eigen::VectorXd& du, const spatial::TaskVector& p,
                                          const std::string& where) {
    const int d = model.task_dimension;
    Eigen::MatrixXd map = data.A_task;
    if (d == 6) {
        const double cp = std::cos(p(4)), sp = std::sin(p(4)), cy = std::cos(p(5)), sy = std::sin(p(5));
        Eigen::Matrix3d omega;
        omega << cy * cp, -sy, 0.0, sy * cp, cy, 0.0, -sp, 0.0, 1.0;
        map.rightCols(3) = data.A_task.rightCols(3) * omega;
    }
    const Eigen::VectorXd dp = map.colPivHouseholderQr().solve(du);
    const double residual = (map * dp - du).norm();
    if (!dp.allFinite() || !(residual <= kRateTolerance * std::max(1.0, du.norm()))) {
        std::ostringstream out;
        out.precision(6);
        out << where << ": du1..du" << model.actuators << " are not the rates of any motion of the platform (residual "
            << residual << ")";
        throw Error(out.str());
    }
    return dp;
}

SpatialStart initialState(const spatial::Model& model, const io::Table& table, const std::string& source) {
    const int d = model.task_dimension, n = model.actuators;
    const std::vector<std::string> names = model.coordinates();
    std::string where = source;
    where += table.lines.empty() ? std::string(": first row") : ":" + std::to_string(table.lines.front());
    const auto& first = table.rows.front();
    const auto value = [&](const std::string& name) { return first[table.column(name)]; };
    const auto hasAll = [&](const std::vector<std::string>& columns) {
        return std::all_of(columns.begin(), columns.end(), [&](const std::string& c) { return table.has(c); });
    };
    for (const char* planar : {"theta", "dtheta"}) {
        if (table.has(planar)) {
            throw Error(where + ": column '" + planar + "': a spatial robot's pose is " + joined(names, ",") +
                        " (theta is a planar robot's)");
        }
    }
    SpatialStart start;
    start.p = model.home;
    start.dp = spatial::TaskVector::Zero(d);
    if (!hasAll(names)) {
        std::vector<std::string> given;
        for (const std::string& c : names)
            if (table.has(c)) given.push_back(c);
        if (!given.empty()) {
            throw Error(where + ": the pose needs every column of " + joined(names, ",") + ", the row gives only " +
                        joined(given, ","));
        }
        if (table.has("u1")) {
            throw Error(where + ": a spatial robot starts from a pose: give " + joined(names, ",") +
                        " in the first row (u1..u" + std::to_string(n) + " alone are not read)");
        }
        start.origin = "home, at rest";
        return start;
    }
    for (int i = 0; i < d; ++i) start.p(i) = value(names[static_cast<std::size_t>(i)]);
    spatial::Data data(model);
    if (const Status status = spatial::inverseKinematics(model, data, start.p); !status) {
        throw Error(where + ": initial pose: " + spatial::describe(status, model));
    }
    std::vector<std::string> rates, du;
    for (const std::string& c : names) rates.push_back("d" + c);
    for (int a = 1; a <= n; ++a) du.push_back("du" + std::to_string(a));
    const std::string pose_origin = "first row's " + joined(names, ",");
    if (hasAll(rates)) {
        for (int i = 0; i < d; ++i) start.dp(i) = value(rates[static_cast<std::size_t>(i)]);
        start.origin = pose_origin + " and " + joined(rates, ",");
    } else if (hasAll(du)) {
        Eigen::VectorXd rate(n);
        for (int a = 0; a < n; ++a) rate(a) = value(du[static_cast<std::size_t>(a)]);
        start.dp = poseRateFromActuators(model, data, rate, start.p, where);
        start.origin = pose_origin + " and du1..du" + std::to_string(n);
    } else {
        start.origin = pose_origin + ", at rest";
    }
    return start;
}

}  // namespace

SimulateResult runSpatialSimulate(const SimulateOptions& options, TableSink& table, Observer& observer) {
    validate(options);
    if (options.assembly_mode > 0) {
        throw OptionError("assembly_mode", "a spatial robot starts from the first row's pose (planar for now)");
    }
    if (options.reactions) throw OptionError("reactions", "a spatial robot's joint reactions are planar for now");
    const spatial::Model model(io::loadSpatialRobotDescription(options.robot.path, options.robot.set));
    const int n = model.actuators, d = model.task_dimension;
    const std::string source = options.forces_table ? std::string("forces") : options.forces;
    io::Table first;
    const Interpolation interpolation = options.interpolation;
    ForceSignal forces = options.forces_table ? tables::forcesFromTable(*options.forces_table, n, interpolation, source)
                                              : tables::forcesFromCsvFile(options.forces, n, interpolation, first);
    const io::Table& head = options.forces_table ? *options.forces_table : first;
    const double t0 = forces.firstTime();
    const double duration = options.duration ? *options.duration : forces.lastTime() - t0;
    if (!(duration > 0.0)) throw Error(source + ": a single force sample: give --duration");
    if (!(duration <= kSimulatedDurationRange.hi) || !(duration * options.rate <= kMaxSimulatedSamples)) {
        throw Error(source + ": " + std::to_string(duration) + " s at " + std::to_string(options.rate) +
                    " Hz: simulate takes at most 1000 s and 1e7 output samples (give a shorter --duration)");
    }
    SimulatorOptions simulator_options;
    static_cast<IntegrationTolerances&>(simulator_options) = options;
    simulator_options.poll = [&observer] { stopIfRequested(observer); };
    spatial::Simulator simulator(model, simulator_options);
    const SpatialStart initial = initialState(model, head, source);
    if (const Status status = simulator.reset(initial.p, initial.dp, t0); !status) {
        throw Error(source + ": initial state (" + initial.origin + "): " + spatial::describe(status, model));
    }
    SimulateResult out;
    out.duration = duration;
    out.origin = initial.origin;
    out.interpolation = name(forces.interpolation());
    simulator.setForces(std::move(forces));

    std::vector<std::string> columns{"t"};
    for (const std::string& c : model.coordinates()) columns.push_back(c);
    for (const char* prefix : {"u", "du", "tau"}) {
        for (int a = 1; a <= n; ++a) columns.push_back(prefix + std::to_string(a));
    }
    columns.emplace_back("kinetic");
    table.columns(columns);
    std::vector<double> row(columns.size());
    const auto count = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(duration * options.rate)));
    Meter meter(observer, duration, "s");
    for (std::size_t k = 0; k <= count; ++k) {
        const double t = k < count ? t0 + static_cast<double>(k) / options.rate : t0 + duration;
        meter(t - t0);
        if (const Status status = simulator.advance(std::max(0.0, t - simulator.time())); !status) {
            const std::string message = text::sampleTime(simulator.time()) + ": " + spatial::describe(status, model);
            if (!options.partial) throw Error(message);
            out.stopped = message;
            break;
        }
        const spatial::TaskVector p = simulator.pose();
        const spatial::Data& data = simulator.data();
        std::size_t c = 0;
        row[c++] = simulator.time();
        for (int i = 0; i < d; ++i) row[c++] = p(i);
        for (int a = 0; a < n; ++a) row[c++] = data.u(a);
        for (int a = 0; a < n; ++a) row[c++] = data.du(a);
        for (int a = 0; a < n; ++a) row[c++] = data.tau(a);
        row[c] = simulator.kineticEnergy();
        table.row(row);
        ++out.rows;
    }
    meter.report(simulator.time() - t0);
    out.accepted_steps = simulator.acceptedSteps();
    out.rejected_steps = simulator.rejectedSteps();
    out.evaluations = simulator.evaluations();
    return out;
}

}  // namespace nocdyn::app
