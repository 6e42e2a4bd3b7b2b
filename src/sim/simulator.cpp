// Time integration of the forward dynamics (Boost.Odeint) and the interpolated actuator forces
// (Boost.Math) (simulator.hpp).
#include "nocdyn/sim/simulator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>
#include <boost/numeric/odeint.hpp>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"

namespace nocdyn {

// ---- interpolated forces ------------------------------------------------------------

const char* name(Interpolation interpolation) {
    switch (interpolation) {
        case Interpolation::hold:
            return "hold";
        case Interpolation::linear:
            return "linear";
        case Interpolation::cubic:
            break;
    }
    return "cubic";
}

struct ForceSignal::Impl {
    std::vector<double> t;
    /// The forces sample by sample, n to a sample (flat: 8 n bytes a sample, nothing more).
    std::vector<double> tau;
    Eigen::Index n = 0;
    Interpolation interpolation = Interpolation::cubic;
    /// One spline per actuator (cubic only).
    std::vector<boost::math::interpolators::cardinal_cubic_b_spline<double>> spline;

    [[nodiscard]] Eigen::Map<const Eigen::VectorXd> sample(std::size_t k) const {
        return {tau.data() + k * static_cast<std::size_t>(n), n};
    }
};

namespace {

/// Smallest number of samples from which the spline estimates its endpoint slopes.
constexpr std::size_t kMinSplineSamples = 5;
/// Largest deviation of a sample time from the uniform grid accepted for the spline, in steps.
constexpr double kUniformTolerance = 1e-6;

std::vector<double> flatten(const std::vector<ActuatorVector>& tau) {
    const auto n = static_cast<std::size_t>(tau.empty() ? 0 : tau.front().size());
    std::vector<double> flat;
    flat.reserve(n * tau.size());
    for (const ActuatorVector& f : tau) {
        if (static_cast<std::size_t>(f.size()) != n) break;  // refused by the constructor
        flat.insert(flat.end(), f.data(), f.data() + n);
    }
    return flat;
}

}  // namespace

ForceSignal::ForceSignal(std::vector<double> times, const std::vector<ActuatorVector>& tau, Interpolation interpolation,
                         const std::string& source)
    : impl_(std::make_unique<Impl>()) {
    if (times.size() != tau.size()) throw Error(source + ": as many force samples as times are needed");
    for (std::size_t k = 0; k < tau.size(); ++k) {
        if (tau[k].size() != tau.front().size()) {
            std::ostringstream out;
            out.precision(17);
            out << source << ": sample " << k + 1 << " (t = " << times[k] << " s): " << tau[k].size()
                << " forces, not all finite (expected " << tau.front().size() << ")";
            throw Error(out.str());
        }
    }
    const int n = tau.empty() ? 0 : static_cast<int>(tau.front().size());
    *this = ForceSignal(std::move(times), flatten(tau), n, interpolation, source);
}

ForceSignal::ForceSignal(std::vector<double> times, std::vector<double> tau, int actuators, Interpolation interpolation,
                         const std::string& source)
    : impl_(std::make_unique<Impl>()) {
    Impl& s = *impl_;
    if (times.empty()) throw Error(source + ": no force sample");
    const auto n = static_cast<Eigen::Index>(actuators);
    if (n < 1 || n > kMaxActuators || tau.size() != times.size() * static_cast<std::size_t>(n))
        throw Error(source + ": as many force samples as times are needed");
    s.tau = std::move(tau);
    s.n = n;
    for (std::size_t k = 0; k < times.size(); ++k) {
        std::ostringstream out;
        out.precision(17);
        if (!std::isfinite(times[k])) {
            out << source << ": sample " << k + 1 << ": t is not finite";
            throw Error(out.str());
        }
        if (k > 0 && !(times[k] > times[k - 1])) {
            out << source << ": sample " << k + 1 << ": t = " << times[k]
                << " s does not increase (previous: " << times[k - 1] << " s)";
            throw Error(out.str());
        }
        if (!s.sample(k).allFinite()) {
            out << source << ": sample " << k + 1 << " (t = " << times[k] << " s): " << n
                << " forces, not all finite (expected " << n << ")";
            throw Error(out.str());
        }
    }
    if (interpolation == Interpolation::cubic && times.size() < kMinSplineSamples)
        interpolation = Interpolation::linear;
    s.t = std::move(times);
    s.interpolation = interpolation;
    if (interpolation != Interpolation::cubic) return;
    // cardinal B-spline: uniform samples t_k = t_0 + k h
    const std::size_t N = s.t.size();
    const double h = (s.t.back() - s.t.front()) / static_cast<double>(N - 1);
    for (std::size_t k = 0; k < N; ++k) {
        const double expected = s.t.front() + static_cast<double>(k) * h;
        if (std::abs(s.t[k] - expected) > kUniformTolerance * h) {
            std::ostringstream out;
            out.precision(17);
            out << source << ": sample " << k + 1 << ": t = " << s.t[k] << " s is off the uniform grid of step " << h
                << " s (expected " << expected
                << " s); cubic interpolation needs uniformly spaced samples: resample them, or use linear or hold";
            throw Error(out.str());
        }
    }
    std::vector<double> f(N);
    s.spline.reserve(static_cast<std::size_t>(n));
    for (Eigen::Index a = 0; a < n; ++a) {
        for (std::size_t k = 0; k < N; ++k) f[k] = s.sample(k)(a);
        // endpoint slopes by the one-sided five-point differences, O(h^4); given here because
        // the estimate of the right one in Boost 1.74 mirrors the wrong samples (an O(1) slope
        // error, 4e-4 on x^3 sampled at h = 0.01: tested)
        const std::size_t e = N - 1;
        const double left = (-25.0 * f[0] + 48.0 * f[1] - 36.0 * f[2] + 16.0 * f[3] - 3.0 * f[4]) / (12.0 * h);
        const double right =
            (25.0 * f[e] - 48.0 * f[e - 1] + 36.0 * f[e - 2] - 16.0 * f[e - 3] + 3.0 * f[e - 4]) / (12.0 * h);
        s.spline.emplace_back(f.data(), N, s.t.front(), h, left, right);
    }
}

ForceSignal::~ForceSignal() = default;
ForceSignal::ForceSignal(ForceSignal&&) noexcept = default;
ForceSignal& ForceSignal::operator=(ForceSignal&&) noexcept = default;

int ForceSignal::actuators() const { return static_cast<int>(impl_->n); }
std::size_t ForceSignal::samples() const { return impl_->t.size(); }
double ForceSignal::firstTime() const { return impl_->t.front(); }
double ForceSignal::lastTime() const { return impl_->t.back(); }
Interpolation ForceSignal::interpolation() const { return impl_->interpolation; }

std::size_t ForceSignal::piece(double t) const {
    return static_cast<std::size_t>(std::upper_bound(impl_->t.begin(), impl_->t.end(), t) - impl_->t.begin());
}

double ForceSignal::pieceEnd(std::size_t k) const {
    const std::vector<double>& t = impl_->t;
    if (k >= t.size()) return std::numeric_limits<double>::infinity();
    // the spline is smooth from the first sample to the last
    if (impl_->interpolation == Interpolation::cubic && k > 0) return t.back();
    return t[k];
}

void ForceSignal::evaluate(double time, std::size_t k, ActuatorVector& tau) const {
    const Impl& s = *impl_;
    const std::size_t N = s.t.size();
    if (k == 0 || N == 1) {
        tau = s.sample(0);
        return;
    }
    if (k >= N) {
        tau = s.sample(s.t.size() - 1);
        return;
    }
    switch (s.interpolation) {
        case Interpolation::hold:
            tau = s.sample(k - 1);
            return;
        case Interpolation::linear: {
            const double r = std::clamp((time - s.t[k - 1]) / (s.t[k] - s.t[k - 1]), 0.0, 1.0);
            tau = s.sample(k - 1) + r * (s.sample(k) - s.sample(k - 1));
            return;
        }
        case Interpolation::cubic: {
            const double x = std::clamp(time, s.t.front(), s.t.back());
            tau.resize(static_cast<Eigen::Index>(s.spline.size()));
            for (std::size_t a = 0; a < s.spline.size(); ++a) tau(static_cast<Eigen::Index>(a)) = s.spline[a](x);
            return;
        }
    }
}

ActuatorVector ForceSignal::at(double t) const {
    ActuatorVector tau;
    evaluate(t, piece(t), tau);
    return tau;
}

// ---- time integration -----------------------------------------------------------------

namespace {

namespace odeint = boost::numeric::odeint;
/// Integrator state x = [theta, x_c, y_c, dtheta, dx_c, dy_c] (fixed size: no allocation).
using State = std::array<double, 6>;
using Dopri5 = odeint::runge_kutta_dopri5<State>;
using Controlled = odeint::controlled_runge_kutta<Dopri5>;

Pose poseOf(const State& x) { return {x[0], x[1], x[2]}; }
Twist rateOf(const State& x) { return {x[3], x[4], x[5]}; }

}  // namespace

// The integrator runs ahead of the simulator's time: its last accepted step goes from
// (x_old, t_old) to (x_new, t_new), and the state at any time in between is the stepper's
// dense output (4th order), so that the steps are the error control's and not the output
// rate's. New forces (setForces, reset) restart it at the current time.
struct Simulator::Impl {
    Impl(const Model& m, const SimulatorOptions& o)
        : model(m),
          options(o),
          stepper(odeint::make_controlled(o.absolute_tolerance, o.relative_tolerance, Dopri5())),
          data(model),
          scratch(model),
          held(ActuatorVector::Zero(m.actuators)),
          force(ActuatorVector::Zero(m.actuators)),
          step(o.initial_step) {}

    Model model;
    SimulatorOptions options;
    unsigned polled = 0;  // steps since the start, for options.poll
    Controlled stepper;
    Data data;     ///< every stage at the current time
    Data scratch;  ///< right-hand-side evaluations
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
        const Status status = forwardDynamics(model, scratch, poseOf(xs), rateOf(xs), force);
        for (std::size_t i = 0; i < 3; ++i) dxdt[i] = xs[i + 3];
        if (!status) {
            if (failure.ok()) failure = status;
            for (std::size_t i = 3; i < 6; ++i) dxdt[i] = 0.0;
            return;
        }
        for (std::size_t i = 0; i < 3; ++i) dxdt[i + 3] = scratch.t_M_dot(static_cast<Eigen::Index>(i));
    }

    [[nodiscard]] std::size_t pieceAt(double time) const { return signal ? signal->piece(time) : 0; }
    [[nodiscard]] double pieceEnd(std::size_t k) const {
        return signal ? signal->pieceEnd(k) : std::numeric_limits<double>::infinity();
    }

    /// Every stage at the current time and state into `data`.
    Status evaluateCurrent() {
        forcesAt(t, pieceAt(t), force);
        return forwardDynamics(model, data, poseOf(x), rateOf(x), force);
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
            if (result != odeint::success) {
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
            if (!clipped && result == odeint::success) step = h;  // the controller's proposal for the next step
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

Simulator::Simulator(const Model& model, const SimulatorOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {
    (void)reset(model.home);
}

Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

Status Simulator::reset(const Pose& p_in, const Twist& dp_in, double t) {
    Impl& s = *impl_;
    // a two-DOF robot's state is [x, y] and its rates: theta at home(0), at rest (E p_t, E dp_t)
    const bool task = s.model.task_dimension == 2;
    const Pose p = task ? Pose(s.model.home(0), p_in(1), p_in(2)) : p_in;
    const Twist dp = task ? Twist(0.0, dp_in(1), dp_in(2)) : dp_in;
    s.held.setZero();
    s.signal.reset();
    if (const Status status = forwardDynamics(s.model, s.scratch, p, dp, s.held); !status) return status;
    s.x = {p(0), p(1), p(2), dp(0), dp(1), dp(2)};
    s.t = t;
    s.step = s.options.initial_step;
    s.restart = true;
    return s.evaluateCurrent();
}

void Simulator::setForces(const ActuatorVector& tau) {
    impl_->signal.reset();
    impl_->held = tau;
    impl_->restart = true;
}

void Simulator::setForces(ForceSignal forces) {
    impl_->signal = std::make_unique<ForceSignal>(std::move(forces));
    impl_->restart = true;
}

Status Simulator::advance(double dt) {
    Impl& s = *impl_;
    if (s.signal ? s.signal->actuators() != s.model.actuators : s.held.size() != s.model.actuators) {
        return {StatusCode::not_finite, -1, static_cast<double>(s.signal ? s.signal->actuators() : s.held.size())};
    }
    if (!(dt >= 0.0) || !std::isfinite(dt)) return {StatusCode::not_finite, -1, dt};
    if (dt == 0.0) {
        s.restart = true;  // the forces may have changed at t
        return s.evaluateCurrent();
    }
    return s.advanceTo(s.t + dt);
}

Status Simulator::advance(double dt, const ActuatorVector& tau) {
    setForces(tau);
    return advance(dt);
}

double Simulator::time() const { return impl_->t; }
const Pose& Simulator::pose() const { return impl_->data.p; }
const Twist& Simulator::poseRate() const { return impl_->data.t_M; }
const Twist& Simulator::poseAcceleration() const { return impl_->data.t_M_dot; }
const ActuatorVector& Simulator::u() const { return impl_->data.u; }
const ActuatorVector& Simulator::du() const { return impl_->data.du; }
const ActuatorVector& Simulator::tau() const { return impl_->data.tau; }
double Simulator::kineticEnergy() const { return nocdyn::kineticEnergy(impl_->model, impl_->data); }
double Simulator::potentialEnergy() const { return nocdyn::potentialEnergy(impl_->model, impl_->data); }
const Data& Simulator::data() const { return impl_->data; }
const Model& Simulator::model() const { return impl_->model; }
const SimulatorOptions& Simulator::options() const { return impl_->options; }
std::size_t Simulator::acceptedSteps() const { return impl_->accepted; }
std::size_t Simulator::rejectedSteps() const { return impl_->rejected; }
std::size_t Simulator::evaluations() const { return impl_->evaluations; }
std::size_t Simulator::flooredSteps() const { return impl_->forced; }

}  // namespace nocdyn
