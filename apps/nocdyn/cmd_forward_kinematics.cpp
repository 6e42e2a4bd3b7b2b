// nocdyn forward-kinematics: actuator displacements -> every platform pose that closes the
// three loops (direct displacement; see include/nocdyn/prr3/direct_kinematics.hpp).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/prr3/direct_kinematics.hpp"

namespace nocdyn::cli {

namespace {

struct ForwardKinematicsOptions {
    std::vector<double> u;
    std::string robot;
    bool json = false;
    bool all_branches = false;
};

void run(const ForwardKinematicsOptions& options) {
    const prr3::Model model(loadRobotOrDefault(options.robot, "forward-kinematics"));
    const prr3::JointVector u(options.u[0], options.u[1], options.u[2]);
    const auto all = prr3::directDisplacement(model, u, {.working_branch_only = false});
    std::vector<prr3::AssemblyMode> shown;
    int working = 0;
    for (const auto& mode : all) {
        working += mode.working;
        if (options.all_branches || mode.working) shown.push_back(mode);
    }
    const double half = 0.5 * model.parameters.stroke;
    const bool in_stroke = u.cwiseAbs().maxCoeff() <= half;
    if (options.json) {
        nlohmann::json out;
        out["robot"] = model.parameters.name;
        out["u"] = {u(0), u(1), u(2)};
        out["within_stroke"] = in_stroke;
        out["solutions_all_branches"] = all.size();
        out["solutions_working_branches"] = working;
        nlohmann::json list = nlohmann::json::array();
        for (const auto& mode : shown) {
            list.push_back({{"pose", {{"theta", mode.p(0)}, {"x", mode.p(1)}, {"y", mode.p(2)}}},
                            {"working", mode.working},
                            {"side", mode.side},
                            {"ahead", mode.ahead},
                            {"closure_residual", mode.closure_residual},
                            {"u_error", mode.u_error},
                            {"cond_H", mode.cond_H}});
        }
        out["solutions"] = list;
        std::cout << out.dump(2) << "\n";
        return;
    }
    std::printf("robot %s, u = [%+.6f, %+.6f, %+.6f] mm%s\n", model.parameters.name.c_str(), u(0) * 1e3, u(1) * 1e3,
                u(2) * 1e3, in_stroke ? "" : " (beyond the actuator stroke)");
    std::printf(
        "real solutions: %zu on any limb branches, %d with every limb on its working branch "
        "(phi_A in (0, pi/2))\n",
        all.size(), working);
    int index = 0;
    for (const auto& mode : shown) {
        std::printf("%d. theta = %+.12f rad (%+.6f deg), x = %+.9f mm, y = %+.9f mm%s\n", ++index, mode.p(0),
                    mode.p(0) * 180.0 / std::numbers::pi, mode.p(1) * 1e3, mode.p(2) * 1e3,
                    mode.working ? "" : "  [not on the working branches]");
        std::printf("   closure residual %.1e m, u recomputed from the pose within %.1e m, cond(H) %.3g\n",
                    mode.closure_residual, mode.u_error, mode.cond_H);
    }
    if (shown.empty())
        std::printf("no pose closes the three loops on the %s branches\n", options.all_branches ? "any" : "working");
}

}  // namespace

void addForwardKinematicsCommand(CLI::App& app) {
    auto options = std::make_shared<ForwardKinematicsOptions>();
    CLI::App* command = app.add_subcommand(
        "forward-kinematics",
        "Direct displacement: every platform pose [theta, x, y] with actuator displacements U1 U2 U3 [m].\n"
        "Exact: the loop closures reduce to one polynomial in tan(theta/2) solved by its companion matrix; each\n"
        "root is polished by Newton and checked by inverse displacement to 1e-12 m. By default only the poses\n"
        "with every limb on its working branch (phi_A in (0, pi/2)) are listed.");
    command->add_option("U", options->u, "Actuator displacements u1 u2 u3 [m]")
        ->required()
        ->expected(3)
        ->allow_extra_args(false)
        ->check(finiteIn(-1e3, 1e3, "m"));
    addRobotOption(*command, options->robot);
    command->add_flag("--json", options->json, "Print JSON");
    command->add_flag("--all-branches", options->all_branches,
                      "Also list the poses with a limb off its working branch");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
