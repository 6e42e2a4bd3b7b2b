// Trajectory sampling through the per-sample inverse dynamics of any robot, with the limits
// checked between output samples as well (see sampling.hpp).
#include "nocdyn/analysis/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

SampleGrid sampleGrid(double duration, double rate) {
    if (!std::isfinite(duration) || duration <= 0.0) {
        throw Error("duration must be a positive number of seconds, got " + std::to_string(duration));
    }
    if (!std::isfinite(rate) || rate <= 0.0) {
        throw Error("rate must be a positive number of samples per second, got " + std::to_string(rate));
    }
    const double count = std::round(duration * rate);
    if (count < 1.0) throw Error("duration * rate rounds to zero samples");
    if (count > 1e8) throw Error("duration * rate asks for more than 10^8 samples");
    return {rate, static_cast<std::size_t>(count)};
}

std::vector<double> sampleTimes(double duration, double rate) {
    const SampleGrid grid = sampleGrid(duration, rate);
    std::vector<double> times(grid.count);
    for (std::size_t k = 0; k < times.size(); ++k) times[k] = grid.time(k);
    return times;
}

double highestFrequency(const PoseTrajectory& trajectory) {
    double highest = 0.0;
    for (const AxisMotion* axis : {&trajectory.theta, &trajectory.x, &trajectory.y}) {
        for (const Harmonic& h : axis->harmonics) {
            if (h.amplitude != 0.0) highest = std::max(highest, std::abs(h.frequency));
        }
    }
    return highest;
}

namespace {

/// "t = ... s: reason".
std::string atTime(double t, const std::string& reason) { return text::sampleTime(t) + ": " + reason; }

/// The per-sample path with every check; holds the scratch Data, the peaks and violations.
class Sampler {
public:
    Sampler(const Model& model, const PoseTrajectory& trajectory, LimitPolicy policy)
        : model_(model), trajectory_(trajectory), policy_(policy), data_(model) {
        const double f = highestFrequency(trajectory);
        spacing_ = f > 0.0 ? 1.0 / (kLimitChecksPerPeriod * f) : 0.0;
        summary.peak_u.assign(static_cast<std::size_t>(model.actuators), 0.0);
        summary.peak_tau.assign(static_cast<std::size_t>(model.actuators), 0.0);
    }

    /// Sample at t: inverse dynamics, finiteness, workspace, joint and effort limits.
    void evaluate(double t, InverseDynamicsSample& s, bool between) {
        const char* where = between ? " (between output samples)" : "";
        s.t = t;
        trajectory_.evaluate(t, s.p, s.dp, s.ddp);
        if (!s.p.allFinite() || !s.dp.allFinite() || !s.ddp.allFinite()) {
            throw Error(atTime(t, std::string("the trajectory's pose or its derivatives are not finite") + where));
        }
        if (const Status status = inverseDynamics(model_, data_, s.p, s.dp, s.ddp); !status) {
            throw Error(atTime(t, describe(status, model_) + where));
        }
        for (int a = 0; a < model_.actuators; ++a) {
            if (!std::isfinite(data_.u(a)) || !std::isfinite(data_.du(a)) || !std::isfinite(data_.ddu(a)) ||
                !std::isfinite(data_.tau(a))) {
                throw Error(atTime(t, "actuator " + std::to_string(a + 1) +
                                          ": the inverse dynamics is not finite (u = " + text::precise(data_.u(a)) +
                                          ", tau = " + text::precise(data_.tau(a)) + ")" + where));
            }
        }
        for (const Status limit : {checkJointLimits(model_, data_), checkEffort(model_, data_)}) {
            if (limit) continue;
            const std::string message = atTime(t, describe(limit, model_) + where);
            if (policy_ == LimitPolicy::error) throw Error(message);
            if (summary.limit_violations.size() < 10) summary.limit_violations.push_back(message);
        }
        for (int a = 0; a < model_.actuators; ++a) {
            const auto aa = static_cast<std::size_t>(a);
            summary.peak_u[aa] = std::max(summary.peak_u[aa], std::abs(data_.u(a)));
            summary.peak_tau[aa] = std::max(summary.peak_tau[aa], std::abs(data_.tau(a)));
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
        for (std::int64_t i = 1; static_cast<double>(i) < pieces; ++i) {
            evaluate(t0 + (t1 - t0) * (static_cast<double>(i) / pieces), scratch_, true);
            ++summary.checks_between_samples;
        }
    }

    LimitSummary summary;
    /// The state of the last evaluate(), every stage computed.
    [[nodiscard]] const Data& data() const { return data_; }

private:
    const Model& model_;
    const PoseTrajectory& trajectory_;
    LimitPolicy policy_;
    double spacing_ = 0.0;  ///< largest interval between checked points [s]; 0: constant pose
    Data data_;
    InverseDynamicsSample scratch_;
};

}  // namespace

void requireBoundedWork(const PoseTrajectory& trajectory, double duration, std::size_t samples) {
    const double f = highestFrequency(trajectory);
    const double points = std::max(static_cast<double>(samples), duration * kLimitChecksPerPeriod * f);
    const double harmonics = static_cast<double>(trajectory.theta.harmonics.size() + trajectory.x.harmonics.size() +
                                                 trajectory.y.harmonics.size());
    const double work = points * std::max(harmonics, 1.0);
    if (work > kMaxTrajectoryWork) {
        // about 10 ns a harmonic term and its two derivatives, 1 us a point of inverse dynamics
        const double hours = points * (1e-6 + 1e-8 * harmonics) / 3600.0;
        throw Error("trajectory '" + trajectory.name + "': " + text::precise(points) +
                    " points (the samples, and the limit checks at " + std::to_string(kLimitChecksPerPeriod) +
                    " a period of its highest harmonic, " + text::precise(f) + " Hz) of " + text::precise(harmonics) +
                    " harmonics: " + text::precise(work) + " harmonic terms, about " + text::precise(hours) +
                    " h of computing, more than the " + text::precise(kMaxTrajectoryWork) +
                    " accepted: shorten the duration, or use fewer or lower harmonics");
    }
}

void requireRateAboveNyquist(const PoseTrajectory& trajectory, double rate) {
    const double f = highestFrequency(trajectory);
    if (f > 0.0 && !(rate > 2.0 * f)) {
        throw Error("sampling rate " + text::precise(rate) +
                    " Hz is not above twice the highest frequency of trajectory '" + trajectory.name + "' (" +
                    text::precise(f) + " Hz), so its samples would alias: use a rate above " + text::precise(2.0 * f) +
                    " Hz");
    }
}

void requireReachable(const Model& model, const PoseTrajectory& trajectory, double duration) {
    const double f = highestFrequency(trajectory);
    requireBoundedWork(trajectory, duration, 1);
    const double pieces = f > 0.0 ? std::ceil(duration * kLimitChecksPerPeriod * f) : 1.0;
    Data data(model);
    Pose p, dp, ddp;
    for (std::int64_t i = 0; static_cast<double>(i) <= pieces; ++i) {
        const double t = duration * (static_cast<double>(i) / pieces);
        trajectory.evaluate(t, p, dp, ddp);
        if (!p.allFinite() || !dp.allFinite() || !ddp.allFinite()) {
            throw Error(atTime(t, "the trajectory's pose or its derivatives are not finite"));
        }
        if (const Status status = inverseDynamics(model, data, p, dp, ddp); !status) {
            throw Error(atTime(t, describe(status, model)));
        }
        if (!data.u.allFinite() || !data.du.allFinite() || !data.ddu.allFinite() || !data.tau.allFinite()) {
            throw Error(atTime(t, "the inverse dynamics is not finite"));
        }
    }
}

LimitSummary streamInverseDynamics(const Model& model, const PoseTrajectory& trajectory, const SampleGrid& grid,
                                   LimitPolicy policy, const std::function<void(const InverseDynamicsSample&)>& sink) {
    requireRateAboveNyquist(trajectory, grid.rate);
    requireBoundedWork(trajectory, static_cast<double>(grid.count) / grid.rate, grid.count);
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

LimitSummary streamInverseDynamicsWithReactions(
    const Model& model, const PoseTrajectory& trajectory, const SampleGrid& grid, LimitPolicy policy,
    const std::function<void(const InverseDynamicsSample&, const Reactions&)>& sink) {
    requireRateAboveNyquist(trajectory, grid.rate);
    Sampler sampler(model, trajectory, policy);
    InverseDynamicsSample sample;
    Reactions reactions;
    for (std::size_t k = 0; k < grid.count; ++k) {
        const double t = grid.time(k);
        if (k > 0) sampler.checkBetween(grid.time(k - 1), t);
        sampler.evaluate(t, sample, false);
        jointReactions(model, sampler.data(), reactions);
        for (int j = 0; j < model.limbs; ++j) {
            for (const Vector3& r : reactions.joint[static_cast<std::size_t>(j)]) {
                if (!r.allFinite()) throw Error(atTime(t, model.limbName(j) + ": the joint reactions are not finite"));
            }
        }
        sink(sample, reactions);
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
    if (!times.empty()) requireBoundedWork(trajectory, times.back() - times.front(), times.size());
    InverseDynamicsSeries series;
    series.samples.resize(times.size());
    Sampler sampler(model, trajectory, policy);
    for (std::size_t k = 0; k < times.size(); ++k) {
        if (k > 0) sampler.checkBetween(times[k - 1], times[k]);
        sampler.evaluate(times[k], series.samples[k], false);
    }
    series.summary = std::move(sampler.summary);
    return series;
}

}  // namespace nocdyn
