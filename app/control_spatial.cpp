#include "app/control_spatial.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "app/inverse_dynamics_spatial.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/escape.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/sim/spatial_control.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn::app {

namespace {

void refusePlanarOnly(const ControlOptions& options) {
    const char* planar = " (planar for now: a spatial robot runs on nocdyn's own plant)";
    if (options.plant_given && options.plant == PlantKind::simbody) {
        throw OptionError("plant", std::string("the Simbody plant of a spatial robot") + planar);
    }
    if (options.payload_mass > 0.0 || options.payload_inertia > 0.0 || !options.payload_com.empty()) {
        throw OptionError("payload_mass", std::string("a payload unknown to the controller") + planar);
    }
    if (options.measure != ControlMeasure::pose || options.noise_u > 0.0 || options.noise_du > 0.0) {
        throw OptionError("measure", std::string("the encoders and the tracker in the loop") + planar);
    }
    if (options.sensor_log || options.noise_tau > 0.0) {
        throw OptionError("log", std::string("the sensors' log") + planar);
    }
}

std::string report(const ControlOptions& options, const spatial::Model& model, const spatial::LoopResult& r,
                   const spatial::LoopOptions& loop, const std::string& trajectory) {
    const std::vector<std::string> names = model.coordinates();
    const int d = model.task_dimension;
    std::string text =
        text::format("%s on the nocdyn plant, %s, %s, %g s at %g Hz (f_n = %g Hz)\n", name(options.controller),
                     io::terminalText(model.name).c_str(), io::terminalText(trajectory).c_str(), loop.duration,
                     loop.rate, options.natural_frequency);
    const auto errors = [&](const char* what, const spatial::TaskVector& e) {
        text += what;
        for (int i = 0; i < d; ++i) {
            text += text::format("%s %s %.4g %s", i == 0 ? "" : ",", names[static_cast<std::size_t>(i)].c_str(),
                                 e(i) * 1e6, i < 3 ? "um" : "urad");
        }
        text += "\n";
    };
    errors("pose: RMS error", r.rms_error);
    errors("pose: peak error", r.peak_error);
    errors("pose, second half: peak error", r.late_peak_error);
    for (int a = 0; a < model.actuators; ++a) {
        const auto [j, k] = model.actuator[static_cast<std::size_t>(a)];
        const spatial::Freedom& f = model.limb[static_cast<std::size_t>(j)].freedoms[static_cast<std::size_t>(k)];
        const char* unit = f.revolute ? "N m" : "N";
        const std::string effort =
            std::isfinite(f.limits.effort) ? text::format("%g %s", f.limits.effort, unit) : std::string("none");
        text += text::format("actuator %d (%s): peak |tau| %.4g %s (effort %s)\n", a + 1,
                             io::terminalText(model.limb[static_cast<std::size_t>(j)].name).c_str(),
                             r.peak_tau[static_cast<std::size_t>(a)], unit, effort.c_str());
    }
    text += text::format("saturated ticks: %zu of %zu\n", r.saturated_ticks, r.t.size());
    return text;
}

}  // namespace

ControlResult runSpatialControl(const ControlOptions& options, Observer& observer) {
    validate(options);
    refusePlanarOnly(options);
    const spatial::Model model(io::loadSpatialRobotDescription(options.robot.path, options.robot.set));
    const int d = model.task_dimension, n = model.actuators;
    const spatial::Trajectory trajectory = spatialTrajectoryOf(options, d);
    spatial::LoopOptions loop;
    loop.rate = options.rate;
    loop.duration = options.duration ? *options.duration : trajectory.duration.value_or(0.2);
    if (!(loop.duration <= kSimulatedDurationRange.hi) || !(loop.duration * loop.rate <= kMaxSimulatedSamples)) {
        throw Error(io::terminalText(options.trajectory) + ": " + std::to_string(loop.duration) + " s at " +
                    std::to_string(loop.rate) + " Hz: control takes at most 1000 s and 1e7 ticks (give --duration)");
    }
    if (trajectory.highestFrequency() > 0.0 && !(loop.rate > 2.0 * trajectory.highestFrequency())) {
        throw OptionError("rate", text::format("%g Hz is not above twice the trajectory's highest frequency (%g Hz)",
                                               loop.rate, trajectory.highestFrequency()));
    }
    static_cast<FeedbackSettings&>(loop) = options;
    loop.saturation = !options.no_saturation;
    static_cast<PoseSensorNoise&>(loop) = poseSensorNoise(options.noise_pose, options.noise_rate, options.seed);
    Meter meter(observer, loop.duration, "s");
    loop.progress = [&meter](double t) { meter(t); };
    const spatial::LoopResult r = spatial::runPoseLoop(model, trajectory, loop);
    meter.report(loop.duration);
    ControlResult out;
    out.trajectory = trajectory.name;
    const std::vector<std::string> names = model.coordinates();
    io::Table& table = out.table;
    table.columns.emplace_back("t");
    for (const std::string& c : names) {
        std::string desired = c;  // appended, not `c + "_d"` (a GCC 12 -Wrestrict false positive)
        desired += "_d";
        table.columns.push_back(std::move(desired));
    }
    for (const std::string& c : names) table.columns.push_back(c);
    for (const char* prefix : {"u", "tau"}) {
        for (int a = 1; a <= n; ++a) {
            std::string name(prefix);
            name += std::to_string(a);
            table.columns.push_back(std::move(name));
        }
    }
    table.rows.reserve(r.t.size());
    for (std::size_t k = 0; k < r.t.size(); ++k) {
        std::vector<double> row{r.t[k]};
        row.reserve(table.columns.size());
        for (int i = 0; i < d; ++i) row.push_back(r.p_d[k](i));
        for (int i = 0; i < d; ++i) row.push_back(r.p[k](i));
        for (int a = 0; a < n; ++a) row.push_back(r.u[k](a));
        for (int a = 0; a < n; ++a) row.push_back(r.tau[k](a));
        table.rows.push_back(std::move(row));
    }
    out.text = report(options, model, r, loop, trajectory.name);
    return out;
}

}  // namespace nocdyn::app
