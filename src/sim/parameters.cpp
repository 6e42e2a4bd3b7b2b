// The standard parameters pi of a model (identification.hpp): their layout, names, units and the
// values the robot file gives. Apart from the regressor so that the calibration reader (and its
// fuzz harness) needs nothing of the identification itself.
#include <cstddef>
#include <string>

#include "nocdyn/sim/identification.hpp"
#include "nocdyn/detail/index.hpp"

namespace nocdyn {

namespace {

using detail::at;

}  // namespace

int parameterCount(const Model& model) { return kBodyParameters * model.bodies + kJointParameters * 3 * model.limbs; }

int bodyParameterIndex(int body) { return kBodyParameters * body; }

int jointParameterIndex(const Model& model, int limb, int joint) {
    return kBodyParameters * model.bodies + kJointParameters * (3 * limb + joint);
}

namespace {

[[nodiscard]] std::string bodyName(const Model& model, int i) {
    if (i == model.platformBody()) return "platform";
    return model.description.limbs[at(i % model.limbs)].name + ".body" + std::to_string(i / model.limbs + 1);
}

}  // namespace

std::string parameterName(const Model& model, int index) {
    static const char* const body_names[kBodyParameters] = {"m", "mc_x", "mc_y", "I_O"};
    const int body_end = kBodyParameters * model.bodies;
    if (index < body_end) return bodyName(model, index / kBodyParameters) + "." + body_names[index % kBodyParameters];
    const int joint = (index - body_end) / kJointParameters;
    return model.description.limbs[at(joint / 3)].name + ".joint" + std::to_string(joint % 3 + 1) +
           ((index - body_end) % kJointParameters == 0 ? ".damping" : ".friction");
}

std::string parameterUnit(const Model& model, int index) {
    static const char* const body_units[kBodyParameters] = {"kg", "kg m", "kg m", "kg m^2"};
    const int body_end = kBodyParameters * model.bodies;
    if (index < body_end) return body_units[index % kBodyParameters];
    const int joint = (index - body_end) / kJointParameters;
    const bool prismatic = model.limb[at(joint / 3)].type[at(joint % 3)] == JointType::prismatic;
    if ((index - body_end) % kJointParameters == 0) return prismatic ? "N s/m" : "N m s/rad";
    return prismatic ? "N" : "N m";
}

Eigen::Vector4d inertialParameters(double mass, const Vector2& com, double inertia) {
    return {mass, mass * com.x(), mass * com.y(), inertia + mass * com.squaredNorm()};
}

ParameterVector standardParameters(const Model& model) {
    ParameterVector pi(parameterCount(model));
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[at(j)];
        for (int b = 0; b < 2; ++b) {
            pi.segment<kBodyParameters>(bodyParameterIndex(model.body(j, b))) =
                inertialParameters(limb.M[at(b)].mass, limb.com_home[at(b)], limb.M[at(b)].inertia);
        }
        for (int k = 0; k < 3; ++k) {
            pi(jointParameterIndex(model, j, k)) = limb.damping[at(k)];
            pi(jointParameterIndex(model, j, k) + 1) = limb.friction[at(k)];
        }
    }
    pi.segment<kBodyParameters>(bodyParameterIndex(model.platformBody())) =
        inertialParameters(model.platform_M.mass, model.platform_com, model.platform_M.inertia);
    return pi;
}

}  // namespace nocdyn
