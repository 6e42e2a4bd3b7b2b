// nocdyn pose: everything the model knows at one platform pose, for any robot, as text or JSON.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "common.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/reactions.hpp"

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
        rows.push_back(row);
    }
    return rows;
}

std::string formatMatrix(const Eigen::Ref<const Eigen::MatrixXd>& m, const char* indent) {
    std::ostringstream out;
    char cell[40];
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
        out << indent << "[";
        for (Eigen::Index k = 0; k < m.cols(); ++k) {
            std::snprintf(cell, sizeof cell, "%s% .9e", k ? "  " : "", m(i, k));
            out << cell;
        }
        out << "]\n";
    }
    return out.str();
}

bool revolute(const Model& model, int j, int k) {
    return model.limb[static_cast<std::size_t>(j)].type[static_cast<std::size_t>(k)] == JointType::revolute;
}

/// Fraction of the joint's range [lower, upper] used on the side q is on (0 when unlimited).
double rangeUsed(const JointLimits& limits, double q) {
    const double bound = q >= 0.0 ? limits.upper : -limits.lower;
    return std::isfinite(bound) && bound > 0.0 ? std::abs(q) / bound : 0.0;
}

/// A pose outside a joint's range, said loudly on standard error (also with --json); far outside
/// (more than 10 times the range), most likely a unit slip: the command line takes m and rad.
void warnOutsideRange(const Model& model, const Data& data, const Status& limits) {
    double worst = 0.0;
    for (int j = 0; j < model.limbs; ++j) {
        for (int k = 0; k < 3; ++k) {
            worst =
                std::max(worst, rangeUsed(model.limb[static_cast<std::size_t>(j)].limits[static_cast<std::size_t>(k)],
                                          data.limb[static_cast<std::size_t>(j)].q(k)));
        }
    }
    std::fprintf(stderr, "nocdyn: warning: %s%s\n", describe(limits, model).c_str(),
                 worst > 10.0 ? " -- far outside the range: the command line takes m and rad (5 mm is 0.005)" : "");
}

/// The compliance results at the pose, when the robot file declares any compliance.
struct ComplianceAtPose {
    analysis::StiffnessData K;
    analysis::LumpedModes modes;
    analysis::ElastodynamicModes elastodynamic;
    bool elastic = false;
};

std::optional<ComplianceAtPose> complianceAtPose(const Model& model, const Data& data) {
    if (!model.description.hasCompliance()) return std::nullopt;
    ComplianceAtPose out;
    const analysis::StiffnessModel compliance(model);
    if (const Status status = analysis::cartesianStiffness(model, compliance, data, out.K); !status) {
        throw Error(describe(status, model));
    }
    analysis::lumpedModes(model, data, out.K, out.modes);
    out.elastic = model.description.hasElasticBody();
    if (out.elastic) {
        if (const Status status = analysis::elastodynamicModes(model, compliance, data, out.elastodynamic); !status) {
            throw Error(describe(status, model));
        }
    }
    return out;
}

nlohmann::json complianceJson(const ComplianceAtPose& c) {
    nlohmann::json coordinates = nlohmann::json::array(), units = nlohmann::json::array();
    for (int r = 0; r < 3; ++r) {
        coordinates.push_back(analysis::coordinateLabel(r));
        nlohmann::json row = nlohmann::json::array();
        for (int k = 0; k < 3; ++k) row.push_back(analysis::stiffnessUnit(r, k));
        units.push_back(row);
    }
    nlohmann::json free = nlohmann::json::array();
    for (int i = 0; i < c.K.free_directions; ++i) {
        const Vector3 v = c.K.free.col(i);
        const Vector3 r = analysis::reported(v);
        free.push_back({{"direction", {r(0), r(1), r(2)}}, {"description", analysis::describeDirection(v)}});
    }
    nlohmann::json out;
    out["stiffness"] = {{"coordinates", coordinates},
                        {"matrix", toJson(analysis::reported(c.K.K))},
                        {"units", units},
                        {"free_directions", free}};
    out["natural_frequencies"] = {c.modes.frequency(0), c.modes.frequency(1), c.modes.frequency(2)};
    nlohmann::json shapes = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) {
        const Vector3 r = analysis::reported(Vector3(c.modes.shape.col(i)));
        shapes.push_back({r(0), r(1), r(2)});
    }
    out["mode_shapes"] = shapes;
    if (c.elastic) {
        out["elastodynamic_frequencies"] = std::vector<double>(
            c.elastodynamic.frequency.data(), c.elastodynamic.frequency.data() + c.elastodynamic.frequency.size());
    }
    return out;
}

void printCompliance(const ComplianceAtPose& c) {
    std::printf("\nstiffness K at C (virtual joint method, gravity preload ignored; dQ = K dp, rows and columns:");
    for (int r = 0; r < 3; ++r) std::printf(" %s", analysis::coordinateLabel(r).c_str());
    std::printf(")\n%s", formatMatrix(analysis::reported(c.K.K), "  ").c_str());
    std::printf("units:\n");
    for (int r = 0; r < 3; ++r) {
        std::printf("  [");
        for (int k = 0; k < 3; ++k) std::printf("%s%-8s", k ? "  " : "", analysis::stiffnessUnit(r, k).c_str());
        std::printf("]\n");
    }
    for (int i = 0; i < c.K.free_directions; ++i) {
        std::printf("free direction (no stiffness): %s\n",
                    analysis::describeDirection(Vector3(c.K.free.col(i))).c_str());
    }
    std::printf("natural frequencies (lumped model K v = w^2 M v) [Hz]: %.6g %.6g %.6g\n", c.modes.frequency(0),
                c.modes.frequency(1), c.modes.frequency(2));
    std::printf("mode shapes (columns, mass-normalised; rows:");
    for (int r = 0; r < 3; ++r) std::printf(" %s", analysis::coordinateLabel(r).c_str());
    std::printf("):\n%s", formatMatrix(analysis::reported(c.modes.shape), "  ").c_str());
    if (c.elastic) {
        std::printf("elastodynamic frequencies (%d DOF) [Hz]:", c.elastodynamic.dofs);
        for (Eigen::Index i = 0; i < c.elastodynamic.frequency.size(); ++i) {
            std::printf(" %.6g", c.elastodynamic.frequency(i));
        }
        std::printf("\n");
    }
}

void run(const PoseOptions& options) {
    const Model model(loadRobotDescriptionOrDefault(options.robot));
    Data data(model);
    const Pose p(options.theta, options.x, options.y);
    if (const Status status = inverseDynamics(model, data, p, Twist::Zero(), Twist::Zero()); !status) {
        throw Error(describe(status, model));
    }
    const Status limits = checkJointLimits(model, data);
    if (!limits) warnOutsideRange(model, data, limits);
    // at rest (dp = ddp = 0) tau holds the pose against gravity; the reactions that go with it
    Reactions reactions;
    jointReactions(model, data, reactions);
    // du = A xi_P = A S(c) dp/dt: the actuation map in the pose's own rates (eq. 5 generalised)
    const Eigen::MatrixXd A_pose = Eigen::MatrixXd(data.A) * platformTwistMap(p.tail<2>());
    const char* coordinates = model.coordinates == Coordinates::actuators ? "actuators" : "platform";
    const std::optional<ComplianceAtPose> compliance = complianceAtPose(model, data);

    if (options.json) {
        nlohmann::json out;
        out["robot"] = model.description.name;
        out["pose"] = {{"theta", p(0)}, {"x", p(1)}, {"y", p(2)}};
        nlohmann::json limbs = nlohmann::json::array();
        for (int j = 0; j < model.limbs; ++j) {
            const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
            limbs.push_back({{"limb", j + 1},
                             {"name", model.description.limbs[static_cast<std::size_t>(j)].name},
                             {"type", model.description.limbs[static_cast<std::size_t>(j)].type()},
                             {"q", {ld.q(0), ld.q(1), ld.q(2)}},
                             {"cond_J", ld.cond}});
        }
        out["limbs"] = limbs;
        nlohmann::json actuators = nlohmann::json::array();
        for (int a = 0; a < model.actuators; ++a) {
            const int j = model.actuator_limb[static_cast<std::size_t>(a)];
            const int k = model.actuator_joint[static_cast<std::size_t>(a)];
            actuators.push_back(
                {{"actuator", a + 1},
                 {"limb", j + 1},
                 {"joint", k + 1},
                 {"u", data.u(a)},
                 {"range_used",
                  rangeUsed(model.limb[static_cast<std::size_t>(j)].limits[static_cast<std::size_t>(k)], data.u(a))}});
        }
        out["actuators"] = actuators;
        out["A"] = toJson(A_pose);
        out["cond_A"] = data.cond_A;
        out["coordinates"] = coordinates;
        out["I"] = toJson(data.I);
        out["within_limits"] = limits.ok();
        nlohmann::json joints = nlohmann::json::array();
        for (int j = 0; j < model.limbs; ++j) {
            for (int k = 0; k < 3; ++k) {
                const Vector3& r = reactions.joint[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
                joints.push_back({{"limb", j + 1},
                                  {"joint", k + 1},
                                  {"type", revolute(model, j, k) ? "R" : "P"},
                                  {"fx", r(0)},
                                  {"fy", r(1)},
                                  {"m", r(2)}});
            }
        }
        out["tau"] = std::vector<double>(data.tau.data(), data.tau.data() + model.actuators);
        out["reactions"] = joints;
        if (compliance) out.update(complianceJson(*compliance));
        std::cout << out.dump(2) << "\n";
        return;
    }
    constexpr double deg = 180.0 / std::numbers::pi;
    std::printf("robot %s, pose theta = %.9g rad (%.6g deg), x = %.9g m, y = %.9g m\n\n",
                model.description.name.c_str(), p(0), p(0) * deg, p(1), p(2));
    std::printf("limb  type  q1                q2                q3                cond J_j\n");
    for (int j = 0; j < model.limbs; ++j) {
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        std::printf("%-4d  %s  ", j + 1, model.description.limbs[static_cast<std::size_t>(j)].type().c_str());
        for (int k = 0; k < 3; ++k) {
            if (revolute(model, j, k))
                std::printf("%+11.6f deg   ", ld.q(k) * deg);
            else
                std::printf("%+11.6f mm    ", ld.q(k) * 1e3);
        }
        std::printf("%.4g\n", ld.cond);
    }
    std::printf("\nactuator  limb  joint  u                 range used\n");
    for (int a = 0; a < model.actuators; ++a) {
        const int j = model.actuator_limb[static_cast<std::size_t>(a)];
        const int k = model.actuator_joint[static_cast<std::size_t>(a)];
        const double used =
            rangeUsed(model.limb[static_cast<std::size_t>(j)].limits[static_cast<std::size_t>(k)], data.u(a));
        std::printf("%-8d  %-4d  %-5d  %+11.6f %-4s  %6.2f %%\n", a + 1, j + 1, k + 1,
                    revolute(model, j, k) ? data.u(a) * deg : data.u(a) * 1e3, revolute(model, j, k) ? "deg" : "mm",
                    100.0 * used);
    }
    std::printf("\nactuation map du = A dp/dt (eq. 5 generalised; rows: actuators, columns: theta, x, y):\n%s",
                formatMatrix(A_pose, "  ").c_str());
    std::printf("condition numbers (scaled, limit %.6g): actuation %.6g\n", model.max_condition, data.cond_A);
    if (model.coordinates == Coordinates::actuators) {
        std::printf("joint-space inertia I (eq. 23), in the actuator variables:\n%s",
                    formatMatrix(data.I, "  ").c_str());
    } else {
        std::printf("inertia I (eq. 23) in the platform pose (redundant actuation):\n%s",
                    formatMatrix(data.I, "  ").c_str());
    }
    std::printf("\nat rest under gravity: tau =");
    for (int a = 0; a < model.actuators; ++a) std::printf(" %+.6e", data.tau(a));
    std::printf("\njoint reactions (base frame, inboard body on outboard body, effort and friction taken out):\n");
    std::printf("limb  joint  fx [N]           fy [N]           m [N m]\n");
    for (int j = 0; j < model.limbs; ++j) {
        for (int k = 0; k < 3; ++k) {
            const Vector3& r = reactions.joint[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
            std::printf("%-4d  %d %s    %+.9e  %+.9e  %+.9e\n", j + 1, k + 1, revolute(model, j, k) ? "R" : "P", r(0),
                        r(1), r(2));
        }
    }
    if (compliance) printCompliance(*compliance);
    if (!limits) std::printf("\nwarning: %s\n", describe(limits, model).c_str());
}

}  // namespace

void addPoseCommand(CLI::App& app) {
    auto options = std::make_shared<PoseOptions>();
    CLI::App* command = app.add_subcommand(
        "pose",
        "At one platform pose of any robot: every limb's joint variables and the condition number of\n"
        "its Jacobian, the actuator variables and how much of their range they use, the actuation map\n"
        "du = A dp/dt and its condition number, the inertia I (eq. 23), and at rest under gravity the\n"
        "actuator forces and every joint's reaction (base frame, the inboard body on the outboard body,\n"
        "the joint's effort and friction taken out; JSON: \"tau\" and \"reactions\").\n"
        "When the robot file declares compliance (stiffness, elastic), also the stiffness K and the\n"
        "natural frequencies (JSON: \"stiffness\", \"natural_frequencies\", \"elastodynamic_frequencies\").\n"
        "Example: nocdyn pose 0.05 0.001 -0.002 --robot robots/3-rrr.yaml   (theta in rad, x and y in m)");
    command->add_option("THETA", options->theta, "Platform rotation [rad]")
        ->required()
        ->check(finiteIn(-1e6, 1e6, "rad"));
    command->add_option("X", options->x, "x of the platform's operation point C [m]")
        ->required()
        ->check(finiteIn(-1e3, 1e3, "m"));
    command->add_option("Y", options->y, "y of the platform's operation point C [m]")
        ->required()
        ->check(finiteIn(-1e3, 1e3, "m"));
    addRobotOption(*command, options->robot);
    command->add_flag("--json", options->json, "Write JSON instead of text");
    command->callback([options] { run(*options); });
}

}  // namespace nocdyn::cli
