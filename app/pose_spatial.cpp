#include "app/pose_spatial.hpp"

#include <cmath>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_reactions.hpp"

namespace nocdyn::app {

namespace {

/// Fraction of the joint's range [lower, upper] used on the side q is on (0 when unlimited).
double rangeOf(const JointLimits& limits, double q) {
    const double bound = q >= 0.0 ? limits.upper : -limits.lower;
    return std::isfinite(bound) && bound > 0.0 ? std::abs(q) / bound : 0.0;
}

}  // namespace

bool isSpatialRobot(const RobotSource& source) {
    if (source.description || source.path.empty()) return false;
    return io::isSpatial(io::readRobotFileText(source.path), source.path);
}

SpatialPoseResult runSpatialPose(const RobotSource& source, const std::vector<double>& pose, Observer& observer) {
    return runSpatialPose(io::loadSpatialRobotDescription(source.path, source.set), source.path, pose, observer);
}

SpatialPoseResult runSpatialPose(const SpatialRobotDescription& description, const std::string& source,
                                 const std::vector<double>& pose, Observer& observer) {
    const spatial::Model model(description);
    const int d = model.task_dimension;
    if (static_cast<int>(pose.size()) != d) {
        throw Error("pose: the robot " + model.name + " takes " + std::to_string(d) + " pose coordinates (" +
                    (d == 3 ? "X Y Z" : "X Y Z ROLL PITCH YAW") + "), got " + std::to_string(pose.size()));
    }
    spatial::TaskVector p(d);
    for (int i = 0; i < d; ++i) p(i) = pose[static_cast<std::size_t>(i)];
    spatial::Data data(model);
    const spatial::TaskVector zero = spatial::TaskVector::Zero(d);
    if (const Status status = spatial::inverseDynamics(model, data, p, zero, zero); !status) {
        throw Error(source + ": " + spatial::describe(status, model));
    }
    spatial::conditionNumbers(model, data);  // reported: the exact values
    SpatialPoseResult out;
    out.robot = model.name;
    out.coordinates = model.coordinates();
    out.pose = pose;
    out.max_condition = model.max_condition;
    for (int j = 0; j < model.limbs(); ++j) {
        const spatial::Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const spatial::LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        const SpatialLimbDescription& ldesc = description.limbs[static_cast<std::size_t>(j)];
        SpatialPoseLimb l;
        l.limb = j + 1;
        l.name = limb.name;
        l.type = ldesc.type();
        for (int k = 0; k < limb.size(); ++k) {
            const spatial::Freedom& f = limb.freedoms[static_cast<std::size_t>(k)];
            l.q.push_back(ld.q(k));
            l.kinds.push_back(f.revolute ? 'R' : 'P');
            std::string of = std::to_string(f.joint + 1);
            of.insert(of.begin(), ldesc.joints[static_cast<std::size_t>(f.joint)].letter());
            l.of.push_back(of);
            const SpatialJointType type = ldesc.joints[static_cast<std::size_t>(f.joint)].type;
            if (type != SpatialJointType::revolute && type != SpatialJointType::prismatic) continue;  // U, S: no limits
            const double q = ld.q(k);
            if (out.within_limits && (q < f.limits.lower || q > f.limits.upper)) {
                out.within_limits = false;
                std::ostringstream text;
                text.precision(6);
                text << "joint range exceeded: limb " << j + 1 << " (" << limb.name << "), joint " << f.joint + 1
                     << ": q = " << q << ", range [" << f.limits.lower << ", " << f.limits.upper << "]";
                out.limits = text.str();
                observer.warning(out.limits);
            }
        }
        l.cond_J = ld.condition;
        out.limbs.push_back(l);
    }
    for (int a = 0; a < model.actuators; ++a) {
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a)];
        const spatial::Freedom& f = model.limb[static_cast<std::size_t>(j)].freedoms[static_cast<std::size_t>(k)];
        out.actuators.push_back({a + 1, j + 1, f.joint + 1, f.revolute, data.u(a), rangeOf(f.limits, data.u(a))});
    }
    out.A = data.A_task;  // du = A [v; w] at the platform point
    out.cond_A = data.actuation_condition;
    out.tau = data.tau;
    spatial::Reactions reactions(model);
    if (const Status status = spatial::jointReactions(model, data, reactions); !status) {
        throw Error(source + ": joint reactions at rest: " + spatial::describe(status, model));
    }
    out.balance_residual = reactions.balance_residual;
    for (std::size_t j = 0; j < reactions.joint.size(); ++j) {
        for (std::size_t k = 0; k < reactions.joint[j].size(); ++k) {
            const spatial::JointReaction& r = reactions.joint[j][k];
            out.reactions.push_back(
                {static_cast<int>(j) + 1, static_cast<int>(k) + 1, r.type, r.point, r.force, r.moment});
        }
    }
    return out;
}

}  // namespace nocdyn::app
