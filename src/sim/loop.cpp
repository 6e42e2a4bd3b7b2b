// The closed loop's tick (loop.hpp).
#include "loop.hpp"

#include <algorithm>
#include <cmath>

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::detail {

void failTick(const Model& model, double t, const Status& status, const char* what) {
    throw Error(text::sampleTime(t) + ": " + what + ": " + describe(status, model));
}

void runTicks(PoseController& controller, RobotPlant& plant, const PoseTrajectory& trajectory,
              const std::vector<double>& times, Data& data, LoopSensing& sensing, const LoopClock& clock,
              const TickKeeping& keeping, PoseLoopResult& result) {
    const Model& model = controller.model();
    const double dt = 1.0 / clock.rate;
    const int n = model.actuators;
    for (auto* v : {&result.p, &result.p_d}) v->reserve(times.size());
    if (keeping.keep_actuators) {
        for (auto* v : {&result.u, &result.u_d, &result.tau}) v->reserve(times.size());
        if (sensing.readsEncoders()) result.u_measured.reserve(times.size());
    }
    result.t.reserve(times.size());
    // the actuator summaries, accumulated here when the ticks are not kept
    const auto un = static_cast<std::size_t>(n);
    std::vector<double> sum_sq(un, 0.0), peak(un, 0.0), peak_tau(un, 0.0);

    PoseReference reference;
    Sensed sensed;
    ActuatorVector tau(n);
    Pose next_p, next_dp, next_ddp;
    for (const double t : times) {
        if (clock.progress) clock.progress(t);
        if (const Status status = poseReference(model, data, trajectory, t, reference); !status) {
            failTick(model, t, status, "reference");
        }
        // feed-forward: the mean reference acceleration over the hold, so that the held force
        // gives the reference's change of rate over the tick
        trajectory.evaluate(t + dt, next_p, next_dp, next_ddp);
        const Twist ddp_ff = (next_dp - reference.dp) / dt;
        const Pose p = plant.pose();
        const Twist dp = plant.poseRate();
        if (!p.allFinite() || !dp.allFinite()) failTick(model, t, {StatusCode::not_finite, -1, 0.0}, "plant state");
        sensing.sense(t, plant, p, dp, reference, ddp_ff, sensed);
        if (const Status status = controller.compute(sensed.p, sensed.dp, sensed.command, tau); !status) {
            failTick(model, t, status, "controller");
        }
        if (clock.saturation && controller.saturate(tau)) ++result.saturated_ticks;
        const ActuatorVector u_now = plant.u();
        if (keeping.on_tick != nullptr && *keeping.on_tick) (*keeping.on_tick)(result.t.size(), t, u_now, tau);
        result.t.push_back(t);
        result.p.push_back(p);
        result.p_d.push_back(reference.p);
        if (keeping.keep_actuators) {
            result.u.push_back(u_now);
            result.u_d.push_back(reference.u);
            result.tau.push_back(tau);
            if (sensed.u_measured != nullptr) result.u_measured.push_back(*sensed.u_measured);
        } else {
            for (int a = 0; a < n; ++a) {
                const auto ai = static_cast<std::size_t>(a);
                const double e = std::abs(reference.u(a) - u_now(a));
                sum_sq[ai] += e * e;
                peak[ai] = std::max(peak[ai], e);
                peak_tau[ai] = std::max(peak_tau[ai], std::abs(tau(a)));
            }
        }
        plant.setForces(tau);
        plant.advance(dt);
    }

    summarizeLoop(result);
    if (!keeping.keep_actuators && !result.t.empty()) {
        result.rms_error.resize(un);
        for (std::size_t a = 0; a < un; ++a)
            result.rms_error[a] = std::sqrt(sum_sq[a] / static_cast<double>(result.t.size()));
        result.peak_error = peak;
        result.peak_tau = peak_tau;
    }
}

}  // namespace nocdyn::detail
