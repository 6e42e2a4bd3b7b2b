// nocdyn pose X Y THETA: binds app::PoseOptions and renders the report as text or JSON.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <numbers>

#include "app/pose.hpp"
#include "commands.hpp"
#include "common.hpp"
#include "pose_output.hpp"
#include "progress.hpp"
#include "nocdyn/io/escape.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace pose_command {

struct Options : app::PoseOptions {
    bool json = false;
    std::vector<double> angles;  ///< a spatial robot's ROLL PITCH YAW, after X Y Z
};

constexpr double kDeg = 180.0 / std::numbers::pi;

void printJson(const app::PoseResult& r) {
    nlohmann::json out;
    out["robot"] = r.robot;
    out["pose"] = {{"x", r.pose(0)}, {"y", r.pose(1)}};
    if (r.task_dimension == 3) out["pose"]["theta"] = r.pose(2);
    for (const app::PoseLimb& l : r.limbs) {
        out["limbs"].push_back({{"limb", l.limb},
                                {"name", l.name},
                                {"type", l.type},
                                {"q", {l.q(0), l.q(1), l.q(2)}},
                                {"cond_J", l.cond_J}});
    }
    for (const app::PoseActuator& a : r.actuators) {
        out["actuators"].push_back(
            {{"actuator", a.actuator}, {"limb", a.limb}, {"joint", a.joint}, {"u", a.u}, {"range_used", a.range_used}});
    }
    out["A"] = matrixJson(r.A);
    out["cond_A"] = r.cond_A;
    out["coordinates"] = r.coordinates;
    out["I"] = matrixJson(r.I);
    out["within_limits"] = r.within_limits;
    out["tau"] = std::vector<double>(r.tau.data(), r.tau.data() + r.tau.size());
    for (const app::PoseReaction& j : r.reactions) {
        out["reactions"].push_back({{"limb", j.limb},
                                    {"joint", j.joint},
                                    {"type", j.revolute ? "R" : "P"},
                                    {"fx", j.f(0)},
                                    {"fy", j.f(1)},
                                    {"m", j.f(2)}});
    }
    if (r.compliance) out.update(poseComplianceJson(*r.compliance));
    std::cout << out.dump(2) << "\n";
}

void printText(const app::PoseResult& r) {
    if (r.task_dimension == 2) {
        std::printf("robot %s (motion: translation), pose x = %.9g m, y = %.9g m\n\n",
                    io::terminalText(r.robot).c_str(), r.pose(0), r.pose(1));
    } else {
        std::printf("robot %s, pose x = %.9g m, y = %.9g m, theta = %.9g rad (%.6g deg)\n\n",
                    io::terminalText(r.robot).c_str(), r.pose(0), r.pose(1), r.pose(2), r.pose(2) * kDeg);
    }
    const char* columns = r.task_dimension == 2 ? "x, y" : "x, y, theta";
    std::printf("limb  type  q1                q2                q3                cond J_j\n");
    for (const app::PoseLimb& l : r.limbs) {
        std::printf("%-4d  %s  ", l.limb, l.type.c_str());
        for (std::size_t k = 0; k < 3; ++k) {
            const double q = l.q(static_cast<Eigen::Index>(k));
            // a value that rounds to zero at six decimals (rounding noise, -0) is shown as +0.000000
            const double shown = l.revolute[k] ? q * kDeg : q * 1e3;
            std::printf(l.revolute[k] ? "%+11.6f deg   " : "%+11.6f mm    ", std::abs(shown) < 5e-7 ? 0.0 : shown);
        }
        std::printf("%.4g\n", l.cond_J);
    }
    std::printf("\nactuator  limb  joint  u                 range used\n");
    for (const app::PoseActuator& a : r.actuators) {
        std::printf("%-8d  %-4d  %-5d  %+11.6f %-4s  %6.2f %%\n", a.actuator, a.limb, a.joint,
                    a.revolute ? a.u * kDeg : a.u * 1e3, a.revolute ? "deg" : "mm", 100.0 * a.range_used);
    }
    std::printf("\nactuation map du = A dp/dt (eq. 5 generalised; rows: actuators, columns: %s):\n%s", columns,
                matrixText(r.A).c_str());
    std::printf("condition numbers (scaled, limit %.6g): actuation %.6g\n", r.max_condition, r.cond_A);
    if (r.task_dimension == 2) {
        std::printf("inertia I (eq. 23) in the tool point's x, y (E^T I E):\n%s", matrixText(r.I).c_str());
    } else {
        std::printf(r.coordinates == "actuators" ? "joint-space inertia I (eq. 23), in the actuator variables:\n%s"
                                                 : "inertia I (eq. 23) in the platform pose x, y, theta (redundant "
                                                   "actuation):\n%s",
                    matrixText(r.I).c_str());
    }
    std::printf("\nat rest under gravity: tau =");
    for (const double tau : r.tau) std::printf(" %+.6e", tau);
    std::printf("\njoint reactions (base frame, inboard body on outboard body, effort and friction taken out):\n");
    std::printf("limb  joint  fx [N]           fy [N]           m [N m]\n");
    for (const app::PoseReaction& j : r.reactions) {
        std::printf("%-4d  %d %s    %+.9e  %+.9e  %+.9e\n", j.limb, j.joint, j.revolute ? "R" : "P", j.f(0), j.f(1),
                    j.f(2));
    }
    if (r.compliance) printPoseCompliance(*r.compliance);
    if (!r.within_limits) std::printf("\nwarning: %s\n", io::terminalText(r.limits).c_str());
}

}  // namespace pose_command

void addPoseCommand(CLI::App& app) {
    auto options = std::make_shared<pose_command::Options>();
    CLI::App* command = app.add_subcommand(
        "pose",
        "At one platform pose of any robot: every limb's joint variables and the condition number of\n"
        "its Jacobian, the actuator variables and how much of their range they use, the actuation map\n"
        "du = A dp/dt and its condition number, the inertia I (eq. 23), and at rest under gravity the\n"
        "actuator forces and every joint's reaction (base frame, the inboard body on the outboard body,\n"
        "the joint's effort and friction taken out; JSON: \"tau\" and \"reactions\").\n"
        "When the robot file declares compliance (stiffness, elastic), also the stiffness K and the\n"
        "natural frequencies (JSON: \"stiffness\", \"natural_frequencies\", \"elastodynamic_frequencies\").\n"
        "Every pose vector and matrix is in the order x, y, theta (a two-DOF robot, motion: translation:\n"
        "X Y only, and x, y).\n"
        "Example: nocdyn pose 0.001 -0.002 0.05 --robot robots/3-rrr.yaml   (x and y in m, theta in rad)");
    command->add_option("X", options->x, "x of the platform's operation point C [m]")
        ->required()
        ->check(within(app::kLengthRange));
    command->add_option("Y", options->y, "y of the platform's operation point C [m]")
        ->required()
        ->check(within(app::kLengthRange));
    // optional: a two-DOF robot (motion: translation) has none, a turning platform needs it
    command
        ->add_option("THETA", options->theta,
                     "Platform rotation [rad] (not for a two-DOF robot); a spatial robot's Z [m]")
        ->check(within(app::kAngleRange));
    command->add_option("ANGLES", options->angles, "A spatial robot's ROLL PITCH YAW [rad] (motion: full)")
        ->expected(0, 3)
        ->check(within(app::kAngleRange));
    addRobotOption(*command, options->robot);
    command->add_flag("--json", options->json, "Write JSON instead of text");
    CLI::Option* theta = command->get_option("THETA");
    command->callback([options, theta] {
        if (theta->count() == 0) options->theta = std::numeric_limits<double>::quiet_NaN();
        TerminalObserver observer("nocdyn pose");
        if (app::isSpatialRobot(options->robot)) {  // X Y Z [ROLL PITCH YAW]
            std::vector<double> pose{options->x, options->y};
            if (theta->count() > 0) pose.push_back(options->theta);
            pose.insert(pose.end(), options->angles.begin(), options->angles.end());
            return printSpatialPose(app::runSpatialPose(options->robot, pose, observer), options->json);
        }
        if (!options->angles.empty()) throw Error("pose: ROLL PITCH YAW are for a spatial robot");
        const app::PoseResult result = app::runPose(*options, observer);
        options->json ? pose_command::printJson(result) : pose_command::printText(result);
    });
}

}  // namespace nocdyn::cli
