// The commands that serve a purpose beyond one computation (an earthquake replay, an
// identification, an excitation, an animation, the paper's results, the engines' check) bound
// as their options structs and run functions (app/).
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "app/animate.hpp"
#include "app/excite.hpp"
#include "app/identify.hpp"
#include "app/shake.hpp"
#include "app/shake_records.hpp"
#include "app_bindings.hpp"
#include "arrays.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/tables/calibration.hpp"
#include "render/plot.hpp"

namespace nocdyn::python {

namespace {

void bindShake(py::module_& m) {
    using O = app::ShakeOptions;
    OptionsClass<O>(m, "ShakeOptions")
        .field("robot", &O::robot)
        .field("out_dir", &O::out_dir)
        .option("record", &O::record)
        .option("axis", &O::axis)
        .option("record_y", &O::record_y)
        .option("record_theta", &O::record_theta)
        .option("time_scale", &O::time_scale_text)
        .option("highpass", &O::highpass)
        .option("margin", &O::margin)
        .option("window", &O::window)
        .option("x_azimuth", &O::x_azimuth)
        .option("per_axis_scale", &O::per_axis_scale)
        .option("plant", &O::plant)
        .option("rate", &O::rate)
        .option("controller", &O::controller)
        .option("natural_frequency", &O::natural_frequency)
        .option("acceleration_gain", &O::acceleration_gain)
        .option("noise_u", &O::noise_u)
        .option("accel_noise_density", &O::accel_noise_density)
        .option("accel_bandwidth", &O::accel_bandwidth)
        .option("accel_baseline", &O::accel_baseline)
        .option("no_accelerometer", &O::no_accelerometer)
        .option("amplitude", &O::amplitude)
        .option("identify_payload", &O::identify_payload)
        .option("iterations", &O::iterations)
        .option("iteration_gain", &O::iteration_gain)
        .option("iteration_tolerance", &O::iteration_tolerance)
        .option("drive_model", &O::drive_model)
        .option("drive_specimen", &O::drive_specimen)
        .option("excitation_duration", &O::excitation_duration)
        .option("threads", &O::threads)
        .option("max_rms_percent", &O::max_rms_percent)
        .option("max_peak_percent", &O::max_peak_percent)
        .option("min_spectrum_percent", &O::min_spectrum_percent)
        .option("payload_mass", &O::payload_mass)
        .option("noise_pose", &O::noise_pose)
        .option("noise_rate", &O::noise_rate)
        .option("seed", &O::seed)
        .option("accuracy", &O::accuracy);
    m.def(
        "_run_shake",
        [](const O& options, const py::object& progress) {
            app::OutputFolder files(options.out_dir);
            const app::ShakeResult r =
                runJob(progress, [&](app::Observer& observer) { return app::runShake(options, observer, files); });
            return py::make_tuple(r.table.columns, rowsArray(r.table), r.metrics_json, r.text);
        },
        py::arg("options"), py::arg("progress") = py::none());
    // the records a list of AT2 files makes (component files of one record grouped), as shake reads them
    m.def(
        "_record_groups",
        [](const std::vector<std::string>& files) {
            py::list out;
            for (const app::RecordFiles& r : app::groupRecordFiles(files)) out.append(py::make_tuple(r.label, r.files));
            return out;
        },
        py::arg("files"));
}

/// The fit of measured against predicted forces on the held-out samples, as numbers.
py::dict fitDict(const FitReport& fit) {
    py::dict out;
    out["fit_samples"] = fit.fit_samples;
    out["holdout_samples"] = fit.holdout_samples;
    out["rms_fit"] = toArray(fit.rms_fit);
    out["rms_holdout"] = toArray(fit.rms_holdout);
    out["rms_measured"] = toArray(fit.rms_measured);
    out["condition"] = fit.condition;
    out["correlation_samples"] = fit.correlation_samples;
    out["effective_samples"] = fit.effective_samples;
    out["t"] = toArray(fit.t);
    out["measured"] = toArray(fit.measured);
    out["predicted"] = toArray(fit.predicted);
    return out;
}

py::list estimatesList(const std::vector<Estimate>& estimates, bool with_prior) {
    py::list out;
    for (const Estimate& e : estimates) {
        py::dict d;
        d["name"] = e.name;
        d["value"] = e.value;
        d["stddev"] = e.stddev;
        if (with_prior) d["robot_file"] = e.prior;
        d["unit"] = e.unit;
        out.append(d);
    }
    return out;
}

/// The identified payload as numbers: mass [kg], com (2,) [m], inertia [kg m^2], their standard
/// deviations, the covariance of [mass, com_x, com_y, inertia, friction...], the bounds it lies
/// on, the friction identified alongside and the fit.
py::dict payloadDict(const PayloadResult& r) {
    py::dict out;
    out["mass"] = r.mass;
    out["com"] = toArray(std::vector<double>{r.com.x(), r.com.y()});
    out["inertia"] = r.inertia;
    out["mass_sd"] = r.mass_sd;
    out["com_sd"] = toArray(std::vector<double>{r.com_sd.x(), r.com_sd.y()});
    out["inertia_sd"] = r.inertia_sd;
    out["covariance"] = toArray(r.covariance);
    out["inertia_constrained"] = r.inertia_constrained;
    py::list active;
    for (const ActiveBound& b : r.active_bounds) {
        py::dict d;
        d["parameter"] = b.parameter;
        d["side"] = b.upper ? "upper" : "lower";
        d["bound"] = b.bound;
        d["unbounded"] = b.unbounded;
        active.append(d);
    }
    out["active_bounds"] = active;
    out["friction"] = estimatesList(r.friction, false);
    out["fit"] = fitDict(r.fit);
    return out;
}

/// The identified base parameters as numbers: each with its standard deviation and the robot
/// file's value, their covariance and the fit.
py::dict baseDict(const BaseResult& r) {
    py::dict out;
    out["base_parameters"] = estimatesList(r.beta, true);
    out["covariance"] = toArray(r.covariance);
    out["fit"] = fitDict(r.fit);
    return out;
}

void bindIdentify(py::module_& m) {
    using O = app::IdentifyOptions;
    OptionsClass<O>(m, "IdentifyOptions")
        .field("robot", &O::robot)
        .option("data", &O::data)
        .option("payload", &O::payload)
        .option("base", &O::base)
        .option("friction", &O::friction)
        .option("held_forces", &O::held_forces)
        .option("cutoff", &O::cutoff)
        .option("holdout", &O::holdout)
        .option("calibration", &O::calibration)
        .option("prior", &O::prior)
        .def(
            "use_data",
            [](O& o, const std::vector<std::string>& columns,
               const py::array_t<double, py::array::c_style | py::array::forcecast>& data) {
                if (data.ndim() != 2 || data.shape(1) != static_cast<py::ssize_t>(columns.size())) {
                    throw app::OptionError(
                        "data", "expected a (rows, " + std::to_string(columns.size()) + ") table of numbers");
                }
                io::Table table{columns, {}};
                for (py::ssize_t i = 0; i < data.shape(0); ++i)
                    table.rows.emplace_back(data.data(i, 0), data.data(i, 0) + data.shape(1));
                o.data_table = std::move(table);
                if (o.data.empty()) o.data = "data";
            },
            py::arg("columns"), py::arg("data"),
            "The log of this table (columns t, u1..un, tau1..taun) instead of a file")
        .def(
            "use_prior",
            [](O& o, const std::array<std::array<double, 2>, 4>& bounds) {
                PayloadPrior prior;
                Bounds* each[4] = {&prior.mass, &prior.com_x, &prior.com_y, &prior.inertia};
                for (std::size_t i = 0; i < 4; ++i) *each[i] = Bounds{bounds[i][0], bounds[i][1]};
                o.prior_bounds = prior;
            },
            py::arg("bounds"), "Bounds (lower, upper) on mass, com_x, com_y, inertia instead of a prior file");
    m.def(
        "_load_prior",
        [](const std::string& path) {
            // a prior file's bounds as (lower, upper) pairs, None for an open side
            const PayloadPrior prior = tables::loadPayloadPrior(path);
            py::dict out;
            const auto side = [](double v) -> py::object {
                return std::isfinite(v) ? py::object(py::float_(v)) : py::none();
            };
            const std::pair<const char*, const Bounds*> items[] = {
                {"mass", &prior.mass}, {"com_x", &prior.com_x}, {"com_y", &prior.com_y}, {"inertia", &prior.inertia}};
            for (const auto& [name, b] : items) {
                if (std::isfinite(b->lower) || std::isfinite(b->upper))
                    out[name] = py::make_tuple(side(b->lower), side(b->upper));
            }
            return out;
        },
        py::arg("path"));
    m.def(
        "_run_identify",
        [](const O& options, const py::object& progress, const std::string& figure) {
            const app::IdentifyResult r =
                runJob(progress, [&](app::Observer& observer) { return app::runIdentify(options, observer); });
            if (!figure.empty()) {
                const py::gil_scoped_release release;
                render::renderFigure(r.figure, figure);
            }
            return py::make_tuple(r.text, r.yaml, r.payload ? py::object(payloadDict(*r.payload)) : py::none(),
                                  r.base ? py::object(baseDict(*r.base)) : py::none());
        },
        py::arg("options"), py::arg("progress") = py::none(), py::arg("figure") = std::string());
}

void bindExcite(py::module_& m) {
    using O = app::ExciteOptions;
    OptionsClass<O>(m, "ExciteOptions")
        .field("robot", &O::robot)
        .option("payload_guess", &O::payload_guess)
        .property(
            "base", [](const O& o) { return o.parameters == ExcitedParameters::base; },
            [](O& o, bool base) { o.parameters = base ? ExcitedParameters::base : ExcitedParameters::payload; })
        .option("friction", &O::friction)
        .option("duration", &O::duration)
        .option("base_frequency", &O::base_frequency)
        .option("harmonics", &O::harmonics)
        .option("margin", &O::margin)
        .option("max_condition", &O::max_condition)
        .option("evaluations", &O::evaluations)
        .option("random_shapes", &O::random_shapes)
        .option("samples", &O::samples)
        .option("check_samples", &O::check_samples)
        .option("seed", &O::seed)
        .option("optimizer", &O::optimizer);
    m.def(
        "_run_excite",
        [](const O& options, const py::object& progress) {
            const app::ExciteResult r =
                runJob(progress, [&](app::Observer& observer) { return app::runExcite(options, observer); });
            return py::make_tuple(r.text, r.yaml);
        },
        py::arg("options"), py::arg("progress") = py::none());
}

void bindAnimate(py::module_& m) {
    using O = app::AnimateOptions;
    OptionsClass<O, app::SamplingOptions>(m, "AnimateOptions")
        .field("robot", &O::robot)
        .inherited("trajectory")
        .option("motion", &O::motion)
        .inherited("duration")
        .inherited("rate")
        .option("slow_motion", &O::slow_motion)
        .option("magnify", &O::magnify)
        .option("frame", &O::frame)
        .def(
            "use_motion_table",
            [](O& o, const std::vector<std::string>& columns,
               const py::array_t<double, py::array::c_style | py::array::forcecast>& data, const std::string& name) {
                if (data.ndim() != 2 || data.shape(1) != static_cast<py::ssize_t>(columns.size())) {
                    throw app::OptionError("motion", "expected a (rows, " + std::to_string(columns.size()) + ") table");
                }
                io::Table table{columns, {}};
                for (py::ssize_t i = 0; i < data.shape(0); ++i) {
                    table.rows.emplace_back(data.data(i, 0), data.data(i, 0) + data.shape(1));
                }
                o.motion_table = std::move(table);
                o.motion_name = name;
            },
            py::arg("columns"), py::arg("data"), py::arg("name"), "The motion as a table in memory");
    m.def(
        "_run_animate",
        [](const O& options, const py::object& progress, const std::string& png, const std::string& svg) {
            const app::AnimateResult r =
                runJob(progress, [&](app::Observer& observer) { return app::runAnimate(options, observer); });
            if (r.frame) {
                const py::gil_scoped_release release;
                render::renderFigureFiles(*r.frame, png, svg);
            }
            return r.html;
        },
        py::arg("options"), py::arg("progress") = py::none(), py::arg("png") = std::string(),
        py::arg("svg") = std::string());
}

}  // namespace

void bindPurpose(py::module_& m) {
    bindShake(m);
    bindIdentify(m);
    bindExcite(m);
    bindAnimate(m);
}

}  // namespace nocdyn::python
