// Computed-torque and PD control of a spatial robot in its pose coordinates, and the closed
// loop on its simulated forward dynamics (spatial_simulator.hpp): the planar controllers
// (sim/control.hpp) in six (or three) coordinates.
//   computed torque: tau = inverse dynamics at the measured (p, dp) with
//                    ddp_cmd = ddp_d + K_d (dp_d - dp) + K_p (p_d - p);
//   PD:              A_E(p)^T tau = M(home) (K_p (p_d - p) + K_d (dp_d - dp)),
// tau the minimum-norm forces when redundant, K_p = w^2, K_d = 2 w, w = 2 pi f_n (critically
// damped error dynamics with a perfect model), each force clipped at its joint's effort.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/simulator.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_trajectory.hpp"

namespace nocdyn::spatial {

/// The pose sensor's noise (PoseSensorNoise: the measured x, y, z, roll, pitch, yaw and rates).
struct LoopOptions : LoopClock, PoseSensorNoise, FeedbackSettings {
    /// Computed torque: the forces of the state predicted at the middle of the hold,
    /// (p + dp dt / 2 + ddp_cmd dt^2 / 8, dp + ddp_cmd dt / 2), not of the tick's state: the
    /// forces held over the tick then match its mean motion to O(dt^2) (the rate-dependent
    /// terms, and the sign of each joint's Coulomb friction where its rate is about to turn).
    bool mid_hold = false;
    /// The plant's integration (its tolerances, steps); the defaults are spatial::Simulator's.
    SimulatorOptions simulator = {};
    /// The controller's model when it is not the plant's (the plant carrying a payload the
    /// controller knows only as identified); the same actuators and pose coordinates. nullptr:
    /// the plant's.
    const Model* controller_model = nullptr;
};

/// One row per controller tick (the state at the tick, before its forces act).
struct LoopResult {
    std::vector<double> t;
    std::vector<TaskVector> p, p_d;
    std::vector<ActuatorVector> u, u_d, tau;
    TaskVector rms_error, peak_error;  ///< of p_d - p per coordinate
    TaskVector late_peak_error;        ///< over the second half of the run
    std::vector<double> peak_tau;      ///< max |tau| per actuator (after clipping)
    std::size_t saturated_ticks = 0;
};

/// The plant (spatial::Simulator on `model`) starts on the reference (p_d(0), dp_d(0)); each
/// tick measures (p, dp) (+ noise), computes and clips the forces and holds them for 1 / rate.
/// The feedforward acceleration is the reference's mean over the hold. Throws nocdyn::Error
/// "t = ... s: reason" when the reference, the controller or the plant fails.
[[nodiscard]] LoopResult runPoseLoop(const Model& model, const Trajectory& trajectory, const LoopOptions& options);

}  // namespace nocdyn::spatial
