// nocdyn forward-kinematics U...: binds app::ForwardKinematicsOptions and renders the assembly
// modes as text or JSON (poses x, y, theta; x, y for a two-DOF robot).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>

#include "app/forward_kinematics.hpp"
#include "app/pose_spatial.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "forward_kinematics_output.hpp"
#include "progress.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/model.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace forward_kinematics_command {

struct Options : app::ForwardKinematicsOptions {
    bool json = false;
};

void printJson(const app::ForwardKinematicsResult& r) {
    nlohmann::json out;
    out["robot"] = r.robot;
    out["u"] = r.u;
    out["within_limits"] = r.outside == 0;
    out["solutions_all_branches"] = r.solutions_all_branches;
    out["solutions_working_branches"] = r.solutions_working_branches;
    out["degenerate"] = r.degenerate;
    nlohmann::json list = nlohmann::json::array();
    for (const app::ForwardKinematicsSolution& s : r.solutions) {
        nlohmann::json pose = {{"x", s.pose(0)}, {"y", s.pose(1)}};
        if (r.task_dimension == 3) pose["theta"] = s.pose(2);
        list.push_back({{"pose", pose},
                        {"working", s.working},
                        {"branch", s.branch},
                        {"u_error", s.u_error},
                        {"condition", s.condition}});
    }
    out["solutions"] = list;
    std::cout << out.dump(2) << "\n";
}

void printText(const app::ForwardKinematicsResult& r) {
    std::printf("robot %s, u =", io::terminalText(r.robot).c_str());
    for (std::size_t a = 0; a < r.u.size(); ++a) {
        std::printf("%s %+.9g %s", a == 0 ? " [" : ",", r.u[a], r.revolute[a] ? "rad" : "m");
    }
    if (r.outside > 0) {
        std::printf("] (u%d beyond its joint's range)\n", r.outside);
    } else {
        std::printf("]\n");
    }
    std::printf("real solutions: %d on any limb branches, %d with every limb on its home branch (the working mode)\n",
                r.solutions_all_branches, r.solutions_working_branches);
    if (r.degenerate) {
        std::printf(
            "the closures do not isolate the pose for every choice of equations (an architecture singularity): "
            "the list may be incomplete\n");
    }
    int index = 0;
    for (const app::ForwardKinematicsSolution& s : r.solutions) {
        if (r.task_dimension == 2) {
            std::printf("%d. x = %+.9f mm, y = %+.9f mm%s\n", ++index, s.pose(0) * 1e3, s.pose(1) * 1e3,
                        s.working ? "" : "  [not on the home branches]");
        } else {
            std::printf("%d. x = %+.9f mm, y = %+.9f mm, theta = %+.12f rad (%+.6f deg)%s\n", ++index, s.pose(0) * 1e3,
                        s.pose(1) * 1e3, s.pose(2), s.pose(2) * 180.0 / std::numbers::pi,
                        s.working ? "" : "  [not on the home branches]");
        }
        std::printf("   branches [");
        for (std::size_t j = 0; j < s.branch.size(); ++j) std::printf("%s%+d", j == 0 ? "" : " ", s.branch[j]);
        std::printf("], u recomputed from the pose within %.1e, condition %.3g\n", s.u_error, s.condition);
    }
    if (r.solutions_all_branches == 0) {
        std::printf("no pose closes the loops with these actuator values: the robot cannot assemble\n");
    } else if (index == 0) {
        std::printf("no pose with every limb on its home branch; --all-branches lists the %d others\n",
                    r.solutions_all_branches);
    }
}

void run(const Options& options) {
    TerminalObserver observer("nocdyn forward-kinematics");
    app::ForwardKinematicsResult result;
    try {
        if (app::isSpatialRobot(options.robot)) {  // every mode found, poses x y z (roll pitch yaw)
            return printSpatialForwardKinematics(app::runSpatialForwardKinematics(options.robot, options.u, observer),
                                                 options.json);
        }
        result = app::runForwardKinematics(options, observer);
    } catch (const app::OptionError& e) {
        // the wrong number of values is a usage error (exit 2), as a malformed one is
        if (e.field() != "u") throw;
        throw CLI::ValidationError("U", commandLineText(e.message()));
    }
    if (options.json)
        printJson(result);
    else
        printText(result);
}

}  // namespace forward_kinematics_command

void addForwardKinematicsCommand(CLI::App& app) {
    auto options = std::make_shared<forward_kinematics_command::Options>();
    CLI::App* command = app.add_subcommand(
        "forward-kinematics",
        "Direct kinematics: every platform pose [x, y, theta] with actuator values U1 .. Un (one per actuated\n"
        "joint of --robot, in file order: m for P joints, rad for R joints; three for the paper's 3-PRR).\n"
        "Exact: the loop closures reduce to one polynomial in tan(theta/2) solved by its companion matrix; each\n"
        "root is polished by Newton and checked by inverse displacement on each limb's branch (+1/-1, 0 for\n"
        "limbs with one solution) to round-off. By default only the working mode is listed: every limb on its\n"
        "home branch (the one it has at home, as the dynamics use); --all-branches lists every assembly mode\n"
        "(sorted by theta). A two-DOF robot (motion: translation) gives poses [x, y]: the tool point on the\n"
        "circles of its locked limbs, both assembly modes listed by x. Values beyond an actuated joint's range are "
        "flagged (JSON: within_limits); the poses\n"
        "are listed all the same. Exit 0 also when no pose closes (zero solutions); exit 2 when the number of\n"
        "values is wrong.\n"
        "A spatial robot (space: spatial) gives poses [x, y, z] (motion: translation) or [x, y, z, roll, pitch,\n"
        "yaw]: the Delta's (three R-U-U limbs) two assembly modes in closed form (three spheres), other robots'\n"
        "modes found by many-start continuation; every mode is listed, the working one (limbs on their home\n"
        "branches, nearest home) marked; no pose (out of reach) is an error.");
    command->add_option("U", options->u, "Actuator values u1 .. un [m or rad]")
        ->required()
        ->expected(1, kMaxActuators)
        ->check(within(app::kLengthRange));
    addRobotOption(*command, options->robot);
    command->add_flag("--json", options->json, "Print JSON");
    command->add_flag("--all-branches", options->all_branches,
                      "Also list the poses with a limb off its working branch");
    command->callback([options] { forward_kinematics_command::run(*options); });
}

}  // namespace nocdyn::cli
