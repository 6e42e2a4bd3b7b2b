// Time integration of the forward dynamics (forward_dynamics.hpp) of any robot, under actuator
// forces held, or given as samples and interpolated (ForceSignal).
//
// Simulator integrates the state with Boost.Odeint's controlled Dormand-Prince 5(4) stepper
// (adaptive steps, error per component |err| <= abs + rel |x|), ending a step at every instant
// where the actuator forces are not smooth (ForceSignal::pieceEnd) so that no step straddles a
// jump, and reads the state between steps from the stepper's dense output.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "nocdyn/choice.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// How the actuator forces vary between their samples.
enum class Interpolation {
    hold,    ///< zero-order hold: tau_k on [t_k, t_k+1), as a DAC outputs it
    linear,  ///< straight lines between the samples
    cubic,   ///< interpolating cubic B-spline (C2) through uniformly spaced samples
};

inline constexpr std::array<Choice<Interpolation>, 3> kInterpolations{
    {{Interpolation::hold, "hold"}, {Interpolation::linear, "linear"}, {Interpolation::cubic, "cubic"}}};
[[nodiscard]] constexpr std::span<const Choice<Interpolation>> choices(Interpolation) { return kInterpolations; }

/// "hold", "linear" or "cubic".
[[nodiscard]] inline const char* name(Interpolation interpolation) { return nameOf(interpolation).data(); }

/// Actuator forces given at increasing times and interpolated in between; held at the first
/// sample before it and at the last one after it. Built once (allocates, throws nocdyn::Error);
/// evaluated without allocating.
///
/// The signal is smooth on pieces: for hold and linear the pieces are the intervals between
/// samples; the cubic spline is smooth on [t_0, t_last] as a whole (Boost.Math's
/// cardinal_cubic_b_spline, endpoint slopes estimated to O(h^4)). Piece k (0..N) is the
/// interval [t_(k-1), t_k) (piece 0 before the first sample, piece N after the last).
class ForceSignal {
public:
    /// tau[s] are the n forces at times[s]. Throws nocdyn::Error naming `source` for no sample,
    /// samples of different sizes, non-increasing or non-finite times or values, and, with
    /// cubic, times that are not uniformly spaced (to 1e-6 of the step). With fewer than 5
    /// samples (too few for the spline's endpoint slopes) cubic is taken as linear.
    ForceSignal(std::vector<double> times, const std::vector<ActuatorVector>& tau, Interpolation interpolation,
                const std::string& source = "forces");
    /// The same from flat storage: tau holds `actuators` forces a sample, sample after sample
    /// (kept as given: 8 bytes a force, no per-sample overhead).
    ForceSignal(std::vector<double> times, std::vector<double> tau, int actuators, Interpolation interpolation,
                const std::string& source = "forces");
    ~ForceSignal();
    ForceSignal(ForceSignal&&) noexcept;
    ForceSignal& operator=(ForceSignal&&) noexcept;
    ForceSignal(const ForceSignal&) = delete;
    ForceSignal& operator=(const ForceSignal&) = delete;

    [[nodiscard]] int actuators() const;
    [[nodiscard]] std::size_t samples() const;
    [[nodiscard]] double firstTime() const;
    [[nodiscard]] double lastTime() const;
    /// The interpolation in use (linear when cubic was asked with fewer than 5 samples).
    [[nodiscard]] Interpolation interpolation() const;

    /// Piece containing time t: the number of samples at or before t.
    [[nodiscard]] std::size_t piece(double t) const;
    /// End of piece k: the next instant where the signal is not smooth (+infinity for the last).
    [[nodiscard]] double pieceEnd(std::size_t k) const;
    /// Forces at t as given on piece k (continuous up to and including the piece's end, so
    /// that an integration step ending there sees the piece's own limit). Allocation-free.
    void evaluate(double t, std::size_t k, ActuatorVector& tau) const;
    /// Forces at t (right-continuous: at a sample of a hold, that sample's value).
    [[nodiscard]] ActuatorVector at(double t) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// The integrator's error control as a user chooses it (the command line's and Python's `atol`,
/// `rtol` and `max_step`), shared by SimulatorOptions and the simulate job's options.
struct IntegrationTolerances {
    double atol = 1e-12;     ///< absolute, per component of (p [rad, m], dp/dt [rad/s, m/s])
    double rtol = 1e-10;     ///< relative
    double max_step = 1e-2;  ///< the largest step [s]
};

struct SimulatorOptions : IntegrationTolerances {
    double initial_step = 1e-5;  ///< [s]
    /// Smallest step the controller may take [s]: below it advance() fails with
    /// integration_step_too_small instead of crawling forever.
    double min_step = 1e-12;
    /// A step the error test rejects down to this size [s] is taken at this size without the
    /// test. Coulomb friction's sign q' jumps where a joint's rate changes sign: while a joint
    /// sticks (q' chattering about 0) every step straddles a jump, and the error control would
    /// shrink the step without end. The error of such a step is about the jump in acceleration
    /// times h^2 / 2 (2 N on 1 kg at 1 us: 1e-12 m). 0 turns the floor off.
    double floor_step = 1e-6;
    /// Most steps (accepted and rejected) over one advance(): beyond it integration_too_many_steps.
    std::size_t max_steps = 10'000'000;
    /// Called every 1024 steps of advance() (a caller's Ctrl-C, a deadline). It may throw to
    /// stop the integration; the simulator must then be reset before it is used again.
    std::function<void()> poll = {};
};

/// Time integration of the forward dynamics of any robot. Holds a copy of the model;
/// advance() does not allocate.
class Simulator {
public:
    explicit Simulator(const Model& model, const SimulatorOptions& options = {});
    ~Simulator();
    Simulator(Simulator&&) noexcept;
    Simulator& operator=(Simulator&&) noexcept;
    Simulator(const Simulator&) = delete;
    Simulator& operator=(const Simulator&) = delete;

    /// Starts at pose p with rate dp at time t, under zero forces until advance() gives some.
    /// Fails (leaving the previous state) when p or dp is out of reach, singular or not finite.
    /// A two-DOF robot (model.task_dimension == 2) starts at [home(0), p(1), p(2)] with rate
    /// [0, dp(1), dp(2)]: its state is [x, y] and their rates, theta no coordinate of it.
    Status reset(const Pose& p, const Twist& dp = Twist::Zero(), double t = 0.0);

    /// From now on, the forces held at tau (n values). Allocation-free.
    void setForces(const ActuatorVector& tau);
    /// From now on, the forces of a signal (kept by the simulator); the integration stops at
    /// the end of each of its pieces.
    void setForces(ForceSignal forces);

    /// Integrates over dt >= 0 [s] under the forces set. The integrator keeps its own steps
    /// (chosen by its error control) across calls while the forces stay set, and gives the
    /// state at t + dt by its dense output; so the output rate does not cost steps. On
    /// failure the simulator stops at the last state it reached (time() tells when), with
    /// the Status of what stopped it: unreachable, singular_limb (naming the limb),
    /// singular_actuation, integration_step_too_small, integration_too_many_steps, or
    /// not_finite (also for forces of the wrong size). Allocation-free.
    Status advance(double dt);
    /// setForces(tau), then advance(dt): a zero-order hold over dt.
    Status advance(double dt, const ActuatorVector& tau);

    [[nodiscard]] double time() const;
    [[nodiscard]] const Pose& pose() const;
    [[nodiscard]] const Twist& poseRate() const;
    [[nodiscard]] const Twist& poseAcceleration() const;
    [[nodiscard]] const ActuatorVector& u() const;
    [[nodiscard]] const ActuatorVector& du() const;
    /// The forces in effect at the current time [N, N m].
    [[nodiscard]] const ActuatorVector& tau() const;
    /// Kinetic energy of every body [J].
    [[nodiscard]] double kineticEnergy() const;
    /// Potential energy of gravity (potentialEnergy in dynamics.hpp) [J].
    [[nodiscard]] double potentialEnergy() const;
    /// Every stage, position to forward dynamics, at the current state and forces.
    [[nodiscard]] const Data& data() const;
    [[nodiscard]] const Model& model() const;
    [[nodiscard]] const SimulatorOptions& options() const;
    /// Accepted and rejected integration steps, and right-hand-side evaluations, since construction.
    [[nodiscard]] std::size_t acceptedSteps() const;
    [[nodiscard]] std::size_t rejectedSteps() const;
    [[nodiscard]] std::size_t evaluations() const;
    /// Of the accepted steps, those taken at SimulatorOptions::floor_step without the error test.
    [[nodiscard]] std::size_t flooredSteps() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nocdyn
