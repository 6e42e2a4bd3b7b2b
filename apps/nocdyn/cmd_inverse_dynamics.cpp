// nocdyn inverse-dynamics: a pose trajectory -> u, du, ddu, tau as CSV (eqs. 5, 20, Appendix A).
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/tables/tables.hpp"
#include "nocdyn/analysis/sampling.hpp"

namespace nocdyn::cli {

namespace {

struct InverseDynamicsOptions : TrajectoryOptions {
    bool allow_limits = false;
    bool reactions = false;
};

// Rows are written as they are computed (memory does not depend on the sample count); a file
// is only renamed into place once every sample passed, so an error leaves no partial file.
void run(const InverseDynamicsOptions& options) {
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    const SampleGrid grid = sampleGrid(chooseDuration(options.duration, trajectory), options.rate);
    requireRateAboveNyquist(trajectory, grid.rate);
    const auto policy = options.allow_limits ? LimitPolicy::record : LimitPolicy::error;
    io::OutputFile out = openOutput(options.output);
    std::vector<std::string> columns = io::inverseDynamicsColumns(model.actuators);
    if (options.reactions) {
        for (std::string& name : io::reactionColumns(model.limbs)) columns.push_back(std::move(name));
    }
    io::CsvWriter csv(out, columns, /*background=*/true);  // formats while we compute
    std::vector<double> row;
    Progress progress(static_cast<double>(grid.count) / grid.rate);
    const LimitSummary summary =
        options.reactions
            ? streamInverseDynamicsWithReactions(model, trajectory, grid, policy,
                                                 [&](const InverseDynamicsSample& sample, const Reactions& r) {
                                                     io::inverseDynamicsRow(sample, row);
                                                     io::appendReactions(r, model.limbs, row);
                                                     csv.row(row);
                                                     progress.update(sample.t);
                                                 })
            : streamInverseDynamics(model, trajectory, grid, policy, [&](const InverseDynamicsSample& sample) {
                  io::inverseDynamicsRow(sample, row);
                  csv.row(row);
                  progress.update(sample.t);
              });
    progress.finish();
    csv.finish();
    out.commit();
    for (const std::string& violation : summary.limit_violations)
        std::cerr << "nocdyn: warning: " << io::terminalText(violation) << "\n";
}

}  // namespace

void addInverseDynamicsCommand(CLI::App& app) {
    auto options = std::make_shared<InverseDynamicsOptions>();
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
            "the rows before it).");
    addTrajectoryOptions(*command, *options);
    command->add_flag("--allow-limits", options->allow_limits,
                      "Write the CSV even when a joint range, joint velocity or effort limit is exceeded (warnings\n"
                      "on stderr); a pose out of reach, a singular posture or a non-finite value stays an error");
    command->add_flag("--reactions", options->reactions,
                      "Add every joint's reaction after the other columns: limb{i}_j{k}_fx, _fy [N] and _m [N m]\n"
                      "for limb i and joint k (1-based, file order): the wrench of the joint's inboard body on its\n"
                      "outboard body in the base frame, without the joint's own effort and friction (R: the force at\n"
                      "the axis, m = 0; P: the force normal to the joint and the couple about the outboard c.o.m.)");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
