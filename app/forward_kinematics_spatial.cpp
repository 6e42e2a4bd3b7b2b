#include "app/forward_kinematics_spatial.hpp"

#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_direct_kinematics.hpp"

namespace nocdyn::app {

SpatialForwardKinematicsResult runSpatialForwardKinematics(const RobotSource& source, const std::vector<double>& u,
                                                           Observer& observer) {
    for (const double value : u) requireIn(value, kLengthRange, "u");
    const spatial::Model model(io::loadSpatialRobotDescription(source.path, source.set));
    const int n = model.actuators;
    if (static_cast<int>(u.size()) != n) {
        throw OptionError("u", io::terminalText(model.name) + " (" + io::terminalText(source.path) + ") has " +
                                   std::to_string(n) + " actuators: give " + std::to_string(n) + " values U1 .. U" +
                                   std::to_string(n) + ", not " + std::to_string(u.size()));
    }
    SpatialForwardKinematicsResult out;
    out.robot = model.name;
    out.coordinates = model.coordinates();
    out.u = u;
    spatial::ActuatorVector values(n);
    for (int a = 0; a < n; ++a) {
        values(a) = u[static_cast<std::size_t>(a)];
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a)];
        const spatial::Freedom& f = model.limb[static_cast<std::size_t>(j)].freedoms[static_cast<std::size_t>(k)];
        out.revolute.push_back(f.revolute);
        if (out.outside == 0 && (values(a) < f.limits.lower || values(a) > f.limits.upper)) out.outside = a + 1;
    }
    if (out.outside > 0) {
        observer.warning("u" + std::to_string(out.outside) +
                         " is outside its joint's range (values are in m and rad: 5 mm is 0.005)");
    }
    const spatial::AssemblyModes modes = spatial::assemblyModes(model, values);
    out.method = modes.method == spatial::DirectMethod::three_spheres ? "three spheres" : "many starts";
    out.complete = modes.complete;
    out.starts = modes.starts;
    if (modes.modes.empty()) {
        std::ostringstream text;
        text.precision(6);
        text << source.path << ": no pose closes the loops with these actuator values (out of reach): ";
        if (modes.method == spatial::DirectMethod::three_spheres) {
            text << "the forearms' three spheres do not meet (they miss by " << modes.gap << " m^2)";
        } else {
            text << "none found from " << modes.starts << " starts";
        }
        throw Error(text.str());
    }
    for (const spatial::AssemblyMode& mode : modes.modes) {
        out.solutions.push_back({std::vector<double>(mode.p.data(), mode.p.data() + mode.p.size()), mode.working,
                                 mode.home_branches, mode.u_error, mode.condition});
    }
    return out;
}

}  // namespace nocdyn::app
