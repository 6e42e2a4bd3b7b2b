#include "nocdyn/sim/spatial_control.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <random>

#include <Eigen/LU>

#include "nocdyn/detail/eigen_instances.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/spatial_simulator.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::spatial {

namespace {

/// The effort limit of each actuator (+infinity when none).
ActuatorVector effortLimits(const Model& model) {
    ActuatorVector effort(model.actuators);
    for (int a = 0; a < model.actuators; ++a) {
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a)];
        effort(a) = model.limb[static_cast<std::size_t>(j)].freedoms[static_cast<std::size_t>(k)].limits.effort;
    }
    return effort;
}

[[noreturn]] void fail(double t, const Status& status, const Model& model, const char* what) {
    throw Error(text::sampleTime(t) + ": " + what + ": " + describe(status, model));
}

}  // namespace

LoopResult runPoseLoop(const Model& model, const Trajectory& trajectory, const LoopOptions& options) {
    const int d = model.task_dimension, n = model.actuators;
    const double dt = 1.0 / options.rate, w = 2.0 * std::numbers::pi * options.natural_frequency;
    const double kp = w * w, kd = 2.0 * w;
    const auto ticks = static_cast<std::size_t>(std::llround(options.duration * options.rate));
    const ActuatorVector effort = effortLimits(model);
    const Model& known = options.controller_model != nullptr ? *options.controller_model : model;
    if (known.task_dimension != d || known.actuators != n)
        throw Error("the controller's model and the plant differ in pose coordinates or actuators");
    Data controller(known), reference(model);
    TaskMatrix M_home;
    if (options.controller == ControlLaw::pd) {
        if (const Status status = massMatrix(known, controller, model.home, M_home); !status) {
            throw Error("pd: the mass matrix at home: " + describe(status, known));
        }
    }
    TaskVector p_d, dp_d, ddp_d, p_next, dp_next, ddp_next;
    trajectory.evaluate(0.0, p_d, dp_d, ddp_d);
    Simulator plant(model, options.simulator);
    if (const Status status = plant.reset(p_d, dp_d); !status) fail(0.0, status, model, "the reference's start");
    std::mt19937 rng(options.seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    LoopResult out;
    out.t.reserve(ticks);
    ActuatorVector tau(n);
    TaskVector p(d), dp(d), cmd(d);
    for (std::size_t k = 0; k < ticks; ++k) {
        const double t = static_cast<double>(k) * dt;
        if (options.progress) options.progress(t);
        trajectory.evaluate(t, p_d, dp_d, ddp_d);
        trajectory.evaluate(t + dt, p_next, dp_next, ddp_next);
        if (const Status status = inverseKinematics(model, reference, p_d); !status) {
            fail(t, status, model, "the reference");
        }
        // the measurement
        p = plant.pose();
        dp = plant.poseRate();
        for (int i = 0; i < d; ++i) {
            p(i) += (i < 3 ? options.noise_position : options.noise_angle) * unit(rng);
            dp(i) += options.noise_rate * unit(rng);
        }
        const TaskVector e = p_d - p, de = dp_d - dp;
        if (options.controller == ControlLaw::computed_torque) {
            // the reference's mean acceleration over the hold, and the error feedback
            cmd = (dp_next - dp_d) / dt + kd * de + kp * e;
            if (options.mid_hold) {
                // the state at the middle of the hold, under cmd
                p += (0.5 * dt) * dp + (0.125 * dt * dt) * cmd;
                dp += (0.5 * dt) * cmd;
            }
            const Status status = inverseDynamics(known, controller, p, dp, cmd);
            if (!status) fail(t, status, known, "the controller");
            tau = controller.tau;
        } else {
            if (const Status status = inverseKinematics(known, controller, p); !status) {
                fail(t, status, known, "the controller");
            }
            const TaskVector lambda = M_home * (kp * e + kd * de);
            const ActuationMatrix AE = controller.A.rightCols(d);
            const TaskMatrix gram = AE.transpose() * AE;
            tau.noalias() = AE * Eigen::PartialPivLU<TaskMatrix>(gram).solve(lambda);
        }
        bool clipped = false;
        if (options.saturation) {
            for (int a = 0; a < n; ++a) {
                if (std::abs(tau(a)) > effort(a)) {
                    tau(a) = std::copysign(effort(a), tau(a));
                    clipped = true;
                }
            }
        }
        out.saturated_ticks += clipped ? 1 : 0;
        out.t.push_back(t);
        out.p.push_back(plant.pose());
        out.p_d.push_back(p_d);
        out.u.push_back(plant.data().u);
        out.u_d.push_back(reference.u);
        out.tau.push_back(tau);
        plant.setForces(nocdyn::ActuatorVector(tau));
        if (const Status status = plant.advance(dt); !status) fail(plant.time(), status, model, "the plant");
    }
    // the summaries
    out.rms_error = TaskVector::Zero(d);
    out.peak_error = TaskVector::Zero(d);
    out.late_peak_error = TaskVector::Zero(d);
    out.peak_tau.assign(static_cast<std::size_t>(n), 0.0);
    for (std::size_t k = 0; k < out.t.size(); ++k) {
        const TaskVector e = (out.p_d[k] - out.p[k]).cwiseAbs();
        out.rms_error += e.cwiseAbs2();
        out.peak_error = out.peak_error.cwiseMax(e);
        if (2 * k >= out.t.size()) out.late_peak_error = out.late_peak_error.cwiseMax(e);
        for (int a = 0; a < n; ++a) {
            out.peak_tau[static_cast<std::size_t>(a)] =
                std::max(out.peak_tau[static_cast<std::size_t>(a)], std::abs(out.tau[k](a)));
        }
    }
    if (!out.t.empty()) out.rms_error = (out.rms_error / static_cast<double>(out.t.size())).cwiseSqrt();
    return out;
}

}  // namespace nocdyn::spatial
