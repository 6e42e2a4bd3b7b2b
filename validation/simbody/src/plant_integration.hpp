// The forward-dynamics plants' time step (SimbodyRobot, SimbodyMechanism): Simbody's error-
// controlled integrator over a plant State, restarted from that State whenever it changed
// from outside (a reset, new actuator forces, a new accuracy). Internal to nocdyn_simbody.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include <Simbody.h>

#include "nocdyn/error.hpp"

namespace nocdyn::validation::detail {

/// Integrator state of one plant.
struct PlantIntegration {
    bool stale = true;        ///< the plant State changed since the integrator last started from it
    bool started = false;     ///< the integrator ran since the last reset
    long steps_before = 0;    ///< steps of the integrator's earlier runs since the last reset
    double accuracy = 1e-10;  ///< integrator accuracy; the constraint tolerance is 1 % of it

    void reset() {
        stale = true;
        started = false;
        steps_before = 0;
    }
    [[nodiscard]] long steps(const SimTK::Integrator& integrator) const {
        return steps_before + (started ? integrator.getNumStepsTaken() : 0);
    }
    void setAccuracy(double value) {
        if (!(value > 0.0 && value < 1.0)) throw Error("Simbody plant: integrator accuracy must lie in (0, 1)");
        accuracy = value;
        stale = true;
    }
};

/// Integrates `plant` forward dt >= 0 seconds. Throws nocdyn::Error for a bad dt or when
/// Simbody's integration fails (naming the time).
inline void advancePlant(const SimTK::MultibodySystem& system, SimTK::Integrator& integrator, SimTK::State& plant,
                         PlantIntegration& run, double dt) {
    if (!(dt >= 0.0) || !std::isfinite(dt)) {
        throw Error("Simbody plant: advance() needs a finite dt >= 0, got " + std::to_string(dt));
    }
    if (dt == 0.0) return;
    if (run.stale) {
        if (run.started) run.steps_before += integrator.getNumStepsTaken();
        run.started = true;
        integrator.setAccuracy(run.accuracy);
        integrator.setConstraintTolerance(0.01 * run.accuracy);
        integrator.setProjectInterpolatedStates(true);
        integrator.initialize(plant);
        run.stale = false;
    }
    const double target = plant.getTime() + dt;
    // stepTo returns at the target unless an event or a report interrupts it: bounded retries
    constexpr int kMaxCalls = 1000;
    try {
        for (int call = 0; call < kMaxCalls && integrator.getTime() < target; ++call) integrator.stepTo(target);
    } catch (const std::exception& ex) {
        run.stale = true;
        std::ostringstream msg;
        msg << "Simbody plant: integration failed at t = " << integrator.getTime() << " s: " << ex.what();
        throw Error(msg.str());
    }
    if (integrator.getTime() < target) throw Error("Simbody plant: the integrator did not reach its target");
    plant = integrator.getState();
    system.realize(plant, SimTK::Stage::Velocity);
}

}  // namespace nocdyn::validation::detail
