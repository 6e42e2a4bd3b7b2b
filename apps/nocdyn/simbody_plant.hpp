// The independent Simbody model (validation/simbody, nocdyn::validation::SimbodyRobot) as a
// control::Plant, so that computed torque designed on the NOC model is tested on a plant it
// shares nothing with but the robot parameters. Built only when the target nocdyn_simbody
// exists; the core library never depends on Simbody.
#pragma once

#include <memory>

#include "nocdyn/control.hpp"
#include "nocdyn/robot.hpp"

namespace nocdyn::validation {
class SimbodyRobot;
}

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

}  // namespace nocdyn::cli
