// Independent Simbody model of any planar parallel robot of the general form
// (RobotDescription: limbs of three R/P joints, any actuated joints, gravity, joint friction).
//
// Each limb is a tree plus one loop-closure constraint at one of its revolute joints (the last
// unactuated R joint, else the last R joint): the joints before it are Pin/Slider mobilizers
// from Ground, the joints after it Pin/Slider mobilizers hanging from the platform (reversed),
// and the closure is a Constraint::PointOnLine (a z-line through the joint axis on one link,
// followed by the axis point on the other: two equations). The platform is on a Planar
// mobilizer from Ground whose motion is prescribed. Gravity is a Force::UniformGravity; joint
// friction a Force::Custom (mobility forces on tree joints, opposite body torques across a
// closure joint), so that Simbody's applied forces hold both.
// See nocdyn/validation/detail/mechanism_common.hpp for how the actuator forces follow.
// Shares only description.hpp and trajectory.hpp with nocdyn; Simbody stays private (pimpl).
#pragma once

#include <memory>
#include <vector>

#include "nocdyn/description.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/validation/mechanism_sample.hpp"

namespace nocdyn::validation {

class SimbodyMechanism {
public:
    /// Builds the model from a description (validated by nocdyn::validate on a copy). Throws
    /// nocdyn::Error if a limb has no revolute joint or the model does not assemble at home.
    explicit SimbodyMechanism(const RobotDescription& robot);
    ~SimbodyMechanism();
    SimbodyMechanism(SimbodyMechanism&&) noexcept;
    SimbodyMechanism& operator=(SimbodyMechanism&&) noexcept;
    SimbodyMechanism(const SimbodyMechanism&) = delete;
    SimbodyMechanism& operator=(const SimbodyMechanism&) = delete;

    /// Inverse dynamics with the platform pose prescribed from the trajectory, one sample per
    /// time. Positions by Simbody's Newton projection (projectQ), continued from home along
    /// the samples (the previous solution extrapolated; subdivided in pose space when a step
    /// fails or jumps), so every limb stays on its home branch; velocities by projectU,
    /// accelerations by realize(Acceleration) with the platform's Motion; then
    /// h = M u' + c - Q_applied (calcResidualForceIgnoringConstraints) and the constraint
    /// Jacobian calcG give the actuator forces (minimum norm when redundant). Throws
    /// nocdyn::Error naming the time when a pose cannot be assembled or is singular.
    std::vector<MechanismSample> inverseDynamics(const PoseTrajectory& trajectory, const std::vector<double>& times);

    /// Number of actuated joints n.
    [[nodiscard]] int actuatorCount() const;

private:
    class Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nocdyn::validation
