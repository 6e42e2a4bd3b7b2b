// Construction of the general Model from a robot description (model.hpp).
#include "nocdyn/model.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/limb_ik.hpp"
#include "nocdyn/printable.hpp"
#include "limb_lanes.hpp"

namespace nocdyn {

namespace {

[[nodiscard]] Twist homeScrew(const LimbModel& limb, int k) {
    const auto kk = static_cast<std::size_t>(k);
    return limb.type[kk] == JointType::revolute ? revoluteTwist(-limb.point_home[kk])
                                                : prismaticTwist(limb.direction[kk]);
}

[[nodiscard]] LimbKind limbKind(const std::array<JointType, 3>& type) {
    const bool r1 = type[0] == JointType::revolute;
    const bool r2 = type[1] == JointType::revolute;
    const bool r3 = type[2] == JointType::revolute;
    if (r1 && r2 && r3) return LimbKind::RRR;
    if (!r1 && r2 && r3) return LimbKind::PRR;
    if (r1 && !r2 && r3) return LimbKind::RPR;
    if (r1 && r2 && !r3) return LimbKind::RRP;
    if (!r1 && r2 && !r3) return LimbKind::PRP;
    if (r1 && !r2 && !r3) return LimbKind::RPP;
    if (!r1 && !r2 && r3) return LimbKind::PPR;
    return LimbKind::PPP;
}

/// Model::uniform_limbs: kind * 3 + the one actuated joint shared by every limb, or -1.
[[nodiscard]] int uniformLimbs(const Model& model) {
    int code = -1;
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        int actuated = -1, count = 0;
        for (int k = 0; k < 3; ++k) {
            if (limb.actuator[static_cast<std::size_t>(k)] >= 0) actuated = k, ++count;
        }
        const int mine = count == 1 ? static_cast<int>(limb.kind) * 3 + actuated : -1;
        if (mine < 0 || (j > 0 && mine != code)) return -1;
        code = mine;
    }
    return code;
}

/// The model's lanes (limb_lanes.hpp) and Model::limbsInLanes. Uniform limbs share their joint scales (1 for R,
/// length_scale for P), which the kernel therefore reads from the first limb.
void fillLanes(Model& model) {
    LimbLanes& l = detail::ModelKernel::startLanes(model);
    if (model.uniform_limbs < 0 || model.limbs > LimbLanes::kLanes) return;
    bool any_friction = false, all_friction = true;
    for (int j = 0; j < model.limbs; ++j) {
        const bool frictionless = model.limb[static_cast<std::size_t>(j)].frictionless;
        any_friction = any_friction || !frictionless;
        all_friction = all_friction && !frictionless;
    }
    if (any_friction && !all_friction) return;
    for (std::size_t lane = 0; lane < LimbLanes::kLanes; ++lane) {
        const auto j = static_cast<int>(lane) < model.limbs ? lane : 0;
        detail::fillLane(l, lane, model.limb[j]);
    }
    detail::ModelKernel::setLimbsInLanes(model, true);
}

}  // namespace

namespace detail {

template <int kN>
void fillLane(LimbLanesOf<kN>& l, std::size_t lane, const LimbModel& limb) {
    for (std::size_t k = 0; k < 3; ++k) {
        l.point_x[k][lane] = limb.point[k].x(), l.point_y[k][lane] = limb.point[k].y();
        l.point_home_x[k][lane] = limb.point_home[k].x(), l.point_home_y[k][lane] = limb.point_home[k].y();
        l.direction_x[k][lane] = limb.direction[k].x(), l.direction_y[k][lane] = limb.direction[k].y();
        l.damping[k][lane] = limb.damping[k], l.friction[k][lane] = limb.friction[k];
    }
    for (std::size_t b = 0; b < 2; ++b) {
        l.com_x[b][lane] = limb.com_home[b].x(), l.com_y[b][lane] = limb.com_home[b].y();
        l.mass[b][lane] = limb.M[b].mass, l.inertia[b][lane] = limb.M[b].inertia;
    }
    l.screw_x[lane] = limb.screw_home[0](1), l.screw_y[lane] = limb.screw_home[0](2);
    l.length1[lane] = limb.length1, l.length2[lane] = limb.length2;
    l.inv_length1_sq[lane] = limb.inv_length1_sq, l.inv_length2_sq[lane] = limb.inv_length2_sq;
    l.branch[lane] = static_cast<double>(limb.branch);
}
template void fillLane<4>(LimbLanesOf<4>& l, std::size_t lane, const LimbModel& limb);
template void fillLane<8>(LimbLanesOf<8>& l, std::size_t lane, const LimbModel& limb);

}  // namespace detail

Model::Model(RobotDescription d) : description(std::move(d)) {
    validate(description);
    const RobotDescription& robot = description;
    limbs = static_cast<int>(robot.limbs.size());
    bodies = 2 * limbs + 1;
    actuators = robot.actuatorCount();
    motion = robot.motion;
    task_dimension = motion == PlatformMotion::translation ? 2 : 3;
    // with a translating point tool the independent coordinates are the pose (task through E)
    coordinates = actuators == 3 && task_dimension == 3 ? Coordinates::actuators : Coordinates::platform;
    max_condition = robot.max_condition;
    gravity = robot.gravity;
    home = robot.home;
    cos_home = std::cos(home(0));
    sin_home = std::sin(home(0));
    platform_M = {robot.platform.inertia, robot.platform.mass};
    platform_com = robot.platform.com;
    platform_com_home = {cos_home * platform_com.x() - sin_home * platform_com.y(),
                         sin_home * platform_com.x() + cos_home * platform_com.y()};
    const Vector2 C_home = home.tail<2>();

    int a = 0;
    double scale = 0.0;
    for (int j = 0; j < limbs; ++j) {
        const LimbDescription& in = robot.limbs[static_cast<std::size_t>(j)];
        LimbModel& out = limb[static_cast<std::size_t>(j)];
        for (std::size_t k = 0; k < 3; ++k) {
            const JointDescription& joint = in.joints[k];
            out.type[k] = joint.type;
            out.point_home[k] = joint.point;
            out.point[k] = joint.point - C_home;
            out.direction[k] = joint.direction;
            out.limits[k] = joint.limits;
            out.damping[k] = joint.damping;
            out.friction[k] = joint.friction;
            if (joint.actuated) {
                out.actuator[k] = a;
                actuator_limb[static_cast<std::size_t>(a)] = j;
                actuator_joint[static_cast<std::size_t>(a)] = static_cast<int>(k);
                ++a;
            }
            if (joint.type == JointType::revolute) scale = std::max(scale, out.point[k].norm());
        }
        for (int k = 0; k < 3; ++k) out.screw_home[static_cast<std::size_t>(k)] = homeScrew(out, k);
        out.kind = limbKind(out.type);
        for (std::size_t b = 0; b < 2; ++b) {
            out.M[b] = {in.bodies[b].inertia, in.bodies[b].mass};
            out.com_home[b] = in.bodies[b].com;
        }
        // Lengths of the closed forms: the links between consecutive revolute axes.
        out.length1 = (out.point_home[1] - out.point_home[0]).norm();
        out.length2 = (out.point_home[2] - out.point_home[1]).norm();
        out.inv_length1_sq = out.length1 > 0.0 ? 1.0 / (out.length1 * out.length1) : 0.0;
        out.inv_length2_sq = out.length2 > 0.0 ? 1.0 / (out.length2 * out.length2) : 0.0;
        out.branch = homeBranch(out);
        const std::string type = in.type();
        const bool two_solutions = type == "RRR" || type == "PRR" || type == "RPR" || type == "RRP";
        if (two_solutions && out.branch == 0) {
            throw Error(where(robot, in.line) + "limbs[" + std::to_string(j) + "] (" + text::printable(in.name) +
                        "): singular at home: the " + type +
                        " limb is at the boundary of its reach (its two assembly branches meet)");
        }
    }
    length_scale = scale > 0.0 ? scale : 1.0;
    for (int j = 0; j < limbs; ++j) {
        LimbModel& out = limb[static_cast<std::size_t>(j)];
        for (std::size_t k = 0; k < 3; ++k) {
            out.joint_scale[k] = out.type[k] == JointType::revolute ? 1.0 : length_scale;
            out.inv_joint_scale[k] = 1.0 / out.joint_scale[k];
            if (out.damping[k] != 0.0 || out.friction[k] != 0.0) out.frictionless = false;
        }
    }
    uniform_limbs = uniformLimbs(*this);
    fillLanes(*this);

    // The home posture must be regular and reproduce q = 0 on every limb.
    Data data(*this);
    Status status = inverseDisplacement(*this, data, home);
    if (status) status = velocityFromPlatformTwist(*this, data, Twist::Zero());
    if (!status) {
        throw Error(where(robot, 0) + "the robot is not regular at its home posture: " + describe(status, *this));
    }
    for (int j = 0; j < limbs; ++j) {
        for (int k = 0; k < 3; ++k) {
            const double q = data.limb[static_cast<std::size_t>(j)].q(k);
            if (!(std::abs(q) <= 1e-9 * std::max(1.0, length_scale))) {
                std::ostringstream msg;
                msg << where(robot, robot.limbs[static_cast<std::size_t>(j)].line) << limbName(j)
                    << ": the closed-form inverse displacement gives q_" << k + 1 << " = " << q
                    << " at home instead of 0";
                throw Error(msg.str());
            }
        }
    }
}

TaskMap taskMap(const Model& model) {
    TaskMap E = TaskMap::Zero(3, model.task_dimension);
    if (model.task_dimension == 3) {
        E.setIdentity();
    } else {
        E(1, 0) = 1.0;
        E(2, 1) = 1.0;
    }
    return E;
}

std::string Model::limbName(int j) const {
    const std::string& name = description.limbs[static_cast<std::size_t>(j)].name;
    const std::string number = "limb " + std::to_string(j + 1);
    return name == "limb" + std::to_string(j + 1) ? number : number + " (" + text::printable(name) + ")";
}

Data::Data(const Model& model)
    : u(ActuatorVector::Zero(model.actuators)),
      du(ActuatorVector::Zero(model.actuators)),
      ddu(ActuatorVector::Zero(model.actuators)),
      tau(ActuatorVector::Zero(model.actuators)),
      A(ActuationMatrix::Zero(model.actuators, 3)) {
    for (auto& T_i : T) T_i.setZero();
    for (auto& T_i : T_dot) T_i.setZero();
}

}  // namespace nocdyn

namespace nocdyn {

std::string describe(const Status& status, const Model& model) {
    std::ostringstream out;
    out.precision(6);
    const std::string limb = status.limb >= 0 ? model.limbName(status.limb) : std::string("the robot");
    const std::string joint = status.joint >= 0 ? ", joint " + std::to_string(status.joint + 1) : std::string();
    const JointLimits* limits = nullptr;
    if (status.limb >= 0 && status.joint >= 0) {
        limits = &model.limb[static_cast<std::size_t>(status.limb)].limits[static_cast<std::size_t>(status.joint)];
    }
    switch (status.code) {
        case StatusCode::ok:
            return "ok";
        case StatusCode::unreachable:
            out << "pose out of reach: " << limb << " cannot close on its home branch; the pose is "
                << status.value * 1e3 << " mm beyond its reach";
            return out.str();
        case StatusCode::singular_limb:
            out << "singular posture: " << limb << ": its Jacobian J has condition number " << status.value
                << " (limit " << model.max_condition << ")";
            return out.str();
        case StatusCode::singular_actuation:
            if (status.value == 0.0)
                return "the actuator rates cannot be given independently: the robot is redundantly actuated";
            out << "actuation singularity: the map from the platform twist to the actuator rates has condition number "
                << status.value << " (limit " << model.max_condition << ")";
            return out.str();
        case StatusCode::joint_limit_exceeded:
            if (!std::isfinite(status.value)) {
                out << "joint variable not finite: " << limb << joint << ": q = " << status.value;
                return out.str();
            }
            out << "joint range exceeded: " << limb << joint << ": q = " << status.value << ", range ["
                << (limits ? limits->lower : 0.0) << ", " << (limits ? limits->upper : 0.0) << "]";
            return out.str();
        case StatusCode::velocity_exceeded:
            out << "joint velocity limit exceeded: " << limb << joint << ": q' = " << status.value << ", limit "
                << (limits ? limits->velocity : 0.0);
            return out.str();
        case StatusCode::effort_exceeded:
            if (!std::isfinite(status.value)) {  // a non-finite input or state, not a measurement
                out << "actuator effort not finite: actuator "
                    << model.limb[static_cast<std::size_t>(status.limb)]
                               .actuator[static_cast<std::size_t>(status.joint)] +
                           1
                    << " (" << limb << joint << "): tau = " << status.value;
                return out.str();
            }
            out << "actuator effort limit exceeded: actuator "
                << model.limb[static_cast<std::size_t>(status.limb)].actuator[static_cast<std::size_t>(status.joint)] +
                       1
                << " (" << limb << joint << "): tau = " << status.value << ", limit "
                << (limits ? limits->effort : 0.0);
            return out.str();
        case StatusCode::not_finite:
            out << "input is not a finite number (" << status.value << ")";
            return out.str();
        case StatusCode::workspace_edge:
            out << "the motion reached the edge of the workspace: " << limb << " is next to a singular posture (its "
                << "Jacobian J has condition number " << status.value << "), so no pose has its actuator further out";
            return out.str();
        case StatusCode::assembly_mode_lost:
            out << "direct kinematics lost the assembly mode (" << limb << ", scaled residual " << status.value
                << "): a singularity was crossed";
            return out.str();
        case StatusCode::integration_step_too_small:
            out << "the integrator's step fell to " << status.value
                << " s, below its minimum: the tolerances are too tight for double precision or the motion too"
                   " violent (loosen --atol/--rtol)";
            return out.str();
        case StatusCode::assembly_mode_missing:
            if (status.value == 0.0) {
                return "no pose with every limb on its home branch has these actuator values: the robot cannot start "
                       "there (forward-kinematics --all-branches lists the poses on other branches)";
            }
            out << "these actuator values give " << status.value << " assembly mode" << (status.value == 1.0 ? "" : "s")
                << " with every limb on its home branch, fewer than the one asked for (forward-kinematics lists them)";
            return out.str();
        case StatusCode::inconsistent_rates:
            out << "the actuator rates are not the rates of any platform motion at this pose (off by " << status.value
                << ")";
            return out.str();
        case StatusCode::rigid_limb:
            out << "infinitely stiff: " << limb
                << " does not yield in some direction of the platform (an actuated joint without a stiffness is"
                   " locked): give its drive a stiffness or make a body elastic";
            return out.str();
        case StatusCode::singular_mass_matrix: {
            // name the bodies whose zero mass or inertia leaves M_p = sum T_i^T M_i T_i singular
            out << "the mass matrix M_p is singular (smallest diagonal entry " << status.value << ")";
            std::string zero;
            for (int i = 0; i < model.bodies; ++i) {
                const InertiaDyad& m = model.inertia(i);
                if (m.mass > 0.0 && m.inertia > 0.0) continue;
                const std::string body = i == model.platformBody() ? std::string("the platform")
                                                                   : model.limbName(i % model.limbs) + " body " +
                                                                         std::to_string(i / model.limbs + 1);
                const char* what = m.mass <= 0.0 && m.inertia <= 0.0 ? "mass and inertia"
                                   : m.mass <= 0.0                   ? "mass"
                                                                     : "inertia";
                zero += (zero.empty() ? "" : ", ") + body + " has zero " + what;
            }
            if (!zero.empty()) {
                out << ": " << zero << "; give the bodies the motion moves a mass and an inertia";
            } else {
                out << ": no body has zero mass or inertia, yet the moving bodies cannot resist every platform motion "
                       "(give the platform a mass and an inertia)";
            }
            return out.str();
        }
        case StatusCode::stiffness_contrast:
            out << "stiffness contrast " << status.value
                << " between the stiffest and the softest direction the platform is held in: double precision "
                   "leaves the softest direction's stiffness and the lowest natural frequency a relative error of "
                   "about "
                << std::numeric_limits<double>::epsilon() * status.value
                << " (at most 1e14 is accepted: give the springs, EA and EI values closer to each other)";
            return out.str();
        case StatusCode::integration_too_many_steps:
            out << "the integrator took " << status.value
                << " steps over one interval without reaching its end (tolerances too tight?)";
            return out.str();
    }
    return "unknown status";
}

}  // namespace nocdyn
