#include "app/forward_kinematics.hpp"

#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/detail/index.hpp"

namespace nocdyn::app {

namespace {

using detail::at;

/// 1-based number of the first actuator whose value is outside its joint's range, else 0.
int outsideRange(const Model& model, const ActuatorVector& u) {
    for (int a = 0; a < model.actuators; ++a) {
        const JointLimits& limits = model.limb[at(model.actuator_limb[at(a)])].limits[at(model.actuator_joint[at(a)])];
        if (u(a) < limits.lower || u(a) > limits.upper) return a + 1;
    }
    return 0;
}

}  // namespace

void validate(const ForwardKinematicsOptions& options) {
    for (const double u : options.u) requireIn(u, kLengthRange, "u");
}

ForwardKinematicsResult runForwardKinematics(const ForwardKinematicsOptions& options, Observer& observer) {
    validate(options);
    const Model model(loadRobot(options.robot));
    const int n = model.actuators;
    if (static_cast<int>(options.u.size()) != n) {
        const std::string robot = io::terminalText(model.description.name) +
                                  (options.robot.path.empty() ? "" : " (" + io::terminalText(options.robot.path) + ")");
        throw OptionError("u", robot + " has " + std::to_string(n) + " actuators: give " + std::to_string(n) +
                                   " values U1 .. U" + std::to_string(n) + ", not " + std::to_string(options.u.size()));
    }
    ForwardKinematicsResult out;
    out.robot = model.description.name;
    out.task_dimension = model.task_dimension;
    out.u = options.u;
    ActuatorVector u(n);
    for (int a = 0; a < n; ++a) {
        u(a) = options.u[at(a)];
        out.revolute.push_back(model.limb[at(model.actuator_limb[at(a)])].type[at(model.actuator_joint[at(a)])] ==
                               JointType::revolute);
    }
    out.outside = outsideRange(model, u);
    if (out.outside > 0) {
        std::string text = "u";
        text += std::to_string(out.outside);
        text += " is outside its joint's range (values are in m and rad: 5 mm is 0.005)";
        observer.warning(text);
    }
    Data data(model);
    AssemblyModes modes;
    if (const Status status = directKinematics(model, data, u, modes); !status) {
        throw Error(options.robot.path + ": " + describe(status, model));
    }
    out.solutions_all_branches = modes.count;
    out.degenerate = modes.degenerate;
    for (const AssemblyMode& mode : modes) {
        out.solutions_working_branches += mode.working ? 1 : 0;
        if (!options.all_branches && !mode.working) continue;
        out.solutions.push_back({userPose(mode.p), mode.working,
                                 std::vector<int>(mode.branch.begin(), mode.branch.begin() + model.limbs), mode.u_error,
                                 mode.condition});
    }
    return out;
}

}  // namespace nocdyn::app
