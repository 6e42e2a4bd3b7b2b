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

void run(const InverseDynamicsOptions& options) {
    const prr3::Model model(loadRobotOrDefault(options.robot));
    const PoseTrajectory trajectory = io::trajectoryByNameOrFile(options.trajectory);
    const auto times = prr3::sampleTimes(chooseDuration(options.duration, trajectory), options.rate);
    const auto policy = options.allow_limits ? prr3::LimitPolicy::record : prr3::LimitPolicy::error;
    const prr3::InverseDynamicsSeries series = prr3::sampleInverseDynamics(model, trajectory, times, policy);
    for (const std::string& violation : series.limit_violations) std::cerr << "nocdyn: warning: " << violation << "\n";
    writeTable(prr3::toTable(series), options.output);
}

}  // namespace

void addInverseDynamicsCommand(CLI::App& app) {
    auto options = std::make_shared<InverseDynamicsOptions>();
    CLI::App* command = app.add_subcommand(
        "inverse-dynamics",
        "Actuator displacements, rates, accelerations and forces along a platform trajectory.\n"
        "Samples t_k = k / rate, k = 0..round(duration * rate) - 1, and writes CSV with the columns\n"
        "t,x,y,theta,u1,u2,u3,du1,du2,du3,ddu1,ddu2,ddu3,tau1,tau2,tau3,kinetic (SI, 17 digits).\n"
        "A sample outside the workspace, at a singular posture, or beyond the actuator stroke or\n"
        "peak force is an error (no CSV is written).");
    addTrajectoryOptions(*command, *options);
    command->add_flag("--allow-limits", options->allow_limits,
                      "Write the CSV even when the stroke or peak force is exceeded (warnings on stderr)");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
