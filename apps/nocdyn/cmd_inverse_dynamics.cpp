// nocdyn inverse-dynamics: a pose trajectory -> u, du, ddu, tau as CSV (eqs. 5, 20, Appendix A).
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/prr3/sampling.hpp"

namespace nocdyn::cli {

namespace {

struct InverseDynamicsOptions : TrajectoryOptions {
    bool allow_limits = false;
};

// Rows are written as they are computed (memory does not depend on the sample count); a file
// is only renamed into place once every sample passed, so an error leaves no partial file.
void run(const InverseDynamicsOptions& options) {
    const prr3::Model model(loadRobotOrDefault(options.robot));
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    const prr3::SampleGrid grid = prr3::sampleGrid(chooseDuration(options.duration, trajectory), options.rate);
    prr3::requireRateAboveNyquist(trajectory, grid.rate);
    const auto policy = options.allow_limits ? prr3::LimitPolicy::record : prr3::LimitPolicy::error;
    io::OutputFile out = openOutput(options.output);
    io::CsvWriter csv(out, prr3::inverseDynamicsColumns(), /*background=*/true);  // formats while we compute
    const prr3::LimitSummary summary = prr3::streamInverseDynamics(
        model, trajectory, grid, policy, [&](const prr3::InverseDynamicsSample& sample) { csv.row(prr3::toRow(sample)); });
    csv.finish();
    out.commit();
    for (const std::string& violation : summary.limit_violations) std::cerr << "nocdyn: warning: " << violation << "\n";
}

}  // namespace

void addInverseDynamicsCommand(CLI::App& app) {
    auto options = std::make_shared<InverseDynamicsOptions>();
    CLI::App* command = app.add_subcommand(
        "inverse-dynamics",
        "Actuator displacements, rates, accelerations and forces along a platform trajectory.\n"
        "Samples t_k = k / rate, k = 0..round(duration * rate) - 1, and writes CSV with the columns\n"
        "t,x,y,theta,u1,u2,u3,du1,du2,du3,ddu1,ddu2,ddu3,tau1,tau2,tau3,kinetic (SI, shortest form that\n"
        "reads back exactly), row by row. Stroke, peak force and workspace are also checked between\n"
        "samples, at 40 points per period of the trajectory's highest harmonic; a rate at or below twice\n"
        "that frequency is refused. A pose outside the workspace, a singular posture, or one beyond the\n"
        "actuator stroke or peak force is an error (no CSV file is written; on stdout, the rows before it).");
    addTrajectoryOptions(*command, *options);
    command->add_flag("--allow-limits", options->allow_limits,
                      "Write the CSV even when the stroke or peak force is exceeded (warnings on stderr); a pose\n"
                      "outside the workspace, a singular posture or a non-finite value stays an error");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
