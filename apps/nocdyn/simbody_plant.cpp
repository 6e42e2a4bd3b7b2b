#include "simbody_plant.hpp"

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

}  // namespace nocdyn::cli
