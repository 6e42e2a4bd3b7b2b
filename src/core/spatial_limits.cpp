#include "nocdyn/spatial_limits.hpp"

#include <cmath>
#include <cstddef>

#include "nocdyn/text.hpp"

namespace nocdyn::spatial {

namespace {

/// The freedom of limb j that belongs to listed joint `joint` and carries its limits (an R or P
/// joint has one freedom).
const Freedom* freedomOf(const Model& model, int j, int joint) {
    if (j < 0 || j >= model.limbs()) return nullptr;
    for (const Freedom& f : model.limb[static_cast<std::size_t>(j)].freedoms) {
        if (f.joint == joint) return &f;
    }
    return nullptr;
}

}  // namespace

Status checkLimits(const Model& model, const Data& data) {
    for (int j = 0; j < model.limbs(); ++j) {
        const Limb& limb = model.limb[static_cast<std::size_t>(j)];
        const LimbData& ld = data.limb[static_cast<std::size_t>(j)];
        for (int k = 0; k < limb.size(); ++k) {
            const Freedom& f = limb.freedoms[static_cast<std::size_t>(k)];
            const double q = ld.q(k), v = ld.gd(k);
            if (q < f.limits.lower || q > f.limits.upper) return {StatusCode::joint_limit_exceeded, j, q, f.joint};
            if (std::abs(v) > f.limits.velocity) return {StatusCode::velocity_exceeded, j, v, f.joint};
            if (f.actuator >= 0 && std::abs(data.tau(f.actuator)) > f.limits.effort) {
                return {StatusCode::effort_exceeded, j, data.tau(f.actuator), f.joint};
            }
        }
    }
    return {};
}

std::string describeLimit(const Status& status, const Model& model) {
    const Freedom* f = freedomOf(model, status.limb, status.joint);
    if (f == nullptr) {  // not a limit of this model's joints (describe() would come back here)
        std::string out = "a joint's limit passed (limb ";
        out += std::to_string(status.limb + 1);
        out += ", joint ";
        out += std::to_string(status.joint + 1);
        out += ", value ";
        out += text::number(status.value);
        out += ")";
        return out;
    }
    std::string joint = "limb ";
    joint += std::to_string(status.limb + 1);
    joint += " (";
    joint += model.limb[static_cast<std::size_t>(status.limb)].name;
    joint += "), joint ";
    joint += std::to_string(f->joint + 1);
    std::string out;
    switch (status.code) {
        case StatusCode::joint_limit_exceeded:
            out += "joint range exceeded: ";
            out += joint;
            out += ": q = ";
            out += text::number(status.value);
            out += ", range [";
            out += text::number(f->limits.lower);
            out += ", ";
            out += text::number(f->limits.upper);
            out += "]";
            return out;
        case StatusCode::velocity_exceeded:
            out += "joint velocity exceeded: ";
            out += joint;
            out += ": q' = ";
            out += text::number(status.value);
            out += ", limit ";
            out += text::number(f->limits.velocity);
            return out;
        case StatusCode::effort_exceeded:
            out += "effort exceeded: actuator ";
            out += std::to_string(f->actuator + 1);
            out += ", ";
            out += joint;
            out += ": tau = ";
            out += text::number(status.value);
            out += ", limit ";
            out += text::number(f->limits.effort);
            return out;
        default:
            return describe(status, model);
    }
}

}  // namespace nocdyn::spatial
