// Time integration of a spatial robot's forward dynamics (spatial::forwardDynamics) under
// actuator forces held or interpolated (ForceSignal): the same adaptive Dormand-Prince 5(4)
// integration as the planar Simulator (simulator.hpp), over the state [p; dp/dt] with p the
// pose [x, y, z, roll, pitch, yaw] (or [x, y, z] for motion: translation). Every limb follows
// from p by its inverse kinematics at each evaluation, so the loops stay closed exactly (no
// drift of the constraints); the energy's drift is the integrator's error alone.
#pragma once

#include <cstddef>
#include <memory>

#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/spatial.hpp"

namespace nocdyn::spatial {

class Simulator {
public:
    /// Starts at home, at rest. Holds a copy of the model; advance() does not allocate.
    explicit Simulator(const Model& model, const SimulatorOptions& options = {});
    ~Simulator();
    Simulator(Simulator&&) noexcept;
    Simulator& operator=(Simulator&&) noexcept;
    Simulator(const Simulator&) = delete;
    Simulator& operator=(const Simulator&) = delete;

    /// Starts at pose p with rate dp at time t, under zero forces until forces are set. Fails
    /// (leaving the previous state) when p or dp is out of reach, singular or not finite.
    Status reset(const TaskVector& p, const TaskVector& dp, double t = 0.0);
    /// From now on, the forces held at tau (n values), or those of a signal.
    void setForces(const nocdyn::ActuatorVector& tau);
    void setForces(ForceSignal forces);
    /// Integrates over dt >= 0 [s] under the forces set (Simulator::advance in simulator.hpp).
    Status advance(double dt);

    [[nodiscard]] double time() const;
    [[nodiscard]] TaskVector pose() const;
    [[nodiscard]] TaskVector poseRate() const;
    [[nodiscard]] TaskVector poseAcceleration() const;
    /// Every stage at the current state and forces (u, du, ddu, tau, the limbs' joints).
    [[nodiscard]] const Data& data() const;
    [[nodiscard]] const Model& model() const;
    [[nodiscard]] double kineticEnergy() const;
    [[nodiscard]] double potentialEnergy() const;
    [[nodiscard]] std::size_t acceptedSteps() const;
    [[nodiscard]] std::size_t rejectedSteps() const;
    [[nodiscard]] std::size_t evaluations() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nocdyn::spatial
