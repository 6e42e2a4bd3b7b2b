// nocdyn simulate: actuator forces from a CSV file -> platform motion of any robot (forward
// dynamics in the platform coordinates, M_p d2p/dt2 = A_p^T tau - h_p, integrated by
// Boost.Odeint's Dormand-Prince 5(4); forward_dynamics.hpp).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/tables/forces.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/reactions.hpp"

namespace nocdyn::cli {

namespace {

struct SimulateOptions {
    std::string robot, forces, output;
    std::optional<double> duration;
    double rate = 10000.0;
    double absolute_tolerance = 1e-12;
    double relative_tolerance = 1e-10;
    std::string interpolation = "cubic";
    bool partial = false;
    bool reactions = false;
    /// Which working assembly mode of the first row's u (1-based, as forward-kinematics lists
    /// them); 0: the one nearest home.
    int assembly_mode = 0;
};

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

/// The initial state from the first row of the forces file: the pose columns x,y,theta (with
/// dtheta,dx,dy, else du1..dun, else at rest); else u1..un (and du1..dun): the state of a
/// working assembly mode (stateFromActuators); else the robot's home at rest.
InitialState initialState(const Model& model, const io::Table& table, const SimulateOptions& options) {
    const int n = model.actuators;
    const auto& first = table.rows.front();
    const std::string where =
        options.forces + (table.lines.empty() ? std::string(": first row") : ":" + std::to_string(table.lines.front()));
    auto value = [&](const std::string& name) { return first[table.column(name)]; };
    auto hasAll = [&](const char* prefix) {
        for (int a = 1; a <= n; ++a) {
            if (!table.has(prefix + std::to_string(a))) return false;
        }
        return true;
    };
    auto actuatorColumns = [&](const char* prefix) {
        ActuatorVector v(n);
        for (int a = 0; a < n; ++a) v(a) = value(prefix + std::to_string(a + 1));
        return v;
    };
    const bool has_u = hasAll("u"), has_du = hasAll("du");
    InitialState state;
    Data data(model);
    const bool has_pose = table.has("theta") && table.has("x") && table.has("y");
    if (options.assembly_mode > 0 && (has_pose || !has_u)) {
        throw Error(where + ": --assembly-mode " + std::to_string(options.assembly_mode) +
                    " chooses among the poses of the first row's " + columnList("u", n) + ", but the row gives " +
                    (has_pose ? "the pose x,y,theta" : "no " + columnList("u", n)));
    }
    if (has_pose) {
        state.p = Pose(value("theta"), value("x"), value("y"));
        if (const Status status = inverseDisplacement(model, data, state.p); !status)
            throw Error(where + ": initial pose: " + describe(status, model));
        if (has_u) {
            const ActuatorVector u = actuatorColumns("u");
            for (int a = 0; a < n; ++a) {
                if (!(std::abs(u(a) - data.u(a)) <= kInitialStateTolerance)) {
                    std::ostringstream out;
                    out.precision(12);
                    out << where << ": column 'u" << a + 1 << "': " << u(a) << " but the pose x,y,theta gives "
                        << data.u(a);
                    throw Error(out.str());
                }
            }
        }
        if (table.has("dtheta") && table.has("dx") && table.has("dy")) {
            state.dp = Twist(value("dtheta"), value("dx"), value("dy"));
            state.origin = "first row's x,y,theta,dx,dy,dtheta";
        } else if (has_du) {
            state.dp = poseRate(model, data, actuatorColumns("du"), where);
            state.origin = "first row's x,y,theta and " + columnList("du", n);
        } else {
            state.origin = "first row's x,y,theta, at rest";
        }
        return state;
    }
    if (has_u) {
        ActuatorStart start;
        const ActuatorVector du = has_du ? actuatorColumns("du") : ActuatorVector();
        if (const Status status =
                stateFromActuators(model, data, actuatorColumns("u"), du, options.assembly_mode, start);
            !status) {
            const std::string columns = columnList("u", n) + (has_du ? "," + columnList("du", n) : std::string());
            if (status.code == StatusCode::assembly_mode_missing && options.assembly_mode > 0) {
                throw Error(where + ": --assembly-mode " + std::to_string(options.assembly_mode) + ", but " +
                            columnList("u", n) + " give " + std::to_string(start.working) + " working assembly mode" +
                            (start.working == 1 ? "" : "s") + " (forward-kinematics lists them)");
            }
            throw Error(where + ": " + columns + ": " + describe(status, model));
        }
        state.p = start.p;
        state.dp = start.dp;
        std::ostringstream out;
        out.precision(9);
        out << "first row's " << columnList("u", n) << (has_du ? "," + columnList("du", n) : std::string(", at rest"))
            << " (assembly mode " << start.mode << " of " << start.working << " with every limb on its home branch"
            << (start.nearest_home ? ", the nearest home" : ", as --assembly-mode chose") << ": theta = " << start.p(0)
            << " rad, x = " << start.p(1) << " m, y = " << start.p(2) << " m)";
        state.origin = out.str();
        return state;
    }
    state.p = model.home;
    state.origin = "home, at rest";
    return state;
}

std::vector<std::string> outputColumns(int n) { return io::columnNames(io::TableId::simulate, {.actuators = n}); }

void run(const SimulateOptions& options) {
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    const int n = model.actuators;
    const std::map<std::string, Interpolation> interpolations{
        {"hold", Interpolation::hold}, {"linear", Interpolation::linear}, {"cubic", Interpolation::cubic}};
    // read row by row into flat storage: the header and the first row (the initial state) kept
    io::Table table;
    ForceSignal forces = io::forcesFromCsvFile(options.forces, n, interpolations.at(options.interpolation), table);
    const double t0 = forces.firstTime();
    const double duration = options.duration ? *options.duration : forces.lastTime() - t0;
    if (!(duration > 0.0)) throw Error(options.forces + ": a single force sample: give --duration");
    if (!(duration <= kMaxSimulatedDuration)) {
        throw Error(options.forces + ": spans " + std::to_string(duration) + " s; simulate accepts at most " +
                    std::to_string(kMaxSimulatedDuration) + " s (give a shorter --duration)");
    }
    if (!(duration * options.rate <= kMaxSimulatedSamples)) {
        throw Error("--duration " + std::to_string(duration) + " s at --rate " + std::to_string(options.rate) +
                    " Hz gives more than 1e7 output samples, the most simulate accepts");
    }

    SimulatorOptions simulator_options;
    simulator_options.absolute_tolerance = options.absolute_tolerance;
    simulator_options.relative_tolerance = options.relative_tolerance;
    Simulator simulator(model, simulator_options);
    const InitialState initial = initialState(model, table, options);
    if (const Status status = simulator.reset(initial.p, initial.dp, t0); !status)
        throw Error(options.forces + ": initial state (" + initial.origin + "): " + describe(status, model));
    const Interpolation interpolation = forces.interpolation();
    simulator.setForces(std::move(forces));

    // rows at t0 + k / rate, k = 0..count-1, and at t0 + duration
    const auto count = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(duration * options.rate)));
    io::OutputFile out = openOutput(options.output);
    std::vector<std::string> columns = outputColumns(n);
    if (options.reactions) {
        for (std::string& name : io::reactionColumns(model.limbs)) columns.push_back(std::move(name));
    }
    io::CsvWriter csv(out, columns, /*background=*/true);
    std::vector<double> row(static_cast<std::size_t>(4 + 3 * n + 1));
    row.reserve(columns.size());
    Reactions reactions;
    Progress progress(duration);
    for (std::size_t k = 0; k <= count; ++k) {
        const double t = k < count ? t0 + static_cast<double>(k) / options.rate : t0 + duration;
        progress.update(t - t0);
        if (const Status status = simulator.advance(std::max(0.0, t - simulator.time())); !status) {
            if (options.partial) {
                csv.finish();
                out.commit();
            }
            std::ostringstream message;
            message.precision(9);
            message << "t = " << simulator.time() << " s: " << describe(status, model);
            if (options.partial && !options.output.empty()) message << " (" << csv.rows() << " rows written)";
            throw Error(message.str());
        }
        const Pose& p = simulator.pose();
        std::size_t c = 0;
        row[c++] = simulator.time();
        row[c++] = p(1);
        row[c++] = p(2);
        row[c++] = p(0);
        for (int a = 0; a < n; ++a) row[c++] = simulator.u()(a);
        for (int a = 0; a < n; ++a) row[c++] = simulator.du()(a);
        for (int a = 0; a < n; ++a) row[c++] = simulator.tau()(a);
        row[c] = simulator.kineticEnergy();
        if (options.reactions) {
            // the simulated state's every stage and the forces applied (forwardDynamics sets them)
            jointReactions(model, simulator.data(), reactions);
            row.resize(static_cast<std::size_t>(4 + 3 * n + 1));
            io::appendReactions(reactions, model.limbs, row);
        }
        csv.row(row);
    }
    progress.finish();
    csv.finish();
    out.commit();
    std::cerr << "nocdyn: simulated " << duration << " s from the " << initial.origin << " (" << name(interpolation)
              << " forces): " << simulator.acceptedSteps() << " steps accepted, " << simulator.rejectedSteps()
              << " rejected, " << simulator.evaluations() << " evaluations\n";
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
    auto options = std::make_shared<SimulateOptions>();
    CLI::App* command = app.add_subcommand(
        "simulate",
        "Forward dynamics of any robot: integrates M_p(p) d2p/dt2 = A_p^T tau - h_p(p, dp/dt) (eq. 23 in the\n"
        "platform coordinates, gravity and joint friction from the robot file) under actuator forces read from a\n"
        "CSV with columns t,tau1..taun. The initial state is the first row's x,y,theta with dx,dy,dtheta (else\n"
        "du1..dun, else at rest), so that the CSV of `inverse-dynamics` can be fed straight back; else its\n"
        "u1..un (with du1..dun, else at rest): the pose by direct kinematics, among the assembly modes with\n"
        "every limb on its home branch the one nearest home unless --assembly-mode picks another; else the\n"
        "robot's home at rest. Writes\n"
        "t,x,y,theta,u1..un,du1..dun,tau1..taun,kinetic (SI) at t0 + k / rate up to t0 + duration. A pose out of\n"
        "reach or singular stops it with the time and the limb, and no file unless --partial.");
    addRobotOption(*command, options->robot);
    command->add_option("--forces", options->forces, "CSV file with columns t,tau1..taun [s, N or N m]")
        ->required()
        ->check(CLI::ExistingFile);
    command
        ->add_option("--interpolation", options->interpolation,
                     "Forces between samples: hold (zero-order, as a DAC), linear, or cubic (C2 spline through\n"
                     "uniformly spaced samples; fewer than 5 samples are interpolated linearly)")
        ->check(CLI::IsMember({"hold", "linear", "cubic"}))
        ->capture_default_str();
    command->add_option("--duration", options->duration, "Seconds to simulate [default: the span of the force file]")
        ->check(finiteIn(kMinDuration, kMaxSimulatedDuration, "s"));
    command->add_option("--rate", options->rate, "Output samples per second")
        ->check(finiteIn(kMinRate, kMaxRate, "Hz"))
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV file to write [default: stdout]")->check(nonEmptyPath());
    command
        ->add_option("--atol", options->absolute_tolerance,
                     "Integrator absolute tolerance on the pose [rad, m] and its rate [rad/s, m/s]")
        ->check(finiteIn(1e-15, 1e-2, ""))
        ->capture_default_str();
    command->add_option("--rtol", options->relative_tolerance, "Integrator relative tolerance")
        ->check(finiteIn(1e-14, 1e-2, ""))
        ->capture_default_str();
    command
        ->add_option("--assembly-mode", options->assembly_mode,
                     "When the first row gives u1..un but no pose: start in the K-th assembly mode with every limb\n"
                     "on its home branch, numbered as `forward-kinematics --robot F U1 .. Un` lists them (by theta)\n"
                     "[default: the one nearest home; the summary on stderr names the mode taken]")
        ->check(CLI::Range(1, kMaxAssemblyModes));
    command->add_flag("--partial", options->partial,
                      "When the simulation stops early (singularity, out of reach), keep the rows before it");
    command->add_flag(
        "--reactions", options->reactions,
        "Add every joint's reaction after the other columns, at each output sample from the simulated\n"
        "state and the forces applied: limb{i}_j{k}_fx, _fy [N] and _m [N m] as in inverse-dynamics\n"
        "--reactions (base frame, the inboard body on the outboard body, the joint's effort and friction\n"
        "taken out)");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
