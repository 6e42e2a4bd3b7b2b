// Trajectory sampling through the per-sample inverse dynamics (see sampling.hpp).
#include "nocdyn/prr3/sampling.hpp"

#include <cmath>
#include <sstream>

#include "nocdyn/error.hpp"
#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"

namespace nocdyn::prr3 {

std::vector<double> sampleTimes(double duration, double rate) {
    if (!std::isfinite(duration) || duration <= 0.0) {
        throw Error("duration must be a positive number of seconds, got " + std::to_string(duration));
    }
    if (!std::isfinite(rate) || rate <= 0.0) {
        throw Error("rate must be a positive number of samples per second, got " + std::to_string(rate));
    }
    const double count = std::round(duration * rate);
    if (count < 1.0) throw Error("duration * rate rounds to zero samples");
    if (count > 1e8) throw Error("duration * rate asks for more than 10^8 samples");
    std::vector<double> times(static_cast<std::size_t>(count));
    for (std::size_t k = 0; k < times.size(); ++k) times[k] = static_cast<double>(k) / rate;
    return times;
}

namespace {

std::string atTime(double t, const std::string& reason) {
    std::ostringstream out;
    out.precision(10);
    out << "t = " << t << " s: " << reason;
    return out.str();
}

}  // namespace

InverseDynamicsSeries sampleInverseDynamics(const Model& model, const PoseTrajectory& trajectory,
                                            const std::vector<double>& times, LimitPolicy policy) {
    InverseDynamicsSeries series;
    const std::size_t n = times.size();
    series.t = times;
    series.p.resize(n);
    series.dp.resize(n);
    series.ddp.resize(n);
    series.u.resize(n);
    series.du.resize(n);
    series.ddu.resize(n);
    series.tau.resize(n);
    series.kinetic.resize(n);
    Data data;
    for (std::size_t k = 0; k < n; ++k) {
        trajectory.evaluate(times[k], series.p[k], series.dp[k], series.ddp[k]);
        const Status status = inverseDynamics(model, data, series.p[k], series.dp[k], series.ddp[k]);
        if (!status) throw Error(atTime(times[k], describe(status, model.parameters)));
        for (const Status limit : {checkStroke(model, data), checkForce(model, data)}) {
            if (limit) continue;
            const std::string message = atTime(times[k], describe(limit, model.parameters));
            if (policy == LimitPolicy::error) throw Error(message);
            if (series.limit_violations.size() < 10) series.limit_violations.push_back(message);
        }
        series.u[k] = data.u;
        series.du[k] = data.du;
        series.ddu[k] = data.ddu;
        series.tau[k] = data.tau;
        series.kinetic[k] = kineticEnergy(model, data);
        for (int j = 0; j < kLimbs; ++j) {
            series.peak_stroke[j] = std::max(series.peak_stroke[j], std::abs(data.u(j)));
            series.peak_force[j] = std::max(series.peak_force[j], std::abs(data.tau(j)));
        }
    }
    return series;
}

io::Table toTable(const InverseDynamicsSeries& series) {
    io::Table table;
    table.columns = {"t",   "x",   "y",    "theta", "u1",   "u2",   "u3",   "du1",     "du2",
                     "du3", "ddu1", "ddu2", "ddu3", "tau1", "tau2", "tau3", "kinetic"};
    table.rows.reserve(series.t.size());
    for (std::size_t k = 0; k < series.t.size(); ++k) {
        const Pose& p = series.p[k];
        table.rows.push_back({series.t[k], p(1), p(2), p(0), series.u[k](0), series.u[k](1), series.u[k](2),
                              series.du[k](0), series.du[k](1), series.du[k](2), series.ddu[k](0),
                              series.ddu[k](1), series.ddu[k](2), series.tau[k](0), series.tau[k](1),
                              series.tau[k](2), series.kinetic[k]});
    }
    return table;
}

}  // namespace nocdyn::prr3
