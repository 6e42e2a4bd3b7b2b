// Trajectory sampling through the per-sample inverse dynamics, with the limits checked
// between output samples as well (see sampling.hpp).
#include "nocdyn/prr3/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"

namespace nocdyn::prr3 {

namespace {

std::string atTime(double t, const std::string& reason) {
    std::ostringstream out;
    out.precision(10);
    out << "t = " << t << " s: " << reason;
    return out.str();
}

std::string number(double value) {
    std::ostringstream out;
    out.precision(10);
    out << value;
    return out.str();
}

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

/// The per-sample path with every check; holds the scratch Data, the peaks and violations.
class Sampler {
public:
    Sampler(const Model& model, const PoseTrajectory& trajectory, LimitPolicy policy)
        : model_(model), trajectory_(trajectory), policy_(policy) {
        const double f = highestFrequency(trajectory);
        spacing_ = f > 0.0 ? 1.0 / (kLimitChecksPerPeriod * f) : 0.0;
    }

    /// Sample at t: inverse dynamics, finiteness, workspace, stroke and force.
    void evaluate(double t, InverseDynamicsSample& s, bool between) {
        const char* where = between ? " (between output samples)" : "";
        s.t = t;
        trajectory_.evaluate(t, s.p, s.dp, s.ddp);
        if (!finite(s.p) || !finite(s.dp) || !finite(s.ddp)) {
            throw Error(atTime(t, std::string("the trajectory's pose or its derivatives are not finite") + where));
        }
        if (const Status status = inverseDynamics(model_, data_, s.p, s.dp, s.ddp); !status) {
            throw Error(atTime(t, describe(status, model_.parameters) + where));
        }
        for (int j = 0; j < kLimbs; ++j) {
            if (!std::isfinite(data_.u(j)) || !std::isfinite(data_.du(j)) || !std::isfinite(data_.ddu(j)) ||
                !std::isfinite(data_.tau(j))) {
                throw Error(atTime(t, "limb " + std::to_string(j + 1) + ": the inverse dynamics is not finite (u = " +
                                          number(data_.u(j)) + " m, tau = " + number(data_.tau(j)) + " N)" + where));
            }
        }
        for (const Status limit : {checkStroke(model_, data_), checkForce(model_, data_)}) {
            if (limit) continue;
            const std::string message = atTime(t, describe(limit, model_.parameters) + where);
            if (policy_ == LimitPolicy::error) throw Error(message);
            if (summary.limit_violations.size() < 10) summary.limit_violations.push_back(message);
        }
        for (int j = 0; j < kLimbs; ++j) {
            summary.peak_stroke[j] = std::max(summary.peak_stroke[j], std::abs(data_.u(j)));
            summary.peak_force[j] = std::max(summary.peak_force[j], std::abs(data_.tau(j)));
        }
        s.u = data_.u;
        s.du = data_.du;
        s.ddu = data_.ddu;
        s.tau = data_.tau;
        if (!between) {
            s.kinetic = kineticEnergy(model_, data_);
            if (!std::isfinite(s.kinetic)) throw Error(atTime(t, "the kinetic energy is not finite"));
        }
    }

    /// Every point strictly between t0 and t1 of a grid no coarser than the check spacing.
    void checkBetween(double t0, double t1) {
        if (spacing_ <= 0.0 || t1 - t0 <= spacing_) return;
        const double pieces = std::ceil((t1 - t0) / spacing_);
        for (double i = 1.0; i < pieces; i += 1.0) {
            evaluate(t0 + (t1 - t0) * (i / pieces), scratch_, true);
            ++summary.checks_between_samples;
        }
    }

    LimitSummary summary;

private:
    const Model& model_;
    const PoseTrajectory& trajectory_;
    LimitPolicy policy_;
    double spacing_ = 0.0;  ///< largest interval between checked points [s]; 0: constant pose
    Data data_;
    InverseDynamicsSample scratch_;
};

}  // namespace

void requireReachable(const Model& model, const PoseTrajectory& trajectory, double duration) {
    const double f = highestFrequency(trajectory);
    const double pieces = f > 0.0 ? std::ceil(duration * kLimitChecksPerPeriod * f) : 1.0;
    Data data;
    Pose p, dp, ddp;
    for (double i = 0.0; i <= pieces; i += 1.0) {
        const double t = duration * (i / pieces);
        trajectory.evaluate(t, p, dp, ddp);
        if (!finite(p) || !finite(dp) || !finite(ddp)) {
            throw Error(atTime(t, "the trajectory's pose or its derivatives are not finite"));
        }
        if (const Status status = inverseDynamics(model, data, p, dp, ddp); !status) {
            throw Error(atTime(t, describe(status, model.parameters)));
        }
        if (!data.u.allFinite() || !data.du.allFinite() || !data.ddu.allFinite() || !data.tau.allFinite()) {
            throw Error(atTime(t, "the inverse dynamics is not finite"));
        }
    }
}

LimitSummary streamInverseDynamics(const Model& model, const PoseTrajectory& trajectory, const SampleGrid& grid,
                                   LimitPolicy policy, const std::function<void(const InverseDynamicsSample&)>& sink) {
    requireRateAboveNyquist(trajectory, grid.rate);
    Sampler sampler(model, trajectory, policy);
    InverseDynamicsSample sample;
    for (std::size_t k = 0; k < grid.count; ++k) {
        const double t = grid.time(k);
        if (k > 0) sampler.checkBetween(grid.time(k - 1), t);
        sampler.evaluate(t, sample, false);
        sink(sample);
    }
    return std::move(sampler.summary);
}

InverseDynamicsSeries sampleInverseDynamics(const Model& model, const PoseTrajectory& trajectory,
                                            const std::vector<double>& times, LimitPolicy policy) {
    for (std::size_t k = 1; k < times.size(); ++k) {
        const double interval = times[k] - times[k - 1];
        if (!(interval > 0.0)) throw Error(atTime(times[k], "sampling times must increase"));
        if (2.0 * highestFrequency(trajectory) * interval >= 1.0) requireRateAboveNyquist(trajectory, 1.0 / interval);
    }
    InverseDynamicsSeries series;
    const std::size_t n = times.size();
    series.t.reserve(n);
    for (auto* v : {&series.p, &series.dp, &series.ddp}) v->reserve(n);
    for (auto* v : {&series.u, &series.du, &series.ddu, &series.tau}) v->reserve(n);
    series.kinetic.reserve(n);
    Sampler sampler(model, trajectory, policy);
    InverseDynamicsSample s;
    for (std::size_t k = 0; k < n; ++k) {
        if (k > 0) sampler.checkBetween(times[k - 1], times[k]);
        sampler.evaluate(times[k], s, false);
        series.t.push_back(s.t);
        series.p.push_back(s.p);
        series.dp.push_back(s.dp);
        series.ddp.push_back(s.ddp);
        series.u.push_back(s.u);
        series.du.push_back(s.du);
        series.ddu.push_back(s.ddu);
        series.tau.push_back(s.tau);
        series.kinetic.push_back(s.kinetic);
    }
    series.peak_stroke = sampler.summary.peak_stroke;
    series.peak_force = sampler.summary.peak_force;
    series.limit_violations = std::move(sampler.summary.limit_violations);
    return series;
}

std::vector<std::string> inverseDynamicsColumns() {
    return {"t",   "x",    "y",    "theta", "u1",   "u2",   "u3",   "du1",    "du2",
            "du3", "ddu1", "ddu2", "ddu3",  "tau1", "tau2", "tau3", "kinetic"};
}

std::array<double, 17> toRow(const InverseDynamicsSample& s) {
    return {s.t,     s.p(1),   s.p(2),   s.p(0),   s.u(0),   s.u(1),   s.u(2),   s.du(0),  s.du(1),
            s.du(2), s.ddu(0), s.ddu(1), s.ddu(2), s.tau(0), s.tau(1), s.tau(2), s.kinetic};
}

io::Table toTable(const InverseDynamicsSeries& series) {
    io::Table table;
    table.columns = inverseDynamicsColumns();
    table.rows.reserve(series.t.size());
    InverseDynamicsSample s;
    for (std::size_t k = 0; k < series.t.size(); ++k) {
        s.t = series.t[k];
        s.p = series.p[k];
        s.u = series.u[k];
        s.du = series.du[k];
        s.ddu = series.ddu[k];
        s.tau = series.tau[k];
        s.kinetic = series.kinetic[k];
        const auto row = toRow(s);
        table.rows.emplace_back(row.begin(), row.end());
    }
    return table;
}

}  // namespace nocdyn::prr3
