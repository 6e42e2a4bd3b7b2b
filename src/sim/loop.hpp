// The closed loop's tick, one for every loop (runPoseLoop, runShakeLoop): the reference at t
// and the feed-forward over the hold, the plant's state, what the controller sees (the sensing
// policy: the state itself, noisy, or the encoders and accelerometers through an estimator),
// the forces computed and clipped, the tick recorded, the forces held over dt.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "nocdyn/model.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/plant.hpp"
#include "nocdyn/status.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::detail {

/// Throws nocdyn::Error "t = <t> s: <what>: <status>".
[[noreturn]] void failTick(const Model& model, double t, const Status& status, const char* what);

/// What the controller sees at a tick.
struct Sensed {
    Pose p = Pose::Zero();                       ///< the pose it measures or estimates
    Twist dp = Twist::Zero();                    ///< and its rate
    PoseReference command;                       ///< what it tracks (the reference, or the servo's demand)
    const ActuatorVector* u_measured = nullptr;  ///< the encoders' reading, if any
};

/// The sensing policy: from the plant (true state (p, dp), read by the loop) and the reference
/// (ddp_ff: its mean acceleration over the hold) to what the controller sees.
class LoopSensing {
public:
    virtual ~LoopSensing() = default;
    virtual void sense(double t, const RobotPlant& plant, const Pose& p, const Twist& dp,
                       const PoseReference& reference, const Twist& ddp_ff, Sensed& out) = 0;
    /// Whether sense() gives an encoder reading (kept in result.u_measured).
    [[nodiscard]] virtual bool readsEncoders() const = 0;
};

/// What the shake table's loop adds to the clock (ShakeLoopOptions): keep_actuators false keeps
/// u, u_d, tau and u_measured only in the summaries and hands each tick's to on_tick.
struct TickKeeping {
    bool keep_actuators = true;
    const std::function<void(std::size_t, double, const ActuatorVector&, const ActuatorVector&)>* on_tick = nullptr;
};

/// Runs the ticks at `times` on a plant already reset (data: the workspace of the reference at
/// t = 0), then the summaries of `result` (summarizeLoop; without kept ticks, the actuators'
/// summaries accumulated here).
void runTicks(PoseController& controller, RobotPlant& plant, const PoseTrajectory& trajectory,
              const std::vector<double>& times, Data& data, LoopSensing& sensing, const LoopClock& clock,
              const TickKeeping& keeping, PoseLoopResult& result);

}  // namespace nocdyn::detail
