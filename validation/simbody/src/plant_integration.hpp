// The forward-dynamics plants' time step (SimbodyRobot, SimbodyMechanism): Simbody's error-
// controlled integrator over the plant's State. The integrator is started from the plant State
// after a reset or a new accuracy; from then on its own advanced State is the plant's state:
// new actuator forces are written into it and the integrator is told that the Dynamics stage
// changed (Integrator::reinitialize), so it keeps its step size across the control ticks
// instead of restarting from a guessed one, and nothing is copied per tick. The integrator
// never steps past the end of a tick (no interpolation), so the forces are held exactly over
// [t, t + dt) (zero-order hold). Internal to nocdyn_simbody.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include <Simbody.h>

#include "nocdyn/error.hpp"

namespace nocdyn::validation::detail {

/// Shortest integrator step [s] (see advancePlant).
inline constexpr double kMinStep = 1e-6;

/// Integrator state of one plant.
struct PlantIntegration {
    bool stale = true;        ///< the plant State changed since the integrator last started from it
    bool started = false;     ///< the integrator ran since the last reset
    long steps_before = 0;    ///< steps of the integrator's earlier runs since the last reset
    double accuracy = 1e-10;  ///< integrator accuracy; the constraint tolerance is 1 % of it

    /// True when the integrator's advanced State is the plant's state (else the plant State is).
    [[nodiscard]] bool live() const { return started && !stale; }

    /// The plant State was overwritten from outside (a reset): the integrator restarts from it.
    void reset() {
        stale = true;
        started = false;
        steps_before = 0;
    }
    [[nodiscard]] long steps(const SimTK::Integrator& integrator) const {
        return steps_before + (started ? integrator.getNumStepsTaken() : 0);
    }
    /// The plant's current state: the integrator's while it runs, else the plant State.
    [[nodiscard]] const SimTK::State& current(const SimTK::Integrator& integrator, const SimTK::State& plant) const {
        return live() ? integrator.getAdvancedState() : plant;
    }
    /// The State to write new actuator forces into; call forcesChanged() after writing them.
    [[nodiscard]] SimTK::State& forceState(SimTK::Integrator& integrator, SimTK::State& plant) const {
        return live() ? integrator.updAdvancedState() : plant;
    }
    /// New actuator forces were written into forceState(): a discontinuity at the Dynamics
    /// stage, which the running integrator handles without a restart (its step size is kept).
    void forcesChanged(SimTK::Integrator& integrator) const {
        if (live()) integrator.reinitialize(SimTK::Stage::Dynamics, false);
    }
    /// A new accuracy: the integrator restarts from the current state with it.
    void setAccuracy(double value, const SimTK::Integrator& integrator, SimTK::State& plant) {
        if (!(value > 0.0 && value < 1.0)) throw Error("Simbody plant: integrator accuracy must lie in (0, 1)");
        if (live()) plant = integrator.getAdvancedState();
        accuracy = value;
        stale = true;
    }
};

/// Integrates the plant forward dt >= 0 seconds (from the plant State when the integrator must
/// restart, else from where the integrator stands). Throws nocdyn::Error for a bad dt or when
/// Simbody's integration fails (naming the time).
inline void advancePlant(SimTK::Integrator& integrator, SimTK::State& plant, PlantIntegration& run, double dt) {
    if (!(dt >= 0.0) || !std::isfinite(dt)) {
        throw Error("Simbody plant: advance() needs a finite dt >= 0, got " + std::to_string(dt));
    }
    if (dt == 0.0) return;
    if (!run.live()) {
        if (run.started) run.steps_before += integrator.getNumStepsTaken();
        run.started = true;
        integrator.setAccuracy(run.accuracy);
        integrator.setConstraintTolerance(0.01 * run.accuracy);
        // every tick ends on a step: the advanced State is the plant's state at the tick's end
        integrator.setAllowInterpolation(false);
        // Coulomb friction's sign q' is discontinuous where a joint's rate changes sign: there
        // the error control would shrink the step without end; at the floor, a step of 1 us
        // is accepted (its error from the jump is ~ jump * h^2, far below the accuracy)
        integrator.setMinimumStepSize(kMinStep);
        integrator.initialize(plant);
        run.stale = false;
    }
    const double target = integrator.getAdvancedTime() + dt;
    // stepTo returns at the target unless an event, a restart or a report interrupts it:
    // bounded retries
    constexpr int kMaxCalls = 1000;
    try {
        for (int call = 0; call < kMaxCalls && integrator.getAdvancedTime() < target; ++call)
            integrator.stepTo(target, target);
    } catch (const std::exception& ex) {
        // Simbody restored the last good State: continue from there after a restart
        plant = integrator.getAdvancedState();
        run.stale = true;
        std::ostringstream msg;
        msg << "Simbody plant: integration failed at t = " << integrator.getAdvancedTime() << " s: " << ex.what();
        throw Error(msg.str());
    }
    if (integrator.getAdvancedTime() < target) throw Error("Simbody plant: the integrator did not reach its target");
}

}  // namespace nocdyn::validation::detail
