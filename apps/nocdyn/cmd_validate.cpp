// nocdyn validate: our inverse dynamics against Simbody and MuJoCo on one trajectory.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "engine_comparison.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"

namespace nocdyn::cli {

namespace {

void run(const TrajectoryOptions& options) {
    const RobotParameters robot = loadRobotOrDefault(options.robot);
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    const auto times = prr3::sampleTimes(chooseDuration(options.duration, trajectory), options.rate);
    const EngineComparison comparison = compareWithEngines(robot, trajectory, times);
    writeTable(toTable(comparison), options.output);
    std::cerr << "nocdyn validate: " << trajectory.name << ", " << times.size() << " samples\n"
              << agreementTable(comparison);
}

}  // namespace

void addValidateCommand(CLI::App& app) {
    auto options = std::make_shared<TrajectoryOptions>();
    options->rate = 1000.0;
    CLI::App* command = app.add_subcommand(
        "validate",
        "Actuator forces of our NOC model against two independent multibody engines (Simbody, the\n"
        "reference, and MuJoCo), built from the same robot file and driven by the same platform\n"
        "trajectory. Writes CSV with the columns t,u1..u3,tau1..tau3,simbody_u1..3,simbody_tau1..3,\n"
        "mujoco_u1..3,mujoco_tau1..3,simbody_dtau1..3,mujoco_dtau1..3 and prints on stderr the largest\n"
        "absolute and relative difference per actuator and engine.");
    addTrajectoryOptions(*command, *options);
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
