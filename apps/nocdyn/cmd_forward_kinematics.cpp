// nocdyn forward-kinematics: actuator values -> every platform pose that closes the loops.
// The paper's 3-PRR (short form, or no --robot) keeps its hand-derived solver and output
// (include/nocdyn/prr3/direct_kinematics.hpp); any other robot file goes to the general one
// (include/nocdyn/direct_kinematics.hpp).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/prr3/direct_kinematics.hpp"

namespace nocdyn::cli {

namespace {

struct ForwardKinematicsOptions {
    std::vector<double> u;
    std::string robot;
    bool json = false;
    bool all_branches = false;
};

/// "--robot F has N actuators" unless N values were given: a usage error (exit 2).
void checkCount(const ForwardKinematicsOptions& options, const std::string& robot, int actuators) {
    if (static_cast<int>(options.u.size()) == actuators) return;
    throw CLI::ValidationError("U", robot + " has " + std::to_string(actuators) + " actuators: give " +
                                        std::to_string(actuators) + " values U1 .. U" + std::to_string(actuators) +
                                        ", not " + std::to_string(options.u.size()));
}

/// Any robot file: the general solver, every limb's branch.
void runGeneral(const ForwardKinematicsOptions& options) {
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    checkCount(options, model.description.name + " (" + options.robot + ")", model.actuators);
    ActuatorVector u(model.actuators);
    for (int a = 0; a < model.actuators; ++a) u(a) = options.u[static_cast<std::size_t>(a)];
    Data data(model);
    AssemblyModes modes;
    if (const Status status = directKinematics(model, data, u, modes); !status) {
        throw Error(options.robot + ": " + describe(status, model));
    }
    int working = 0;
    for (const AssemblyMode& mode : modes) working += mode.working ? 1 : 0;
    const auto shown = [&](const AssemblyMode& mode) { return options.all_branches || mode.working; };
    const auto branches = [&](const AssemblyMode& mode) {
        return std::vector<int>(mode.branch.begin(), mode.branch.begin() + model.limbs);
    };
    if (options.json) {
        nlohmann::json out;
        out["robot"] = model.description.name;
        out["u"] = options.u;
        out["solutions_all_branches"] = modes.count;
        out["solutions_working_branches"] = working;
        out["degenerate"] = modes.degenerate;
        nlohmann::json list = nlohmann::json::array();
        for (const AssemblyMode& mode : modes) {
            if (!shown(mode)) continue;
            list.push_back({{"pose", {{"theta", mode.p(0)}, {"x", mode.p(1)}, {"y", mode.p(2)}}},
                            {"working", mode.working},
                            {"branch", branches(mode)},
                            {"u_error", mode.u_error},
                            {"condition", mode.condition}});
        }
        out["solutions"] = list;
        std::cout << out.dump(2) << "\n";
        return;
    }
    std::printf("robot %s, u =", model.description.name.c_str());
    for (int a = 0; a < model.actuators; ++a) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)])];
        const bool revolute = limb.type[static_cast<std::size_t>(model.actuator_joint[static_cast<std::size_t>(a)])] ==
                              JointType::revolute;
        std::printf("%s %+.9g %s", a == 0 ? " [" : ",", u(a), revolute ? "rad" : "m");
    }
    std::printf("]\n");
    std::printf("real solutions: %d on any limb branches, %d with every limb on its home branch (the working mode)\n",
                modes.count, working);
    if (modes.degenerate) {
        std::printf(
            "the closures do not isolate the pose for every choice of equations (an architecture singularity): "
            "the list may be incomplete\n");
    }
    int index = 0;
    for (const AssemblyMode& mode : modes) {
        if (!shown(mode)) continue;
        std::printf("%d. theta = %+.12f rad (%+.6f deg), x = %+.9f mm, y = %+.9f mm%s\n", ++index, mode.p(0),
                    mode.p(0) * 180.0 / std::numbers::pi, mode.p(1) * 1e3, mode.p(2) * 1e3,
                    mode.working ? "" : "  [not on the home branches]");
        std::printf("   branches [");
        for (int j = 0; j < model.limbs; ++j)
            std::printf("%s%+d", j == 0 ? "" : " ", mode.branch[static_cast<std::size_t>(j)]);
        std::printf("], u recomputed from the pose within %.1e, condition %.3g\n", mode.u_error, mode.condition);
    }
    if (modes.count == 0) {
        std::printf("no pose closes the loops with these actuator values: the robot cannot assemble\n");
    } else if (index == 0) {
        std::printf("no pose with every limb on its home branch; --all-branches lists the %d others\n", modes.count);
    }
}

void run(const ForwardKinematicsOptions& options) {
    if (!options.robot.empty() && io::isGeneralForm(io::readRobotFileText(options.robot), options.robot)) {
        runGeneral(options);
        return;
    }
    const prr3::Model model(loadRobotOrDefault(options.robot, "forward-kinematics"));
    checkCount(options, model.parameters.name, 3);
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
        "Direct kinematics: every platform pose [theta, x, y] with actuator values U1 .. Un (one per actuated\n"
        "joint of --robot, in file order: m for P joints, rad for R joints; three for the paper's 3-PRR).\n"
        "Exact: the loop closures reduce to one polynomial in tan(theta/2) solved by its companion matrix; each\n"
        "root is polished by Newton and checked by inverse displacement on each limb's branch (+1/-1, 0 for\n"
        "limbs with one solution) to round-off. By default only the working mode is listed: every limb on its\n"
        "home branch (for the paper's 3-PRR, phi_A in (0, pi/2)); --all-branches lists every assembly mode.\n"
        "Exit 0 also when no pose closes (zero solutions); exit 2 when the number of values is wrong.");
    command->add_option("U", options->u, "Actuator values u1 .. un [m or rad]")
        ->required()
        ->expected(1, kMaxActuators)
        ->check(finiteIn(-1e3, 1e3, "m"));
    addRobotOption(*command, options->robot);
    command->add_flag("--json", options->json, "Print JSON");
    command->add_flag("--all-branches", options->all_branches,
                      "Also list the poses with a limb off its working branch");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
