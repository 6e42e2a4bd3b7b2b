#include "app/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "app/pose_spatial.hpp"
#include "app/simulate_spatial.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/pose_order.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/tables/forces.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

/// Largest accepted difference between a first row's u1..un and the u of its pose [m or rad],
/// and between its du1..dun and the rates of the pose rate found from them (relative).
constexpr double kInitialStateTolerance = 1e-9;

struct InitialState {
    Pose p = Pose::Zero();
    Twist dp = Twist::Zero();
    std::string origin;  ///< for the summary line
};

std::string columnList(const char* prefix, int n) { return std::string(prefix) + "1.." + prefix + std::to_string(n); }

/// dp/dt from the first row's du1..dun at the pose in `data` (position stage done).
Twist poseRate(const Model& model, Data& data, const ActuatorVector& du, const std::string& where) {
    Twist dp = Twist::Zero();
    if (const Status status = velocityFromActuatorRatesLeastSquares(model, data, du, dp, kInitialStateTolerance);
        !status) {
        throw Error(where + ": " + columnList("du", model.actuators) + ": " + describe(status, model));
    }
    return dp;
}

/// The initial state from the first row of the forces: the pose columns x,y,theta (with
/// dtheta,dx,dy, else du1..dun, else at rest); else u1..un (and du1..dun): the state of a
/// working assembly mode (stateFromActuators); else the robot's home at rest. A two-DOF
/// robot's pose columns are x,y (with dx,dy): theta stays at home(0), at rest, and a theta or
/// dtheta column other than 0 is refused.
InitialState initialState(const Model& model, const io::Table& table, const std::string& source, int assembly_mode) {
    const int n = model.actuators;
    const auto& first = table.rows.front();
    // appended, not `":" + ...` (a GCC 12 -Wrestrict false positive)
    std::string where = source;
    if (table.lines.empty()) {
        where += ": first row";
    } else {
        where += ':';
        where += std::to_string(table.lines.front());
    }
    auto value = [&](const std::string& name) { return first[table.column(name)]; };
    auto hasAll = [&](const char* prefix) {
        for (int a = 1; a <= n; ++a) {
            std::string name(prefix);  // appended, not `prefix + ...` (a GCC 12 -Wrestrict false positive)
            name += std::to_string(a);
            if (!table.has(name)) return false;
        }
        return true;
    };
    auto actuatorColumns = [&](const char* prefix) {
        ActuatorVector v(n);
        for (int a = 0; a < n; ++a) {
            std::string name(prefix);
            name += std::to_string(a + 1);
            v(a) = value(name);
        }
        return v;
    };
    const bool has_u = hasAll("u"), has_du = hasAll("du");
    InitialState state;
    Data data(model);
    const bool task = model.task_dimension == 2;
    const char* pose_names = task ? "x,y" : "x,y,theta";
    if (task) {
        for (const char* name : {"theta", "dtheta"}) {
            if (table.has(name) && value(name) != 0.0) {
                std::ostringstream out;
                out.precision(12);
                out << where << ": column '" << name << "': " << value(name)
                    << ", but a two-DOF robot (motion: translation) has no theta: give x,y (and dx,dy)";
                throw Error(out.str());
            }
        }
    }
    const bool has_pose = (task || table.has("theta")) && table.has("x") && table.has("y");
    if (assembly_mode > 0 && (has_pose || !has_u)) {
        throw Error(where + ": --assembly-mode " + std::to_string(assembly_mode) +
                    " chooses among the poses of the first row's " + columnList("u", n) + ", but the row gives " +
                    (has_pose ? std::string("the pose ") + pose_names : "no " + columnList("u", n)));
    }
    if (has_pose) {
        state.p = task ? Pose(model.home(0), value("x"), value("y"))
                       : corePose(Vector3(value("x"), value("y"), value("theta")));
        if (const Status status = inverseDisplacement(model, data, state.p); !status)
            throw Error(where + ": initial pose: " + describe(status, model));
        if (has_u) {
            const ActuatorVector u = actuatorColumns("u");
            for (int a = 0; a < n; ++a) {
                if (!(std::abs(u(a) - data.u(a)) <= kInitialStateTolerance)) {
                    std::ostringstream out;
                    out.precision(12);
                    out << where << ": column 'u" << a + 1 << "': " << u(a) << " but the pose " << pose_names
                        << " gives " << data.u(a);
                    throw Error(out.str());
                }
            }
        }
        const std::string pose_origin = std::string("first row's ") + pose_names;
        if ((task || table.has("dtheta")) && table.has("dx") && table.has("dy")) {
            state.dp = Twist(task ? 0.0 : value("dtheta"), value("dx"), value("dy"));
            state.origin = pose_origin + (task ? ",dx,dy" : ",dx,dy,dtheta");
        } else if (has_du) {
            state.dp = poseRate(model, data, actuatorColumns("du"), where);
            state.origin = pose_origin + " and " + columnList("du", n);
        } else {
            state.origin = pose_origin + ", at rest";
        }
        return state;
    }
    if (has_u) {
        ActuatorStart start;
        const ActuatorVector du = has_du ? actuatorColumns("du") : ActuatorVector();
        if (const Status status = stateFromActuators(model, data, actuatorColumns("u"), du, assembly_mode, start);
            !status) {
            std::string columns = columnList("u", n);
            if (has_du) {
                columns += ',';
                columns += columnList("du", n);
            }
            if (status.code == StatusCode::assembly_mode_missing && assembly_mode > 0) {
                throw Error(where + ": --assembly-mode " + std::to_string(assembly_mode) + ", but " +
                            columnList("u", n) + " give " + std::to_string(start.working) + " working assembly mode" +
                            (start.working == 1 ? "" : "s") + " (forward-kinematics lists them)");
            }
            throw Error(where + ": " + columns + ": " + describe(status, model));
        }
        state.p = start.p;
        state.dp = start.dp;
        std::ostringstream out;
        out << "first row's " << columnList("u", n);
        if (has_du) {
            out << ',' << columnList("du", n);
        } else {
            out << ", at rest";
        }
        out << " (assembly mode " << start.mode << " of " << start.working << " with every limb on its home branch"
            << (start.nearest_home ? ", the nearest home" : ", as --assembly-mode chose")
            << (task ? text::format(": x = %.9g m, y = %.9g m)", start.p(1), start.p(2))
                     : text::format(": x = %.9g m, y = %.9g m, theta = %.9g rad)", start.p(1), start.p(2), start.p(0)));
        state.origin = out.str();
        return state;
    }
    state.p = model.home;
    state.origin = "home, at rest";
    return state;
}

}  // namespace

std::string summaryLine(const SimulateResult& result) {
    std::ostringstream out;
    out << "simulated " << result.duration << " s from the " << result.origin << " (" << result.interpolation
        << " forces): " << result.accepted_steps << " steps accepted, " << result.rejected_steps << " rejected, "
        << result.evaluations << " evaluations";
    return out.str();
}

void validate(const SimulateOptions& options) {
    if (options.duration) requireIn(*options.duration, kSimulatedDurationRange, "duration");
    requireIn(options.rate, kRateRange, "rate");
    requireIn(options.atol, kAbsoluteToleranceRange, "atol");
    requireIn(options.rtol, kRelativeToleranceRange, "rtol");
    requireIn(options.max_step, kMaxStepRange, "max_step");
    if (options.assembly_mode < 0 || options.assembly_mode > kMaxAssemblyModes) {
        throw OptionError("assembly_mode", std::to_string(options.assembly_mode) + " is outside [0, " +
                                               std::to_string(kMaxAssemblyModes) + "] (0: the mode nearest home)");
    }
    if (!options.forces_table && options.forces.empty()) throw OptionError("forces", "give the forces' CSV file");
}

SimulateResult runSimulate(const SimulateOptions& options, TableSink& table, Observer& observer) {
    if (isSpatialRobot(options.robot)) return runSpatialSimulate(options, table, observer);
    validate(options);
    // a two-DOF robot too: its state is [x, y] and their rates (Simulator::reset)
    const Model model(loadRobot(options.robot));
    if (const std::string rigid = rigidPlantWarning(model.description, "simulate"); !rigid.empty())
        observer.warning(rigid);
    const int n = model.actuators;
    const std::string source = options.forces_table ? std::string("forces") : options.forces;
    // a file is read row by row into flat storage: the header and the first row (the initial state) kept
    io::Table first;
    ForceSignal forces = options.forces_table
                             ? tables::forcesFromTable(*options.forces_table, n, options.interpolation, source)
                             : tables::forcesFromCsvFile(options.forces, n, options.interpolation, first);
    const io::Table& head = options.forces_table ? *options.forces_table : first;
    const double t0 = forces.firstTime();
    const double duration = options.duration ? *options.duration : forces.lastTime() - t0;
    if (!(duration > 0.0)) throw Error(source + ": a single force sample: give --duration");
    if (!(duration <= kSimulatedDurationRange.hi)) {
        throw Error(source + ": spans " + std::to_string(duration) + " s; simulate accepts at most " +
                    std::to_string(kSimulatedDurationRange.hi) + " s (give a shorter --duration)");
    }
    if (!(duration * options.rate <= kMaxSimulatedSamples)) {
        throw Error("--duration " + std::to_string(duration) + " s at --rate " + std::to_string(options.rate) +
                    " Hz gives more than 1e7 output samples, the most simulate accepts");
    }

    SimulatorOptions simulator_options;
    static_cast<IntegrationTolerances&>(simulator_options) = options;
    // a long interval between two output rows still answers a stop (Ctrl-C in Python)
    simulator_options.poll = [&observer] { stopIfRequested(observer); };
    Simulator simulator(model, simulator_options);
    const InitialState initial = initialState(model, head, source, options.assembly_mode);
    if (const Status status = simulator.reset(initial.p, initial.dp, t0); !status)
        throw Error(source + ": initial state (" + initial.origin + "): " + describe(status, model));
    SimulateResult out;
    out.duration = duration;
    out.origin = initial.origin;
    out.interpolation = name(forces.interpolation());
    simulator.setForces(std::move(forces));

    // rows at t0 + k / rate, k = 0..count-1, and at t0 + duration
    const auto count = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(duration * options.rate)));
    const bool task = model.task_dimension == 2;
    std::vector<std::string> columns =
        io::columnNames(io::TableId::simulate, {.actuators = n, .task_dimension = model.task_dimension});
    if (options.reactions) {
        for (std::string& column : tables::reactionColumns(model.limbs)) columns.push_back(std::move(column));
    }
    table.columns(columns);
    // t, x, y, theta (not for a two-DOF robot), u, du, tau, kinetic
    const std::size_t base = (task ? 4 : 5) + 3 * static_cast<std::size_t>(n);
    std::vector<double> row(base);
    row.reserve(columns.size());
    Reactions reactions;
    Meter meter(observer, duration, "s");
    for (std::size_t k = 0; k <= count; ++k) {
        const double t = k < count ? t0 + static_cast<double>(k) / options.rate : t0 + duration;
        meter(t - t0);
        if (const Status status = simulator.advance(std::max(0.0, t - simulator.time())); !status) {
            const std::string message = text::sampleTime(simulator.time()) + ": " + describe(status, model);
            if (!options.partial) throw Error(message);
            out.stopped = message;
            break;
        }
        const Pose& p = simulator.pose();
        std::size_t c = 0;
        row[c++] = simulator.time();
        row[c++] = p(1);
        row[c++] = p(2);
        if (!task) row[c++] = p(0);
        for (int a = 0; a < n; ++a) row[c++] = simulator.u()(a);
        for (int a = 0; a < n; ++a) row[c++] = simulator.du()(a);
        for (int a = 0; a < n; ++a) row[c++] = simulator.tau()(a);
        row[c] = simulator.kineticEnergy();
        if (options.reactions) {
            // the simulated state's every stage and the forces applied (forwardDynamics sets them)
            jointReactions(model, simulator.data(), reactions);
            row.resize(base);
            tables::appendReactions(reactions, model.limbs, row);
        }
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
