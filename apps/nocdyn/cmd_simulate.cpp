// nocdyn simulate: actuator forces from a CSV file -> platform motion (forward dynamics,
// eq. 20 solved for ddu, integrated by Boost.Odeint's Dormand-Prince 5(4)).
#include <cmath>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/prr3/forward_dynamics.hpp"
#include "nocdyn/prr3/sampling.hpp"

namespace nocdyn::cli {

namespace {

struct SimulateOptions {
    std::string robot, forces, output;
    std::optional<double> duration;
    double rate = 10000.0;
    double absolute_tolerance = 1e-12;
    double relative_tolerance = 1e-10;
};

void run(const SimulateOptions& options) {
    const prr3::Model model(loadRobotOrDefault(options.robot, "simulate"));
    const io::Table table = io::readCsvFile(options.forces);
    const prr3::ForceSeries forces = prr3::forcesFromTable(table, options.forces);

    prr3::SimulatorOptions simulator_options;
    simulator_options.absolute_tolerance = options.absolute_tolerance;
    simulator_options.relative_tolerance = options.relative_tolerance;
    prr3::Simulator simulator(model, simulator_options);

    // Initial state: the first row's u, du when present (the CSV of `inverse-dynamics`),
    // the pose columns as the tracker's starting guess; else rest at the reference posture.
    const double t0 = forces.t.front();
    const auto& first = table.rows.front();
    auto value = [&](const char* name) { return first[table.column(name)]; };
    Status status;
    if (table.has("u1") && table.has("u2") && table.has("u3") && table.has("du1") && table.has("du2") &&
        table.has("du3")) {
        Pose guess = Pose::Zero();
        if (table.has("theta") && table.has("x") && table.has("y"))
            guess = Pose(value("theta"), value("x"), value("y"));
        status = simulator.resetActuators(prr3::JointVector(value("u1"), value("u2"), value("u3")),
                                          prr3::JointVector(value("du1"), value("du2"), value("du3")), guess, t0);
    } else {
        status = simulator.reset(Pose::Zero(), Twist::Zero(), t0);
    }
    if (!status) throw Error(options.forces + ": initial state: " + describe(status, model.parameters));

    const double duration = options.duration ? *options.duration : forces.t.back() - t0;
    if (!(duration > 0.0)) throw Error(options.forces + ": a single force sample: give --duration");
    if (!(duration <= kMaxSimulatedDuration)) {
        throw Error(options.forces + ": spans " + std::to_string(duration) + " s; simulate accepts at most " +
                    std::to_string(kMaxSimulatedDuration) + " s (give a shorter --duration)");
    }
    if (!(duration * options.rate <= kMaxSimulatedSamples)) {
        throw Error("--duration " + std::to_string(duration) + " s at --rate " + std::to_string(options.rate) +
                    " Hz gives more than 1e7 output samples, the most simulate accepts");
    }
    std::vector<double> times = prr3::sampleTimes(duration, options.rate);
    times.push_back(duration);  // include the end point
    for (double& t : times) t += t0;
    const prr3::SimulationSeries series = prr3::simulateForces(simulator, forces, times);
    writeTable(prr3::toTable(series), options.output);
    std::cerr << "nocdyn: simulated " << duration << " s: " << simulator.acceptedSteps() << " steps accepted, "
              << simulator.rejectedSteps() << " rejected\n";
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
    auto options = std::make_shared<SimulateOptions>();
    CLI::App* command = app.add_subcommand(
        "simulate",
        "Forward dynamics: integrates I(u) ddu = tau - C(u, du) du (eq. 20) under actuator forces read from a CSV\n"
        "with columns t,tau1,tau2,tau3 (linear in between, held after the last row). The initial state is the\n"
        "first row's u1..u3, du1..du3 when present (so the CSV of `inverse-dynamics` can be fed straight back),\n"
        "else rest at the reference posture. Writes t,x,y,theta,u1..u3,du1..du3,tau1..tau3,kinetic (SI) at\n"
        "t0 + k / rate up to t0 + duration.");
    addRobotOption(*command, options->robot);
    command->add_option("--forces", options->forces, "CSV file with columns t,tau1,tau2,tau3 [s, N]")
        ->required()
        ->check(CLI::ExistingFile);
    command->add_option("--duration", options->duration, "Seconds to simulate [default: the span of the force file]")
        ->check(finiteIn(kMinDuration, kMaxSimulatedDuration, "s"));
    command->add_option("--rate", options->rate, "Output samples per second")
        ->check(finiteIn(kMinRate, kMaxRate, "Hz"))
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV file to write [default: stdout]");
    command->add_option("--atol", options->absolute_tolerance, "Integrator absolute tolerance on u [m] and du [m/s]")
        ->check(finiteIn(1e-15, 1e-2, ""))
        ->capture_default_str();
    command->add_option("--rtol", options->relative_tolerance, "Integrator relative tolerance")
        ->check(finiteIn(1e-14, 1e-2, ""))
        ->capture_default_str();
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
