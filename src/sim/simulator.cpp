// Time integration of the forward dynamics (Boost.Odeint) and the interpolated actuator forces
// (Boost.Math) (simulator.hpp).
#include "nocdyn/sim/simulator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <boost/math/interpolators/cardinal_cubic_b_spline.hpp>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "integrator.hpp"

namespace nocdyn {

// ---- interpolated forces ------------------------------------------------------------

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

/// The planar robot's forward dynamics as the integrator's plant: x = [theta, x_c, y_c,
/// dtheta, dx_c, dy_c] (fixed size: no allocation).
struct PlanarPlant {
    using State = std::array<double, 6>;
    explicit PlanarPlant(const Model& m) : model(m), data(model), scratch(model) {}
    PlanarPlant(PlanarPlant&& o) noexcept : model(std::move(o.model)), data(model), scratch(model) {}
    PlanarPlant(const PlanarPlant&) = delete;
    PlanarPlant& operator=(const PlanarPlant&) = delete;
    PlanarPlant& operator=(PlanarPlant&&) = delete;
    ~PlanarPlant() = default;

    Model model;
    Data data;     ///< every stage at the current time
    Data scratch;  ///< right-hand-side evaluations

    static Pose poseOf(const State& x) { return {x[0], x[1], x[2]}; }
    static Twist rateOf(const State& x) { return {x[3], x[4], x[5]}; }
    [[nodiscard]] int actuators() const { return model.actuators; }
    Status derivative(const State& xs, const ActuatorVector& tau, State& dxdt) {
        const Status status = forwardDynamics(model, scratch, poseOf(xs), rateOf(xs), tau);
        if (!status) return status;
        for (std::size_t i = 0; i < 3; ++i) {
            dxdt[i] = xs[i + 3];
            dxdt[i + 3] = scratch.t_M_dot(static_cast<Eigen::Index>(i));
        }
        return {};
    }
    Status current(const State& x, const ActuatorVector& tau) {
        return forwardDynamics(model, data, poseOf(x), rateOf(x), tau);
    }
};

}  // namespace

struct Simulator::Impl : detail::Integrator<PlanarPlant> {
    Impl(const Model& m, const SimulatorOptions& o) : Integrator(PlanarPlant(m), o) {}
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
    const Model& model = s.plant.model;
    const bool task = model.task_dimension == 2;
    const Pose p = task ? Pose(model.home(0), p_in(1), p_in(2)) : p_in;
    const Twist dp = task ? Twist(0.0, dp_in(1), dp_in(2)) : dp_in;
    s.held.setZero();
    if (const Status status = forwardDynamics(model, s.plant.scratch, p, dp, s.held); !status) return status;
    s.start({p(0), p(1), p(2), dp(0), dp(1), dp(2)}, t);
    return s.evaluateCurrent();
}

void Simulator::setForces(const ActuatorVector& tau) { impl_->setForces(tau); }
void Simulator::setForces(ForceSignal forces) { impl_->setForces(std::move(forces)); }
Status Simulator::advance(double dt) { return impl_->advance(dt); }

Status Simulator::advance(double dt, const ActuatorVector& tau) {
    setForces(tau);
    return advance(dt);
}

double Simulator::time() const { return impl_->t; }
const Pose& Simulator::pose() const { return impl_->plant.data.p; }
const Twist& Simulator::poseRate() const { return impl_->plant.data.t_M; }
const Twist& Simulator::poseAcceleration() const { return impl_->plant.data.t_M_dot; }
const ActuatorVector& Simulator::u() const { return impl_->plant.data.u; }
const ActuatorVector& Simulator::du() const { return impl_->plant.data.du; }
const ActuatorVector& Simulator::tau() const { return impl_->plant.data.tau; }
double Simulator::kineticEnergy() const { return nocdyn::kineticEnergy(impl_->plant.model, impl_->plant.data); }
double Simulator::potentialEnergy() const { return nocdyn::potentialEnergy(impl_->plant.model, impl_->plant.data); }
const Data& Simulator::data() const { return impl_->plant.data; }
const Model& Simulator::model() const { return impl_->plant.model; }
const SimulatorOptions& Simulator::options() const { return impl_->options; }
std::size_t Simulator::acceptedSteps() const { return impl_->accepted; }
std::size_t Simulator::rejectedSteps() const { return impl_->rejected; }
std::size_t Simulator::evaluations() const { return impl_->evaluations; }
std::size_t Simulator::flooredSteps() const { return impl_->forced; }

}  // namespace nocdyn
