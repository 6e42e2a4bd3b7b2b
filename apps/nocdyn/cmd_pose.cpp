// nocdyn pose: everything the model knows at one platform pose, as text or JSON.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"

namespace nocdyn::cli {

namespace {

struct PoseOptions {
    double theta = 0.0, x = 0.0, y = 0.0;
    std::string robot;
    bool json = false;
};

nlohmann::json toJson(const Eigen::Ref<const Eigen::MatrixXd>& m) {
    nlohmann::json rows = nlohmann::json::array();
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
        nlohmann::json row = nlohmann::json::array();
        for (Eigen::Index k = 0; k < m.cols(); ++k) row.push_back(m(i, k));
        rows.push_back(m.cols() == 1 ? row[0] : row);
    }
    return rows;
}

std::string formatMatrix(const Matrix3& m, const char* indent) {
    std::ostringstream out;
    char line[160];
    for (int i = 0; i < 3; ++i) {
        std::snprintf(line, sizeof line, "%s[% .9e  % .9e  % .9e]\n", indent, m(i, 0), m(i, 1), m(i, 2));
        out << line;
    }
    return out.str();
}

void run(const PoseOptions& options) {
    const prr3::Model model(loadRobotOrDefault(options.robot));
    prr3::Data data;
    const Pose p(options.theta, options.x, options.y);
    if (const Status status = prr3::inverseDisplacement(model, data, p); !status) {
        throw Error(describe(status, model.parameters));
    }
    if (const Status status = prr3::velocityFromPlatformTwist(model, data, Twist::Zero()); !status) {
        throw Error(describe(status, model.parameters));
    }
    prr3::twistShaping(model, data);
    prr3::jointSpaceDynamics(model, data);
    const double half_stroke = 0.5 * model.parameters.stroke;
    const Status stroke = prr3::checkStroke(model, data);
    const Matrix3 D = data.D.asDiagonal();

    if (options.json) {
        nlohmann::json out;
        out["robot"] = model.parameters.name;
        out["pose"] = {{"theta", p(0)}, {"x", p(1)}, {"y", p(2)}};
        nlohmann::json limbs = nlohmann::json::array();
        for (int j = 0; j < prr3::kLimbs; ++j) {
            limbs.push_back({{"limb", j + 1},
                             {"u", data.u(j)},
                             {"phi_A", data.phi_A(j)},
                             {"phi_M", data.phi_M(j)},
                             {"d_M", data.d_M(j)},
                             {"A", {data.A[j].x(), data.A[j].y()}},
                             {"M", {data.Mj[j].x(), data.Mj[j].y()}},
                             {"stroke_used", std::abs(data.u(j)) / half_stroke}});
        }
        out["limbs"] = limbs;
        out["H"] = toJson(data.H);
        out["D"] = toJson(D);
        out["I"] = toJson(data.I);
        out["cond_H"] = data.cond_H;
        out["cond_D"] = data.cond_D;
        out["within_stroke"] = stroke.ok();
        std::cout << out.dump(2) << "\n";
        return;
    }
    constexpr double deg = 180.0 / std::numbers::pi;
    std::printf("robot %s, pose theta = %.9g rad (%.6g deg), x = %.9g m, y = %.9g m\n\n", model.parameters.name.c_str(),
                p(0), p(0) * deg, p(1), p(2));
    std::printf("limb  u_j [mm]     stroke used  phi_A [deg]  phi_M [deg]  A_j [m]                    M_j [m]\n");
    for (int j = 0; j < prr3::kLimbs; ++j) {
        std::printf("%-4d  %+11.6f  %9.2f %%  %11.6f  %11.6f  (%+.6f, %+.6f)  (%+.6f, %+.6f)\n", j + 1, data.u(j) * 1e3,
                    100.0 * std::abs(data.u(j)) / half_stroke, data.phi_A(j) * deg, data.phi_M(j) * deg, data.A[j].x(),
                    data.A[j].y(), data.Mj[j].x(), data.Mj[j].y());
    }
    std::printf("\nforward Jacobian H (eq. 7; first column in m):\n%s", formatMatrix(data.H, "  ").c_str());
    std::printf("inverse Jacobian D (eq. 6):\n%s", formatMatrix(D, "  ").c_str());
    std::printf("condition numbers: H diag(1/r,1,1): %.6g, D: %.6g (limit %.6g)\n", data.cond_H, data.cond_D,
                model.parameters.max_condition);
    std::printf("joint-space inertia I (eq. 23) [kg]:\n%s", formatMatrix(data.I, "  ").c_str());
    if (!stroke) std::printf("\nwarning: %s\n", describe(stroke, model.parameters).c_str());
}

}  // namespace

void addPoseCommand(CLI::App& app) {
    auto options = std::make_shared<PoseOptions>();
    CLI::App* command = app.add_subcommand(
        "pose",
        "Joint variables (u, phi_A, phi_M), joint centres A_j and M_j, the Jacobians H and D, their\n"
        "condition numbers, the joint-space inertia I and the stroke used, at one platform pose.\n"
        "Example: nocdyn pose 0.05 0.001 -0.002   (theta in rad, x and y in m)");
    command->add_option("THETA", options->theta, "Platform rotation from the reference posture [rad]")
        ->required()
        ->check(finiteIn(-1e6, 1e6, "rad"));
    command->add_option("X", options->x, "x of the platform centroid C [m]")->required()->check(finiteIn(-1e3, 1e3, "m"));
    command->add_option("Y", options->y, "y of the platform centroid C [m]")->required()->check(finiteIn(-1e3, 1e3, "m"));
    addRobotOption(*command, options->robot);
    command->add_flag("--json", options->json, "Write JSON instead of text");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
