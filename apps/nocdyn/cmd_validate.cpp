// nocdyn validate: our inverse dynamics of any robot against Simbody and MuJoCo on one trajectory.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/validation/agreement.hpp"

namespace nocdyn::cli {

namespace {

void run(const TrajectoryOptions& options) {
    const RobotDescription robot = loadRobotDescriptionOrDefault(options.robot);
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    const auto times = sampleTimes(chooseDuration(options.duration, trajectory), options.rate);
    const validation::EngineComparison comparison = validation::compareWithEngines(robot, trajectory, times);
    writeTable(validation::toTable(comparison), options.output);
    std::cerr << "nocdyn validate: " << robot.name << ", " << trajectory.name << ", " << times.size() << " samples\n"
              << validation::agreementTable(comparison);
}

}  // namespace

void addValidateCommand(CLI::App& app) {
    auto options = std::make_shared<TrajectoryOptions>();
    options->rate = 1000.0;
    CLI::App* command = app.add_subcommand(
        "validate",
        "Actuator forces of our NOC model of any robot against two independent multibody engines\n"
        "(Simbody, the reference, and MuJoCo), each built from the same robot file (loops closed at a\n"
        "revolute joint; gravity and joint friction included) and driven by the same platform\n"
        "trajectory. Writes CSV with the columns t,u1..un,tau1..taun,simbody_u1..n,simbody_tau1..n,\n"
        "mujoco_u1..n,mujoco_tau1..n,simbody_dtau1..n,mujoco_dtau1..n and prints on stderr the largest\n"
        "absolute and relative difference per actuator and engine.");
    addTrajectoryOptions(*command, *options);
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
