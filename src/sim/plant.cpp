// nocdyn's own plants (plant.hpp).
#include "nocdyn/sim/plant.hpp"

#include <cmath>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

namespace {

/// "plant: t = <t> s: <status>".
[[noreturn]] void failAt(double t, const Status& status, const Model& model) {
    throw Error("plant: " + text::sampleTime(t) + ": " + describe(status, model));
}

}  // namespace

SimulatorRobotPlant::SimulatorRobotPlant(const Model& model, const SimulatorOptions& options)
    : simulator_(model, options) {}

void SimulatorRobotPlant::reset(const Pose& p, const Twist& dp) {
    if (const Status status = simulator_.reset(p, dp); !status) {
        throw Error("plant reset: " + describe(status, simulator_.model()));
    }
}

void SimulatorRobotPlant::advance(double dt) {
    if (const Status status = simulator_.advance(dt); !status) failAt(simulator_.time(), status, simulator_.model());
}

RungeKuttaRobotPlant::RungeKuttaRobotPlant(const Model& model)
    : model_(model), data_(model_), pose_data_(model_), tau_(ActuatorVector::Zero(model.actuators)) {
    reset(model_.home, Twist::Zero());
}

void RungeKuttaRobotPlant::reset(const Pose& p, const Twist& dp) {
    if (const Status status = forwardDynamics(model_, data_, p, dp, ActuatorVector::Zero(model_.actuators)); !status) {
        throw Error("plant reset: " + describe(status, model_));
    }
    p_ = p;
    dp_ = dp;
    tau_.setZero(model_.actuators);
    t_ = 0.0;
}

void RungeKuttaRobotPlant::acceleration(const Pose& p, const Twist& dp, Twist& a) {
    if (const Status status = forwardDynamics(model_, data_, p, dp, tau_); !status) failAt(t_, status, model_);
    a = data_.t_M_dot;
}

void RungeKuttaRobotPlant::advance(double h) {
    if (!(h >= 0.0) || !std::isfinite(h)) throw Error("plant: advance() needs a finite dt >= 0");
    // x = (p, dp), x' = (dp, a(p, dp)): k_i = (v_i, a_i)
    Twist a1, a2, a3, a4;
    acceleration(p_, dp_, a1);
    const Twist v2 = dp_ + 0.5 * h * a1;
    acceleration(p_ + 0.5 * h * dp_, v2, a2);
    const Twist v3 = dp_ + 0.5 * h * a2;
    acceleration(p_ + 0.5 * h * v2, v3, a3);
    const Twist v4 = dp_ + h * a3;
    acceleration(p_ + h * v3, v4, a4);
    p_ += h / 6.0 * (dp_ + 2.0 * v2 + 2.0 * v3 + v4);
    dp_ += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    t_ += h;
}

ActuatorVector RungeKuttaRobotPlant::u() const {
    // the actuator variables of the current pose (inverse displacement)
    if (const Status status = inverseDisplacement(model_, pose_data_, p_); !status) failAt(t_, status, model_);
    return pose_data_.u;
}

}  // namespace nocdyn
