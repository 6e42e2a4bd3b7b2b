// `inverse-dynamics` of a spatial robot (inverse_dynamics_spatial.hpp).
#include "app/inverse_dynamics_spatial.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/spatial_limits.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

/// "t = ... s: reason".
std::string atTime(double t, const std::string& reason) { return text::sampleTime(t) + ": " + reason; }

/// The per-sample path with every check: holds the scratch Data, the peaks and the violations.
class SpatialSampler {
public:
    SpatialSampler(const spatial::Model& model, const spatial::Trajectory& trajectory, bool allow_limits)
        : model_(model), trajectory_(trajectory), allow_limits_(allow_limits), data_(model) {
        const double f = trajectory.highestFrequency();
        spacing_ = f > 0.0 ? 1.0 / (kLimitChecksPerPeriod * f) : 0.0;
        summary.peak_u.assign(static_cast<std::size_t>(model.actuators), 0.0);
        summary.peak_tau.assign(static_cast<std::size_t>(model.actuators), 0.0);
    }

    /// The sample at t: pose and its derivatives, inverse dynamics, finiteness and limits.
    void evaluate(double t, bool between) {
        const char* where = between ? " (between output samples)" : "";
        trajectory_.evaluate(t, p, dp, ddp);
        if (!p.allFinite() || !dp.allFinite() || !ddp.allFinite()) {
            throw Error(atTime(t, std::string("the trajectory's pose or its derivatives are not finite") + where));
        }
        if (const Status status = spatial::inverseDynamics(model_, data_, p, dp, ddp); !status) {
            throw Error(atTime(t, spatial::describe(status, model_) + where));
        }
        if (!data_.u.allFinite() || !data_.du.allFinite() || !data_.ddu.allFinite() || !data_.tau.allFinite()) {
            throw Error(atTime(t, std::string("the inverse dynamics is not finite") + where));
        }
        checkLimits(t, where);
        for (int a = 0; a < model_.actuators; ++a) {
            const auto aa = static_cast<std::size_t>(a);
            summary.peak_u[aa] = std::max(summary.peak_u[aa], std::abs(data_.u(a)));
            summary.peak_tau[aa] = std::max(summary.peak_tau[aa], std::abs(data_.tau(a)));
        }
        if (!between) {
            kinetic = spatial::kineticEnergy(model_, data_);
            if (!std::isfinite(kinetic)) throw Error(atTime(t, "the kinetic energy is not finite"));
        }
    }

    /// Every point strictly between t0 and t1 of a grid no coarser than the check spacing.
    void checkBetween(double t0, double t1) {
        if (spacing_ <= 0.0 || t1 - t0 <= spacing_) return;
        const double pieces = std::ceil((t1 - t0) / spacing_);
        for (std::int64_t i = 1; static_cast<double>(i) < pieces; ++i) {
            evaluate(t0 + (t1 - t0) * (static_cast<double>(i) / pieces), true);
            ++summary.checks_between_samples;
        }
    }

    [[nodiscard]] const spatial::Data& data() const { return data_; }

    LimitSummary summary;
    spatial::TaskVector p, dp, ddp;  ///< of the last evaluate()
    double kinetic = 0.0;            ///< of the last output sample [J]

private:
    /// A listed R or P joint's range and velocity, an actuator's effort (spatial_limits.hpp):
    /// the first limit passed at this sample.
    void checkLimits(double t, const char* where) {
        if (const Status status = spatial::checkLimits(model_, data_); !status) {
            violation(t, where, spatial::describeLimit(status, model_));
        }
    }

    void violation(double t, const char* where, const std::string& reason) {
        const std::string message = atTime(t, reason + where);
        if (!allow_limits_) throw Error(message);
        if (summary.limit_violations.size() < 10) summary.limit_violations.push_back(message);
    }

    const spatial::Model& model_;
    const spatial::Trajectory& trajectory_;
    bool allow_limits_;
    double spacing_ = 0.0;  ///< largest interval between checked points [s]; 0: no harmonic
    spatial::Data data_;
};

/// Refuses a rate at or below twice the highest harmonic, and a run that would evaluate more
/// than kMaxTrajectoryWork harmonic terms (as the planar sampling does).
void requireSampling(const spatial::Trajectory& trajectory, const SampleGrid& grid) {
    const double f = trajectory.highestFrequency();
    if (f > 0.0 && !(grid.rate > 2.0 * f)) {
        throw Error("sampling rate " + text::precise(grid.rate) +
                    " Hz is not above twice the highest frequency of trajectory '" + trajectory.name + "' (" +
                    text::precise(f) + " Hz), so its samples would alias: use a rate above " + text::precise(2.0 * f) +
                    " Hz");
    }
    const double duration = static_cast<double>(grid.count) / grid.rate;
    const double points = std::max(static_cast<double>(grid.count), duration * kLimitChecksPerPeriod * f);
    const double work = points * std::max(static_cast<double>(trajectory.harmonics()), 1.0);
    if (work > kMaxTrajectoryWork) {
        throw Error("trajectory '" + trajectory.name + "': " + text::precise(points) + " points of " +
                    std::to_string(trajectory.harmonics()) + " harmonics: " + text::precise(work) +
                    " harmonic terms, more than the " + text::precise(kMaxTrajectoryWork) +
                    " accepted: shorten the duration, or use fewer or lower harmonics");
    }
}

}  // namespace

std::vector<std::string> spatialInverseDynamicsColumns(const spatial::Model& model) {
    std::vector<std::string> columns{"t"};
    for (const std::string& c : model.coordinates()) columns.push_back(c);
    for (const char* prefix : {"u", "du", "ddu", "tau"}) {
        for (int a = 1; a <= model.actuators; ++a) columns.push_back(prefix + std::to_string(a));
    }
    columns.emplace_back("kinetic");
    return columns;
}

spatial::Trajectory spatialTrajectoryOf(const SamplingOptions& options, int dimension) {
    if (options.given_trajectory) {
        throw OptionError("trajectory",
                          "a trajectory built in code is planar (x, y, theta): a spatial robot takes a trajectory "
                          "file keyed x, y, z (and roll, pitch, yaw) or a CSV of samples");
    }
    return io::loadSpatialTrajectory(options.trajectory, dimension);
}

InverseDynamicsResult streamSpatialTrajectory(const spatial::Model& model, const spatial::Trajectory& trajectory,
                                              const SamplingOptions& sampling, bool allow_limits, Observer& observer,
                                              const std::function<void()>& start,
                                              const std::function<void(const SpatialSample&)>& sink) {
    validate(sampling);
    if (trajectory.dimension != model.task_dimension) {
        throw Error("trajectory '" + trajectory.name + "': " + std::to_string(trajectory.dimension) +
                    " coordinates, but the robot " + model.name + " has " + std::to_string(model.task_dimension));
    }
    const double duration = sampling.duration ? *sampling.duration : trajectory.duration.value_or(0.2);
    const SampleGrid grid = sampleGrid(duration, sampling.rate);
    requireSampling(trajectory, grid);
    if (start) start();
    SpatialSampler sampler(model, trajectory, allow_limits);
    Meter meter(observer, static_cast<double>(grid.count) / grid.rate, "s");
    for (std::size_t k = 0; k < grid.count; ++k) {
        const double t = grid.time(k);
        if (k > 0) sampler.checkBetween(grid.time(k - 1), t);
        sampler.evaluate(t, false);
        sink(SpatialSample{t, sampler.p, sampler.data(), sampler.kinetic});
        meter(t);
    }
    InverseDynamicsResult out;
    out.samples = grid.count;
    out.summary = std::move(sampler.summary);
    for (const std::string& violation : out.summary.limit_violations) observer.warning(violation);
    return out;
}

InverseDynamicsResult runSpatialInverseDynamics(const spatial::Model& model, const spatial::Trajectory& trajectory,
                                                const SamplingOptions& sampling, bool allow_limits, TableSink& table,
                                                Observer& observer) {
    const int d = model.task_dimension, n = model.actuators;
    std::vector<double> row(static_cast<std::size_t>(1 + d + 4 * n + 1));
    return streamSpatialTrajectory(
        model, trajectory, sampling, allow_limits, observer,
        [&] { table.columns(spatialInverseDynamicsColumns(model)); },
        [&](const SpatialSample& s) {
            std::size_t c = 0;
            row[c++] = s.t;
            for (int i = 0; i < d; ++i) row[c++] = s.p(i);
            for (const spatial::ActuatorVector* v : {&s.data.u, &s.data.du, &s.data.ddu, &s.data.tau}) {
                for (int a = 0; a < n; ++a) row[c++] = (*v)(a);
            }
            row[c] = s.kinetic;
            table.row(row);
        });
}

InverseDynamicsResult runSpatialInverseDynamics(const InverseDynamicsOptions& options, TableSink& table,
                                                Observer& observer) {
    validate(static_cast<const SamplingOptions&>(options));
    if (options.reactions) {
        throw OptionError("reactions",
                          "the joint reactions are computed for planar robots only, not for a spatial "
                          "robot (space: spatial)");
    }
    const spatial::Model model(io::loadSpatialRobotDescription(options.robot.path, options.robot.set));
    const spatial::Trajectory trajectory = spatialTrajectoryOf(options, model.task_dimension);
    return runSpatialInverseDynamics(model, trajectory, options, options.allow_limits, table, observer);
}

}  // namespace nocdyn::app
