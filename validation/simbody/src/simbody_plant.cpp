// The Simbody model as a RobotPlant (see simbody_plant.hpp).
#include "nocdyn/validation/simbody_plant.hpp"

#include "nocdyn/validation/simbody_mechanism.hpp"

namespace nocdyn::validation {

SimbodyPlant::SimbodyPlant(const RobotDescription& robot, double accuracy)
    : mechanism_(std::make_unique<SimbodyMechanism>(robot)) {
    mechanism_->setIntegratorAccuracy(accuracy);
}

SimbodyPlant::~SimbodyPlant() = default;

void SimbodyPlant::reset(const Pose& p, const Twist& dp) { mechanism_->resetPlant(p, dp); }
void SimbodyPlant::setForces(const ActuatorVector& tau) { mechanism_->setActuatorForces(Eigen::VectorXd(tau)); }
void SimbodyPlant::advance(double dt) { mechanism_->advance(dt); }
Pose SimbodyPlant::pose() const { return mechanism_->pose(); }
Twist SimbodyPlant::poseRate() const { return mechanism_->poseRate(); }
ActuatorVector SimbodyPlant::u() const { return mechanism_->u(); }

}  // namespace nocdyn::validation
