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
#include "progress.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/io/escape.hpp"

namespace nocdyn::cli {

// This command's own names, apart from the other commands' (the folder compiles as one unity file).
namespace pose_command {

struct Options : app::PoseOptions {
    bool json = false;
};

constexpr double kDeg = 180.0 / std::numbers::pi;

nlohmann::json complianceJson(const app::PoseCompliance& c) {
    const auto n = static_cast<int>(c.K.rows());  // x, y, theta; a two-DOF robot's x, y
    nlohmann::json coordinates = nlohmann::json::array(), units = nlohmann::json::array();
    for (int r = 0; r < n; ++r) {
        coordinates.push_back(analysis::coordinateLabel(r));
        nlohmann::json row = nlohmann::json::array();
        for (int k = 0; k < n; ++k) row.push_back(analysis::stiffnessUnit(r, k));
        units.push_back(row);
    }
    nlohmann::json free = nlohmann::json::array();
    for (std::size_t i = 0; i < c.free_directions.size(); ++i) {
        const Eigen::VectorXd& v = c.free_directions[i];
        free.push_back({{"direction", std::vector<double>(v.data(), v.data() + v.size())},
                        {"description", c.free_descriptions[i]}});
    }
    nlohmann::json out;
    out["stiffness"] = {
        {"coordinates", coordinates}, {"matrix", matrixJson(c.K)}, {"units", units}, {"free_directions", free}};
    out["natural_frequencies"] = std::vector<double>(c.frequencies.data(), c.frequencies.data() + c.frequencies.size());
    // as the text and Python give them: rows x, y, theta; column i the shape of frequency i
    out["mode_shapes"] = matrixJson(c.mode_shapes);
    if (c.elastodynamic_frequencies) {
        const Eigen::VectorXd& f = *c.elastodynamic_frequencies;
        out["elastodynamic_frequencies"] = std::vector<double>(f.data(), f.data() + f.size());
    }
    out["first_frequency"] = {{"value", c.first_frequency}, {"model", c.first_frequency_model}};
    return out;
}

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
    if (r.compliance) out.update(complianceJson(*r.compliance));
    std::cout << out.dump(2) << "\n";
}

void printCompliance(const app::PoseCompliance& c) {
    std::printf("\nstiffness K at C (virtual joint method, gravity preload ignored; dQ = K dp, rows and columns:");
    const auto n = static_cast<int>(c.K.rows());  // 2: a two-DOF robot, over x, y
    for (int r = 0; r < n; ++r) std::printf(" %s", analysis::coordinateLabel(r).c_str());
    std::printf(")\n%sunits:\n", matrixText(c.K).c_str());
    for (int r = 0; r < n; ++r) {
        std::printf("  [");
        for (int k = 0; k < n; ++k) std::printf("%s%-8s", k ? "  " : "", analysis::stiffnessUnit(r, k).c_str());
        std::printf("]\n");
    }
    for (const std::string& text : c.free_descriptions)
        std::printf("free direction (no stiffness): %s\n", text.c_str());
    std::printf("natural frequencies (lumped model K v = w^2 M v) [Hz]:");
    for (const double f : c.frequencies) std::printf(" %.6g", f);
    std::printf("\nmode shapes (columns, mass-normalised; rows: %s):\n%s", n == 2 ? "x, y" : "x, y, theta",
                matrixText(c.mode_shapes).c_str());
    if (c.elastodynamic_frequencies) {
        std::printf("elastodynamic frequencies (%d DOF) [Hz]:", c.elastodynamic_dofs);
        for (const double f : *c.elastodynamic_frequencies) std::printf(" %.6g", f);
        std::printf("\n");
    }
    std::printf("first natural frequency [Hz]: %.6g (%s model)\n", c.first_frequency, c.first_frequency_model.c_str());
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
    if (r.compliance) printCompliance(*r.compliance);
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
    command->add_option("THETA", options->theta, "Platform rotation [rad] (not for a two-DOF robot)")
        ->check(within(app::kAngleRange));
    addRobotOption(*command, options->robot);
    command->add_flag("--json", options->json, "Write JSON instead of text");
    CLI::Option* theta = command->get_option("THETA");
    command->callback([options, theta] {
        if (theta->count() == 0) options->theta = std::numeric_limits<double>::quiet_NaN();
        TerminalObserver observer("nocdyn pose");
        const app::PoseResult result = app::runPose(*options, observer);
        options->json ? pose_command::printJson(result) : pose_command::printText(result);
    });
}

}  // namespace nocdyn::cli
