#include "simbody_plant.hpp"

#include "nocdyn/validation/simbody_mechanism.hpp"
#include "nocdyn/validation/simbody_robot.hpp"

namespace nocdyn::cli {

SimbodyPlant::SimbodyPlant(const RobotParameters& robot, double accuracy)
    : robot_(std::make_unique<validation::SimbodyRobot>(robot)) {
    robot_->setIntegratorAccuracy(accuracy);
}

SimbodyPlant::~SimbodyPlant() = default;

void SimbodyPlant::reset(const Pose& p, const Twist& dp) { robot_->resetPlant(p, dp); }
void SimbodyPlant::setForces(const control::JointVector& tau) { robot_->setActuatorForces(tau); }
void SimbodyPlant::advance(double dt) { robot_->advance(dt); }
double SimbodyPlant::time() const { return robot_->time(); }
control::JointVector SimbodyPlant::u() const { return robot_->u(); }
control::JointVector SimbodyPlant::du() const { return robot_->du(); }
Pose SimbodyPlant::pose() const { return robot_->pose(); }
Twist SimbodyPlant::poseRate() const { return robot_->poseRate(); }

SimbodyMechanismPlant::SimbodyMechanismPlant(const RobotDescription& robot, double accuracy)
    : mechanism_(std::make_unique<validation::SimbodyMechanism>(robot)) {
    mechanism_->setIntegratorAccuracy(accuracy);
}

SimbodyMechanismPlant::~SimbodyMechanismPlant() = default;

void SimbodyMechanismPlant::reset(const Pose& p, const Twist& dp) { mechanism_->resetPlant(p, dp); }
void SimbodyMechanismPlant::setForces(const ActuatorVector& tau) {
    mechanism_->setActuatorForces(Eigen::VectorXd(tau));
}
void SimbodyMechanismPlant::advance(double dt) { mechanism_->advance(dt); }
Pose SimbodyMechanismPlant::pose() const { return mechanism_->pose(); }
Twist SimbodyMechanismPlant::poseRate() const { return mechanism_->poseRate(); }
ActuatorVector SimbodyMechanismPlant::u() const { return mechanism_->u(); }

}  // namespace nocdyn::cli
