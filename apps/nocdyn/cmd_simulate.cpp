// nocdyn simulate: binds app::SimulateOptions and writes the motion as CSV, row by row as
// computed; the summary line on standard error.
#include <iostream>
#include <memory>

#include "app/simulate.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/io/csv.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace simulate_command {

struct Options : app::SimulateOptions {
    std::string output;
};

void run(const Options& options) {
    io::OutputFile out = openOutput(options.output);
    CsvSink csv(out);
    TerminalObserver observer("nocdyn simulate");
    const app::SimulateResult result = app::runSimulate(options, csv, observer);
    observer.finish();
    csv.finish();
    out.commit();
    if (!result.stopped.empty()) {
        // --partial: the rows before the stop are written, and the run still failed
        throw Error(result.stopped +
                    (options.output.empty() ? "" : " (" + std::to_string(result.rows) + " rows written)"));
    }
    if (!quiet()) std::cerr << "nocdyn: " << app::summaryLine(result) << "\n";
}

}  // namespace simulate_command

void addSimulateCommand(CLI::App& app) {
    auto options = std::make_shared<simulate_command::Options>();
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
        "reach or singular stops it with the time and the limb, and no file unless --partial. A two-DOF robot\n"
        "(motion: translation) moves in x, y only: M_t d2p_t/dt2 = A_t^T tau - h_t with p_t = [x, y], its first\n"
        "row's pose x,y (with dx,dy), and no theta column. A spatial robot (space: spatial) starts from its first\n"
        "row's x,y,z,roll,pitch,yaw (x,y,z for motion: translation) with their rates dx.. (else du1..dun, else\n"
        "at rest), or home, and writes t,x,y,z,roll,pitch,yaw,u1..un,du1..dun,tau1..taun,kinetic.");
    addRobotOption(*command, options->robot);
    command->add_option("--forces", options->forces, "CSV file with columns t,tau1..taun [s, N or N m]")
        ->required()
        ->check(CLI::ExistingFile);
    addChoiceOption(*command, "--interpolation", options->interpolation,
                    "Forces between samples: hold (zero-order, as a DAC), linear, or cubic (C2 spline through\n"
                    "uniformly spaced samples; fewer than 5 samples are interpolated linearly)");
    command->add_option("--duration", options->duration, "Seconds to simulate [default: the span of the force file]")
        ->check(within(app::kSimulatedDurationRange));
    command->add_option("--rate", options->rate, "Output samples per second")
        ->check(within(app::kRateRange))
        ->capture_default_str();
    command->add_option("--output,-o", options->output, "CSV file to write [default: stdout]")->check(nonEmptyPath());
    command
        ->add_option("--atol", options->atol,
                     "Integrator absolute tolerance on the pose [rad, m] and its rate [rad/s, m/s]")
        ->check(within(app::kAbsoluteToleranceRange))
        ->capture_default_str();
    command->add_option("--rtol", options->rtol, "Integrator relative tolerance")
        ->check(within(app::kRelativeToleranceRange))
        ->capture_default_str();
    command->add_option("--max-step", options->max_step, "Integrator's largest step [s]")
        ->check(within(app::kMaxStepRange))
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
    command->callback([options] { simulate_command::run(*options); });
}

}  // namespace nocdyn::cli
