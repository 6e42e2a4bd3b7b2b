// nocdyn inverse-dynamics: binds app::InverseDynamicsOptions and writes the table as CSV, row by
// row as computed (memory does not depend on the sample count).
#include <memory>

#include "app/inverse_dynamics.hpp"
#include "app/inverse_dynamics_spatial.hpp"
#include "app/pose_spatial.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "progress.hpp"
#include "nocdyn/io/layouts.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace inverse_dynamics_command {

struct Options : app::InverseDynamicsOptions {
    std::string output;
};

void run(const Options& options) {
    io::OutputFile out = openOutput(options.output);
    CsvSink csv(out);
    TerminalObserver observer("nocdyn inverse-dynamics");
    if (app::isSpatialRobot(options.robot)) {  // space: spatial, a trajectory keyed x, y, z (roll, pitch, yaw)
        (void)app::runSpatialInverseDynamics(options, csv, observer);
    } else {
        (void)app::runInverseDynamics(options, csv, observer);
    }
    observer.finish();
    csv.finish();
    out.commit();
}

}  // namespace inverse_dynamics_command

void addInverseDynamicsCommand(CLI::App& app) {
    auto options = std::make_shared<inverse_dynamics_command::Options>();
    CLI::App* command = app.add_subcommand(
        "inverse-dynamics",
        "Actuator variables, rates, accelerations and forces of any robot along a platform trajectory\n"
        "(minimum-norm forces when the robot has more than three actuators; gravity and joint friction\n"
        "when its file sets them). Samples t_k = k / rate, k = 0..round(duration * rate) - 1, and writes\n"
        "CSV with the columns " +
            io::columnList(io::TableId::inverse_dynamics) +
            " (SI, shortest\n"
            "form that reads back exactly), row by row. Joint ranges and velocities, actuator efforts and\n"
            "reach are also checked between samples, at 40 points per period of the trajectory's highest\n"
            "harmonic; a rate at or below twice that frequency is refused. A pose out of reach, a singular\n"
            "posture, or one beyond a joint or effort limit is an error (no CSV file is written; on stdout,\n"
            "the rows before it). A two-DOF robot (motion: translation, pose [x, y]) takes a trajectory keyed\n"
            "x, y and its table has no theta column.\n"
            "A spatial robot (space: spatial) takes a trajectory file keyed x, y, z, roll, pitch, yaw (motion:\n"
            "translation: x, y, z), every coordinate given (absolute, m and rad, R = Rz(yaw) Ry(pitch)\n"
            "Rx(roll)), or a CSV of samples with the columns t and those coordinates; its table has the\n"
            "columns t, x, y, z, roll, pitch, yaw (or x, y, z), u1..un, du1..dun, ddu1..ddun, tau1..taun,\n"
            "kinetic.\n"
            "Example: nocdyn inverse-dynamics --robot robots/stewart.yaml --trajectory trajectories/stewart-sway.yaml "
            "-o sway.csv");
    addSamplingOptions(*command, *options);
    addRobotOption(*command, options->robot);
    command->add_option("--output,-o", options->output, "CSV file to write [default: stdout]")->check(nonEmptyPath());
    command->add_flag("--allow-limits", options->allow_limits,
                      "Write the CSV even when a joint range, joint velocity or effort limit is exceeded (warnings\n"
                      "on stderr); a pose out of reach, a singular posture or a non-finite value stays an error");
    command->add_flag("--reactions", options->reactions,
                      "Add every joint's reaction after the other columns: limb{i}_j{k}_fx, _fy [N] and _m [N m]\n"
                      "for limb i and joint k (1-based, file order): the wrench of the joint's inboard body on its\n"
                      "outboard body in the base frame, without the joint's own effort and friction (R: the force at\n"
                      "the axis, m = 0; P: the force normal to the joint and the couple about the outboard c.o.m.)");
    command->callback([options] { inverse_dynamics_command::run(*options); });
}

}  // namespace nocdyn::cli
