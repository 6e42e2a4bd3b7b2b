// The independent Simbody model (validation/simbody, nocdyn::validation::SimbodyRobot) as a
// control::Plant, so that computed torque designed on the NOC model is tested on a plant it
// shares nothing with but the robot parameters. Built only when the target nocdyn_simbody
// exists; the core library never depends on Simbody.
#pragma once

#include <memory>

#include "nocdyn/control.hpp"
#include "nocdyn/general_control.hpp"
#include "nocdyn/robot.hpp"

namespace nocdyn::validation {
class SimbodyRobot;
class SimbodyMechanism;
}  // namespace nocdyn::validation

namespace nocdyn::cli {

class SimbodyPlant final : public control::Plant {
public:
    /// accuracy: Simbody's integrator accuracy (its constraint tolerance follows it).
    explicit SimbodyPlant(const RobotParameters& robot, double accuracy = 1e-10);
    ~SimbodyPlant() override;
    void reset(const Pose& p, const Twist& dp) override;
    void setForces(const control::JointVector& tau) override;
    void advance(double dt) override;
    [[nodiscard]] double time() const override;
    [[nodiscard]] control::JointVector u() const override;
    [[nodiscard]] control::JointVector du() const override;
    [[nodiscard]] Pose pose() const override;
    [[nodiscard]] Twist poseRate() const override;
    [[nodiscard]] std::string name() const override { return "Simbody"; }

private:
    std::unique_ptr<validation::SimbodyRobot> robot_;
};

/// The independent Simbody model of any robot file (validation::SimbodyMechanism) as a
/// RobotPlant: the plant of task-space control for every robot (general_control.hpp).
class SimbodyMechanismPlant final : public RobotPlant {
public:
    /// accuracy: Simbody's integrator accuracy (its constraint tolerance follows it).
    explicit SimbodyMechanismPlant(const RobotDescription& robot, double accuracy = 1e-10);
    ~SimbodyMechanismPlant() override;
    SimbodyMechanismPlant(const SimbodyMechanismPlant&) = delete;
    SimbodyMechanismPlant& operator=(const SimbodyMechanismPlant&) = delete;
    void reset(const Pose& p, const Twist& dp) override;
    void setForces(const ActuatorVector& tau) override;
    void advance(double dt) override;
    [[nodiscard]] Pose pose() const override;
    [[nodiscard]] Twist poseRate() const override;
    [[nodiscard]] ActuatorVector u() const override;
    [[nodiscard]] std::string name() const override { return "Simbody"; }

private:
    std::unique_ptr<validation::SimbodyMechanism> mechanism_;
};

}  // namespace nocdyn::cli
