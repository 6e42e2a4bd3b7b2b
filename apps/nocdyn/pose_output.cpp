#include "pose_output.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>

#include "common.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/io/escape.hpp"

namespace nocdyn::cli {

nlohmann::json poseComplianceJson(const app::PoseCompliance& c) {
    const auto n = static_cast<int>(c.K.rows());  // x, y, theta; a two-DOF robot's x, y
    nlohmann::json coordinates = nlohmann::json::array(), units = nlohmann::json::array();
    for (int r = 0; r < n; ++r) {
        coordinates.push_back(coordinateLabel(r));
        nlohmann::json row = nlohmann::json::array();
        for (int k = 0; k < n; ++k) row.push_back(stiffnessUnit(r, k));
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
    out["first_frequency"] = {{"value", c.first_frequency}, {"model", nameOf(c.first_frequency_model)}};
    return out;
}

void printPoseCompliance(const app::PoseCompliance& c) {
    std::printf("\nstiffness K at C (virtual joint method, gravity preload ignored; dQ = K dp, rows and columns:");
    const auto n = static_cast<int>(c.K.rows());  // 2: a two-DOF robot, over x, y
    for (int r = 0; r < n; ++r) std::printf(" %s", coordinateLabel(r).c_str());
    std::printf(")\n%sunits:\n", matrixText(c.K).c_str());
    for (int r = 0; r < n; ++r) {
        std::printf("  [");
        for (int k = 0; k < n; ++k) std::printf("%s%-8s", k ? "  " : "", stiffnessUnit(r, k).c_str());
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
    std::printf("first natural frequency [Hz]: %.6g (%s model)\n", c.first_frequency,
                std::string(nameOf(c.first_frequency_model)).c_str());
}

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

void spatialJson(const app::SpatialPoseResult& r) {
    nlohmann::json out;
    out["robot"] = r.robot;
    for (std::size_t i = 0; i < r.coordinates.size(); ++i) out["pose"][r.coordinates[i]] = r.pose[i];
    for (const app::SpatialPoseLimb& l : r.limbs) {
        out["limbs"].push_back(
            {{"limb", l.limb}, {"name", l.name}, {"type", l.type}, {"q", l.q}, {"cond_J", l.cond_J}});
    }
    for (const app::SpatialPoseActuator& a : r.actuators) {
        out["actuators"].push_back(
            {{"actuator", a.actuator}, {"limb", a.limb}, {"joint", a.joint}, {"u", a.u}, {"range_used", a.range_used}});
    }
    out["A"] = matrixJson(r.A);
    out["cond_A"] = r.cond_A;
    out["within_limits"] = r.within_limits;
    out["tau"] = std::vector<double>(r.tau.data(), r.tau.data() + r.tau.size());
    const auto vec = [](const Eigen::Vector3d& v) { return std::vector<double>{v(0), v(1), v(2)}; };
    out["reactions"] = nlohmann::json::array();
    for (const app::SpatialPoseReaction& j : r.reactions) {
        out["reactions"].push_back({{"limb", j.limb},
                                    {"joint", j.joint},
                                    {"type", std::string(1, j.type)},
                                    {"point", vec(j.point)},
                                    {"force", vec(j.force)},
                                    {"moment", vec(j.moment)}});
    }
    out["balance_residual"] = r.balance_residual;
    std::cout << out.dump(2) << "\n";
}

}  // namespace

void printSpatialPose(const app::SpatialPoseResult& r, bool json) {
    if (json) {
        spatialJson(r);
        return;
    }
    std::printf("robot %s (spatial), pose", io::terminalText(r.robot).c_str());
    for (std::size_t i = 0; i < r.coordinates.size(); ++i) {
        const bool angle = i >= 3;
        std::printf("%s %s = %.9g %s", i ? "," : "", r.coordinates[i].c_str(), r.pose[i], angle ? "rad" : "m");
        if (angle) std::printf(" (%.6g deg)", r.pose[i] * kDegrees);
    }
    std::printf("\n\nlimb  type  cond J_j  joint variables, base to platform (U and S as 2 and 3 rotations)\n");
    for (const app::SpatialPoseLimb& l : r.limbs) {
        std::printf("%-4d  %-4s  %-8.4g ", l.limb, l.type.c_str(), l.cond_J);
        for (std::size_t k = 0; k < l.q.size(); ++k) {
            const bool revolute = l.kinds[k] == 'R';
            const double shown = revolute ? l.q[k] * kDegrees : l.q[k] * 1e3;
            std::printf(" %s %+.4f %s", l.of[k].c_str(), std::abs(shown) < 5e-5 ? 0.0 : shown, revolute ? "deg" : "mm");
        }
        std::printf("\n");
    }
    std::printf("\nactuator  limb  joint  u                 range used\n");
    for (const app::SpatialPoseActuator& a : r.actuators) {
        std::printf("%-8d  %-4d  %-5d  %+11.6f %-4s  %6.2f %%\n", a.actuator, a.limb, a.joint,
                    a.revolute ? a.u * kDegrees : a.u * 1e3, a.revolute ? "deg" : "mm", 100.0 * a.range_used);
    }
    std::printf(
        "\nactuation map du = A [v; w] (v the platform point's velocity, w the angular velocity; "
        "columns: v_x v_y v_z%s):\n%s",
        r.coordinates.size() == 6 ? " w_x w_y w_z" : "", matrixText(r.A).c_str());
    std::printf("condition numbers (lengths in metres, limit %.6g): actuation %.6g\n", r.max_condition, r.cond_A);
    std::printf("\nat rest under gravity: tau =");
    for (const double tau : r.tau) std::printf(" %+.6e", tau);
    std::printf(
        "\n\njoint reactions at rest (the inboard body on the outboard one, base frame; the moment about "
        "the joint's point, its efforts taken out):\nlimb  joint  force [N]: x, y, z                      "
        "moment [N m]: x, y, z\n");
    for (const app::SpatialPoseReaction& j : r.reactions) {
        std::printf("%-4d  %c%-4d  %+11.4e %+11.4e %+11.4e   %+11.4e %+11.4e %+11.4e\n", j.limb, j.type, j.joint,
                    j.force(0), j.force(1), j.force(2), j.moment(0), j.moment(1), j.moment(2));
    }
    std::printf("platform balance residual: %.3g\n", r.balance_residual);
    if (!r.within_limits) std::printf("\nwarning: %s\n", io::terminalText(r.limits).c_str());
}

}  // namespace nocdyn::cli
