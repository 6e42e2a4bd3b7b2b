// The independent Simbody model of any robot file (validation::SimbodyMechanism) as a
// RobotPlant, so that a controller designed on the NOC model is tested on a plant it shares
// nothing with but the robot file (PlantKind::simbody). Built only when the target
// nocdyn_simbody exists; the library never depends on Simbody.
#pragma once

#include <memory>

#include "nocdyn/description.hpp"
#include "nocdyn/sim/plant.hpp"

namespace nocdyn::validation {

class SimbodyMechanism;

class SimbodyPlant final : public RobotPlant {
public:
    /// accuracy: Simbody's integrator accuracy (its constraint tolerance follows it).
    explicit SimbodyPlant(const RobotDescription& robot, double accuracy = 1e-10);
    ~SimbodyPlant() override;
    SimbodyPlant(const SimbodyPlant&) = delete;
    SimbodyPlant& operator=(const SimbodyPlant&) = delete;
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

}  // namespace nocdyn::validation
