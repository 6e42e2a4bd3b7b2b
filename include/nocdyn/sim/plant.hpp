// The robot a closed loop runs on (RobotPlant) and nocdyn's own plants: the error-controlled
// forward dynamics (SimulatorRobotPlant) and one Runge-Kutta 4 step per controller tick
// (RungeKuttaRobotPlant). A plant on an independent engine (validation/simbody: SimbodyPlant)
// implements the same interface where the engines are allowed; the plants a user chooses from
// are named by PlantKind.
#pragma once

#include <array>
#include <span>
#include <string>

#include "nocdyn/choice.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/sim/simulator.hpp"

namespace nocdyn {

/// The plants a closed loop runs on: the independent Simbody model (when built in), nocdyn's
/// error-controlled forward dynamics (SimulatorRobotPlant), or its Runge-Kutta 4 step per tick
/// (RungeKuttaRobotPlant).
enum class PlantKind { simbody, nocdyn, nocdyn_rk4 };

inline constexpr std::array<Choice<PlantKind>, 3> kPlantKinds{
    {{PlantKind::simbody, "simbody"}, {PlantKind::nocdyn, "nocdyn"}, {PlantKind::nocdyn_rk4, "nocdyn-rk4"}}};
[[nodiscard]] constexpr std::span<const Choice<PlantKind>> choices(PlantKind) { return kPlantKinds; }

/// The robot being controlled, measured by its platform pose and rate (and actuator
/// variables, recorded). Not real-time: methods may throw nocdyn::Error.
class RobotPlant {
public:
    virtual ~RobotPlant() = default;
    /// Assembles the robot at pose p with rate dp, time 0, zero forces.
    virtual void reset(const Pose& p, const Twist& dp) = 0;
    /// Actuator forces (n values) [N, N m], held until changed.
    virtual void setForces(const ActuatorVector& tau) = 0;
    /// Integrates dt seconds forward.
    virtual void advance(double dt) = 0;
    [[nodiscard]] virtual Pose pose() const = 0;
    [[nodiscard]] virtual Twist poseRate() const = 0;
    [[nodiscard]] virtual ActuatorVector u() const = 0;
    [[nodiscard]] virtual std::string name() const = 0;
};

/// Plant on nocdyn's own forward dynamics (Simulator) of a model (possibly with a payload).
class SimulatorRobotPlant final : public RobotPlant {
public:
    explicit SimulatorRobotPlant(const Model& model, const SimulatorOptions& options = {});
    void reset(const Pose& p, const Twist& dp) override;
    void setForces(const ActuatorVector& tau) override { simulator_.setForces(tau); }
    void advance(double dt) override;
    [[nodiscard]] Pose pose() const override { return simulator_.pose(); }
    [[nodiscard]] Twist poseRate() const override { return simulator_.poseRate(); }
    [[nodiscard]] ActuatorVector u() const override { return simulator_.u(); }
    [[nodiscard]] std::string name() const override { return "nocdyn forward dynamics"; }

private:
    Simulator simulator_;
};

/// nocdyn's forward dynamics as a plant integrated by one classical Runge-Kutta step (order 4)
/// per advance(dt), the forces held over it: 4 forward-dynamics evaluations per controller tick
/// where the error-controlled Simulator (SimulatorRobotPlant) takes 8. Its error against the
/// Simulator at 1e-10 is bounded by a test (shake_test). Throws nocdyn::Error "plant: t = ... s:
/// reason" when a stage fails (out of reach, singular).
class RungeKuttaRobotPlant final : public RobotPlant {
public:
    explicit RungeKuttaRobotPlant(const Model& model);
    void reset(const Pose& p, const Twist& dp) override;
    void setForces(const ActuatorVector& tau) override { tau_ = tau; }
    void advance(double dt) override;
    [[nodiscard]] Pose pose() const override { return p_; }
    [[nodiscard]] Twist poseRate() const override { return dp_; }
    [[nodiscard]] ActuatorVector u() const override;
    [[nodiscard]] std::string name() const override { return "nocdyn forward dynamics, RK4 per tick"; }

private:
    /// d2p/dt2 at (p, dp) under tau_, into a.
    void acceleration(const Pose& p, const Twist& dp, Twist& a);
    Model model_;
    Data data_;
    mutable Data pose_data_;  ///< u() of the current pose
    Pose p_ = Pose::Zero();
    Twist dp_ = Twist::Zero();
    ActuatorVector tau_;
    double t_ = 0.0;
};

}  // namespace nocdyn
