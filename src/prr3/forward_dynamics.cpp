// 3-PRR forward dynamics (eq. 20 solved for ddu) and its integration with Boost.Odeint.
#include "nocdyn/prr3/forward_dynamics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <Eigen/Cholesky>
#include <boost/numeric/odeint.hpp>

#include "nocdyn/error.hpp"
#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"

namespace nocdyn::prr3 {

Status forwardDynamics(const Model& model, Data& data, const JointVector& tau, const ExternalLoads& loads) {
    twistShaping(model, data);
    jointSpaceDynamics(model, data);
    // eq. 20: I ddu = tau - C du, plus T_7^T w_ext (eq. 31) and viscous friction -b du
    JointVector rhs = tau;
    rhs.noalias() -= data.C * data.du;
    rhs.noalias() += data.T[kPlatformBody].transpose() * loads.platform_wrench;
    rhs -= loads.viscous_friction.cwiseProduct(data.du);
    const Eigen::LLT<JointMatrix> llt(data.I);
    if (llt.info() != Eigen::Success) return {StatusCode::singular_forward_jacobian, -1, data.I.diagonal().minCoeff()};
    data.tau = tau;
    const JointVector ddu = llt.solve(rhs);
    platformAcceleration(data, ddu);  // d/dt of eq. 5
    return {};
}

Status forwardDynamicsFromState(const Model& model, Data& data, const JointVector& u, const JointVector& du,
                                const JointVector& tau, Pose& pose, const ExternalLoads& loads,
                                const TrackerOptions& tracker) {
    if (const Status status = trackPose(model, data, u, pose, tracker); !status) return status;
    if (const Status status = velocityFromActuatorRates(model, data, du); !status) return status;
    return forwardDynamics(model, data, tau, loads);
}

namespace {

namespace odeint = boost::numeric::odeint;
/// Integrator state x = [u_1, u_2, u_3, du_1, du_2, du_3] (fixed size: no allocation).
using State = std::array<double, 6>;
using Dopri5 = odeint::runge_kutta_dopri5<State>;
using Controlled = odeint::controlled_runge_kutta<Dopri5>;

}  // namespace

struct Simulator::Impl {
    Impl(const Model& m, const SimulatorOptions& o)
        : model(m),
          options(o),
          stepper(odeint::make_controlled(o.absolute_tolerance, o.relative_tolerance, Dopri5())),
          step(o.initial_step) {}

    Model model;
    SimulatorOptions options;
    Controlled stepper;
    Data data;     ///< all stages at the current (accepted) state
    Data scratch;  ///< right-hand-side evaluations
    State x{};
    double t = 0.0;
    double step;                ///< step size proposed by the controller [s]
    Pose pose = Pose::Zero();   ///< pose at the accepted state
    Pose trial = Pose::Zero();  ///< pose found at the last right-hand-side evaluation
    // force profile of the current segment: tau(t) linear from tau_0 at t_0 to tau_1 at t_0 + dt
    JointVector tau_0 = JointVector::Zero(), tau_1 = JointVector::Zero();
    double t_0 = 0.0, dt = 0.0;
    Status failure;
    std::size_t accepted = 0, rejected = 0;

    JointVector forceAt(double time) const {
        const double s = dt > 0.0 ? std::clamp((time - t_0) / dt, 0.0, 1.0) : 0.0;
        return tau_0 + s * (tau_1 - tau_0);
    }

    /// dx/dt = [du; ddu]; on failure records it and returns a zero acceleration.
    void rhs(const State& xs, State& dxdt, double time) {
        const JointVector u(xs[0], xs[1], xs[2]);
        const JointVector du(xs[3], xs[4], xs[5]);
        Pose guess = trial;
        Status status =
            forwardDynamicsFromState(model, scratch, u, du, forceAt(time), guess, options.loads, options.tracker);
        if (!status) {
            guess = pose;  // retry from the last accepted pose
            status =
                forwardDynamicsFromState(model, scratch, u, du, forceAt(time), guess, options.loads, options.tracker);
        }
        for (int j = 0; j < 3; ++j) dxdt[j] = xs[3 + j];
        if (!status) {
            if (failure.ok()) failure = status;
            for (int j = 0; j < 3; ++j) dxdt[3 + j] = 0.0;
            return;
        }
        trial = guess;
        for (int j = 0; j < 3; ++j) dxdt[3 + j] = scratch.ddu(j);
    }

    /// Full evaluation at the current state into `data`.
    Status evaluateCurrent() {
        const JointVector u(x[0], x[1], x[2]);
        const JointVector du(x[3], x[4], x[5]);
        Pose p = pose;
        const Status status =
            forwardDynamicsFromState(model, data, u, du, forceAt(t), p, options.loads, options.tracker);
        if (status) pose = trial = p;
        return status;
    }

    Status integrate(double span) {
        t_0 = t;
        dt = span;
        const double t_end = t + span;
        stepper.reset();  // the FSAL derivative of the last segment used other forces
        const double eps = 1e-13 * std::max(1.0, std::abs(t_end));
        std::size_t steps = 0;
        while (t_end - t > eps) {
            if (++steps > options.max_steps) {
                return {StatusCode::integration_too_many_steps, -1, static_cast<double>(steps - 1)};
            }
            const double remaining = t_end - t;
            const bool clipped = std::min(step, options.max_step) >= remaining;
            double h = clipped ? remaining : std::min(step, options.max_step);
            const State x_saved = x;
            const double t_saved = t;
            failure = {};
            const auto result =
                stepper.try_step([this](const State& xs, State& d, double time) { rhs(xs, d, time); }, x, t, h);
            if (!failure.ok()) {
                // The tracker failed at a trial state: retry with a much smaller step.
                x = x_saved;
                t = t_saved;
                trial = pose;
                stepper.reset();
                ++rejected;
                step = 0.25 * std::min(step, remaining);
                if (step < 1e-12) return failure;
                continue;
            }
            if (result == odeint::success) {
                ++accepted;
                pose = trial;
                if (!clipped) step = h;  // the controller's proposal for the next step
            } else {
                ++rejected;
                step = h;  // reduced by the controller
                // (a step clipped to a tiny remainder of the interval is not the controller's doing)
                if (step < options.min_step && remaining > options.min_step) {
                    return {StatusCode::integration_step_too_small, -1, step};
                }
            }
        }
        t = t_end;
        return evaluateCurrent();
    }
};

Simulator::Simulator(const Model& model, const SimulatorOptions& options)
    : impl_(std::make_unique<Impl>(model, options)) {
    (void)impl_->evaluateCurrent();
}

Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

Status Simulator::reset(const Pose& p, const Twist& dp, double t) {
    Data& d = impl_->data;
    if (const Status status = inverseDisplacement(impl_->model, d, p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(impl_->model, d, dp); !status) return status;
    return resetActuators(d.u, d.du, p, t);
}

Status Simulator::resetActuators(const JointVector& u, const JointVector& du, const Pose& pose_guess, double t) {
    Impl& s = *impl_;
    for (int j = 0; j < 3; ++j) {
        s.x[j] = u(j);
        s.x[3 + j] = du(j);
    }
    s.t = t;
    s.pose = s.trial = pose_guess;
    s.tau_0.setZero();
    s.tau_1.setZero();
    s.t_0 = t;
    s.dt = 0.0;
    s.step = s.options.initial_step;
    s.stepper.reset();
    return s.evaluateCurrent();
}

Status Simulator::advance(double dt, const JointVector& tau) { return advance(dt, tau, tau); }

Status Simulator::advance(double dt, const JointVector& tau_begin, const JointVector& tau_end) {
    impl_->tau_0 = tau_begin;
    impl_->tau_1 = tau_end;
    if (!(dt > 0.0)) {
        impl_->dt = 0.0;
        return impl_->evaluateCurrent();
    }
    return impl_->integrate(dt);
}

double Simulator::time() const { return impl_->t; }
JointVector Simulator::u() const { return {impl_->x[0], impl_->x[1], impl_->x[2]}; }
JointVector Simulator::du() const { return {impl_->x[3], impl_->x[4], impl_->x[5]}; }
Pose Simulator::pose() const { return impl_->pose; }
Twist Simulator::poseRate() const { return impl_->data.t_M; }
double Simulator::kineticEnergy() const { return noc::kineticEnergy(impl_->data.I, du()); }
std::size_t Simulator::acceptedSteps() const { return impl_->accepted; }
std::size_t Simulator::rejectedSteps() const { return impl_->rejected; }
const Data& Simulator::data() const { return impl_->data; }
const Model& Simulator::model() const { return impl_->model; }
const SimulatorOptions& Simulator::options() const { return impl_->options; }

// ---- batch layer ------------------------------------------------------------------

JointVector ForceSeries::at(double time) const {
    if (t.empty()) return JointVector::Zero();
    if (time <= t.front()) return tau.front();
    if (time >= t.back()) return tau.back();
    const auto upper = std::upper_bound(t.begin(), t.end(), time);
    const std::size_t k = static_cast<std::size_t>(upper - t.begin());
    const double s = (time - t[k - 1]) / (t[k] - t[k - 1]);
    return tau[k - 1] + s * (tau[k] - tau[k - 1]);
}

namespace {

std::string atTime(double t, const Status& status, const RobotParameters& robot) {
    std::ostringstream out;
    out.precision(9);
    out << "t = " << t << " s: " << describe(status, robot);
    return out.str();
}

void record(const Simulator& simulator, SimulationSeries& series) {
    series.t.push_back(simulator.time());
    series.p.push_back(simulator.pose());
    series.dp.push_back(simulator.poseRate());
    series.u.push_back(simulator.u());
    series.du.push_back(simulator.du());
    series.tau.push_back(simulator.data().tau);
    series.kinetic.push_back(simulator.kineticEnergy());
}

}  // namespace

SimulationSeries simulateForces(Simulator& simulator, const ForceSeries& forces,
                                const std::vector<double>& output_times) {
    SimulationSeries series;
    const RobotParameters& robot = simulator.model().parameters;
    std::size_t next_force = 0;
    for (const double t_out : output_times) {
        if (t_out < simulator.time() - 1e-12) throw Error("simulation output times must increase");
        // integrate to t_out, stopping at every force sample on the way
        while (simulator.time() < t_out - 1e-15 * std::max(1.0, std::abs(t_out))) {
            const double now = simulator.time();
            while (next_force < forces.t.size() && forces.t[next_force] <= now + 1e-15) ++next_force;
            const double stop = next_force < forces.t.size() ? std::min(t_out, forces.t[next_force]) : t_out;
            const Status status = simulator.advance(stop - now, forces.at(now), forces.at(stop));
            if (!status) throw Error(atTime(simulator.time(), status, robot));
        }
        if (series.t.empty() || t_out > series.t.back()) {
            // refresh the forces stage at exactly t_out (the last segment ended here)
            record(simulator, series);
            series.tau.back() = forces.at(t_out);
        }
    }
    return series;
}

ForceSeries forcesFromTable(const io::Table& table, const std::string& source) {
    ForceSeries forces;
    std::array<std::size_t, 4> column{};
    const char* names[] = {"t", "tau1", "tau2", "tau3"};
    for (int c = 0; c < 4; ++c) {
        if (!table.has(names[c])) throw Error(source + ": missing column '" + names[c] + "'");
        column[c] = table.column(names[c]);
    }
    if (table.rows.empty()) throw Error(source + ": no rows");
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const auto& row = table.rows[r];
        const double t = row[column[0]];
        if (!forces.t.empty() && !(t > forces.t.back())) {
            std::ostringstream out;
            out.precision(17);
            out << source << ":";
            if (r < table.lines.size())
                out << table.lines[r] << ": column 't'";
            else
                out << " row " << r + 1 << ": column 't'";
            out << ": t = " << t << " s does not increase (previous row: " << forces.t.back() << " s)";
            throw Error(out.str());
        }
        forces.t.push_back(t);
        forces.tau.emplace_back(row[column[1]], row[column[2]], row[column[3]]);
    }
    return forces;
}

io::Table toTable(const SimulationSeries& series) {
    io::Table table;
    table.columns = {"t", "x", "y", "theta", "u1", "u2", "u3", "du1", "du2", "du3", "tau1", "tau2", "tau3", "kinetic"};
    table.rows.reserve(series.t.size());
    for (std::size_t k = 0; k < series.t.size(); ++k) {
        const Pose& p = series.p[k];
        table.rows.push_back({series.t[k], p(1), p(2), p(0), series.u[k](0), series.u[k](1), series.u[k](2),
                              series.du[k](0), series.du[k](1), series.du[k](2), series.tau[k](0), series.tau[k](1),
                              series.tau[k](2), series.kinetic[k]});
    }
    return table;
}

}  // namespace nocdyn::prr3
