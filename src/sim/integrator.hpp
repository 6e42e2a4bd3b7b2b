// The adaptive integration shared by the planar and the spatial simulators (simulator.hpp,
// spatial_simulator.hpp): Boost.Odeint's controlled Dormand-Prince 5(4) stepper over the state
// x = [p; dp/dt] of a plant, the actuator forces held or interpolated (ForceSignal), steps that
// end at every instant where the forces are not smooth, and the state between steps from the
// stepper's dense output. Not part of the API.
//
// A Plant provides
//   using State = std::array<double, 2 d>;
//   int actuators() const;
//   Status derivative(const State& x, const ActuatorVector& tau, State& dxdt);  // scratch data
//   Status current(const State& x, const ActuatorVector& tau);  // every stage into its data
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <tuple>
#include <utility>

#include <boost/numeric/odeint.hpp>

#include "nocdyn/sim/simulator.hpp"

namespace nocdyn::detail {

// The integrator runs ahead of the simulator's time: its last accepted step goes from
// (x_old, t_old) to (x_new, t_new), and the state at any time in between is the stepper's
// dense output (4th order), so that the steps are the error control's and not the output
// rate's. New forces (setForces, reset) restart it at the current time.
template <class Plant>
struct Integrator {
    using State = typename Plant::State;
    using Dopri5 = boost::numeric::odeint::runge_kutta_dopri5<State>;
    using Controlled = boost::numeric::odeint::controlled_runge_kutta<Dopri5>;
    static constexpr std::size_t kDof = std::tuple_size_v<State> / 2;

    Integrator(Plant p, const SimulatorOptions& o)
        : plant(std::move(p)),
          options(o),
          stepper(boost::numeric::odeint::make_controlled(o.atol, o.rtol, Dopri5())),
          held(ActuatorVector::Zero(plant.actuators())),
          force(ActuatorVector::Zero(plant.actuators())),
          step(o.initial_step) {}

    Plant plant;
    SimulatorOptions options;
    unsigned polled = 0;  // steps since the start, for options.poll
    Controlled stepper;
    ActuatorVector held;
    ActuatorVector force;                 ///< scratch for the forces at one evaluation
    std::unique_ptr<ForceSignal> signal;  ///< forces from samples, else `held`
    std::size_t piece = 0;                ///< piece of `signal` of the step being taken

    double t = 0.0;  ///< current time
    State x{};       ///< state at t
    double t_old = 0.0, t_new = 0.0;
    State x_old{}, d_old{}, x_new{}, d_new{};
    std::size_t d_new_piece = 0;  ///< piece under which d_new was evaluated
    bool restart = true;          ///< (x_new, d_new) must be re-evaluated at t
    double step;                  ///< step size proposed by the controller [s]
    Status failure;
    std::size_t accepted = 0, rejected = 0, evaluations = 0;
    std::size_t forced = 0;  ///< accepted steps taken at the floor without the error test

    void forcesAt(double time, std::size_t k, ActuatorVector& tau) const {
        if (signal) {
            signal->evaluate(time, k, tau);
        } else {
            tau = held;
        }
    }

    /// dx/dt = [dp; d2p]; on failure records it (the step is then retried smaller).
    void rhs(const State& xs, State& dxdt, double time) {
        ++evaluations;
        forcesAt(time, piece, force);
        const Status status = plant.derivative(xs, force, dxdt);
        if (!status) {
            if (failure.ok()) failure = status;
            for (std::size_t i = 0; i < kDof; ++i) {
                dxdt[i] = xs[i + kDof];
                dxdt[i + kDof] = 0.0;
            }
        }
    }

    [[nodiscard]] std::size_t pieceAt(double time) const { return signal ? signal->piece(time) : 0; }
    [[nodiscard]] double pieceEnd(std::size_t k) const {
        return signal ? signal->pieceEnd(k) : std::numeric_limits<double>::infinity();
    }

    /// Every stage at the current time and state into the plant's data.
    Status evaluateCurrent() {
        forcesAt(t, pieceAt(t), force);
        return plant.current(x, force);
    }

    /// Starts at x at time t under zero forces.
    void start(const State& x0, double time) {
        held.setZero();
        signal.reset();
        x = x0;
        t = time;
        step = options.initial_step;
        restart = true;
    }

    void setForces(const ActuatorVector& tau) {
        signal.reset();
        held = tau;
        restart = true;
    }

    void setForces(ForceSignal forces) {
        signal = std::make_unique<ForceSignal>(std::move(forces));
        restart = true;
    }

    Status advance(double dt) {
        if (signal ? signal->actuators() != plant.actuators() : held.size() != plant.actuators()) {
            return {StatusCode::not_finite, -1, static_cast<double>(signal ? signal->actuators() : held.size())};
        }
        if (!(dt >= 0.0) || !std::isfinite(dt)) return {StatusCode::not_finite, -1, dt};
        if (dt == 0.0) {
            restart = true;  // the forces may have changed at t
            return evaluateCurrent();
        }
        return advanceTo(t + dt);
    }

    /// Derivative at the end of the last step under the forces of the piece that follows.
    Status refreshDerivative() {
        piece = pieceAt(t_new);
        failure = {};
        rhs(x_new, d_new, t_new);
        d_new_piece = piece;
        return failure;
    }

    /// One accepted step from (x_new, t_new), not past the end of the current piece.
    Status takeStep(std::size_t& steps) {
        if (d_new_piece != pieceAt(t_new)) {
            if (const Status status = refreshDerivative(); !status) return status;
        }
        piece = d_new_piece;
        const double end = pieceEnd(piece);
        for (;;) {
            if (++steps > options.max_steps) {
                return {StatusCode::integration_too_many_steps, -1, static_cast<double>(steps - 1)};
            }
            const double room = end - t_new;
            const bool clipped = std::min(step, options.max_step) >= room;
            bool lands = clipped;  // the step ends on the piece's end
            double h = clipped ? room : std::min(step, options.max_step);
            double time = t_new;
            State x_next{}, d_next{};
            failure = {};
            const auto result = stepper.try_step([this](const State& xs, State& d, double tt) { rhs(xs, d, tt); },
                                                 x_new, d_new, time, x_next, d_next, h);
            if (!failure.ok()) {
                // a trial state out of reach or singular: retry much shorter, down to min_step
                ++rejected;
                step = 0.25 * std::min(step, room);
                if (step < options.min_step) return failure;
                continue;
            }
            if (result != boost::numeric::odeint::success) {
                ++rejected;
                step = h;  // reduced by the controller
                if (h < options.floor_step) {
                    // at the floor (SimulatorOptions::floor_step): the step is taken untested
                    lands = options.floor_step >= room;
                    h = std::min(options.floor_step, room);
                    time = t_new;
                    failure = {};
                    stepper.stepper().do_step([this](const State& xs, State& d, double tt) { rhs(xs, d, tt); }, x_new,
                                              d_new, time, x_next, d_next, h);
                    if (!failure.ok()) return failure;
                    ++forced;
                    time += h;
                    step = options.floor_step;
                } else {
                    if (step < options.min_step) return {StatusCode::integration_step_too_small, -1, step};
                    continue;
                }
            }
            ++accepted;
            if (!clipped && result == boost::numeric::odeint::success)
                step = h;  // the controller's proposal for the next step
            x_old = x_new;
            d_old = d_new;
            t_old = t_new;
            x_new = x_next;
            d_new = d_next;
            // land exactly on the end of a piece, so that the next piece starts there
            t_new = lands ? end : time;
            return {};
        }
    }

    Status advanceTo(double t_end) {
        if (restart) {
            x_new = x_old = x;
            t_new = t_old = t;
            if (const Status status = refreshDerivative(); !status) return status;
            d_old = d_new;
            restart = false;
        }
        std::size_t steps = 0;
        while (t_new < t_end) {
            if (options.poll && (++polled & 1023U) == 0) {
                restart = true;  // a throw leaves the step half taken
                options.poll();
                restart = false;
            }
            if (const Status status = takeStep(steps); !status) {
                // stop at the last state reached
                x = x_new;
                t = t_new;
                (void)evaluateCurrent();
                restart = true;
                return status;
            }
        }
        if (t_end == t_new) {
            x = x_new;
        } else {
            stepper.stepper().calc_state(t_end, x, x_old, d_old, t_old, x_new, d_new, t_new);
        }
        t = t_end;
        return evaluateCurrent();
    }
};

}  // namespace nocdyn::detail
