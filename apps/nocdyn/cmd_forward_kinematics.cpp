// nocdyn forward-kinematics: actuator values -> every platform pose that closes the loops,
// by the general solver (include/nocdyn/direct_kinematics.hpp) for any robot file (the 3-PRR
// short form, or no --robot, expanded to the general robot).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/model.hpp"

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

/// 1-based number of the first actuator whose value is outside its joint's range, else 0.
int outsideRange(const Model& model, const ActuatorVector& u) {
    for (int a = 0; a < model.actuators; ++a) {
        const auto ia = static_cast<std::size_t>(a);
        const JointLimits& limits = model.limb[static_cast<std::size_t>(model.actuator_limb[ia])]
                                        .limits[static_cast<std::size_t>(model.actuator_joint[ia])];
        if (u(a) < limits.lower || u(a) > limits.upper) return a + 1;
    }
    return 0;
}

/// Any robot file: the general solver, every limb's branch.
void runGeneral(const ForwardKinematicsOptions& options) {
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    checkCount(options, model.description.name + (options.robot.empty() ? "" : " (" + options.robot + ")"),
               model.actuators);
    ActuatorVector u(model.actuators);
    for (int a = 0; a < model.actuators; ++a) u(a) = options.u[static_cast<std::size_t>(a)];
    const int outside = outsideRange(model, u);
    if (outside > 0) {
        std::cerr << "nocdyn: warning: u" << outside
                  << " is outside its joint's range (the command line takes m and rad: 5 mm is 0.005)\n";
    }
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
        out["within_limits"] = outside == 0;
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
    std::printf("robot %s, u =", io::terminalText(model.description.name).c_str());
    for (int a = 0; a < model.actuators; ++a) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)])];
        const bool revolute = limb.type[static_cast<std::size_t>(model.actuator_joint[static_cast<std::size_t>(a)])] ==
                              JointType::revolute;
        std::printf("%s %+.9g %s", a == 0 ? " [" : ",", u(a), revolute ? "rad" : "m");
    }
    if (outside > 0) {
        std::printf("] (u%d beyond its joint's range)\n", outside);
    } else {
        std::printf("]\n");
    }
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

void run(const ForwardKinematicsOptions& options) { runGeneral(options); }

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
        "home branch (the one it has at home, as the dynamics use); --all-branches lists every assembly mode.\n"
        "Values beyond an actuated joint's range are flagged (JSON: within_limits); the poses are listed all the\n"
        "same. Exit 0 also when no pose closes (zero solutions); exit 2 when the number of values is wrong.");
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
