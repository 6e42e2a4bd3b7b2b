// The commands that serve a purpose beyond one computation (an earthquake replay, an
// identification, an excitation, an animation, the paper's results, the engines' check) bound
// as their options structs and run functions (app/).
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "app/animate.hpp"
#include "app/excite.hpp"
#include "app/identify.hpp"
#include "app/shake.hpp"
#include "app_bindings.hpp"

namespace nocdyn::python {

namespace {

void bindShake(py::module_& m) {
    using O = app::ShakeOptions;
    py::class_<O>(m, "ShakeOptions")
        .def(py::init<>())
        .def_readwrite("robot", &O::robot)
        .def_readwrite("record", &O::record)
        .def_readwrite("record_y", &O::record_y)
        .def_readwrite("record_theta", &O::record_theta)
        .def_readwrite("time_scale", &O::time_scale)
        .def_readwrite("highpass", &O::highpass)
        .def_readwrite("margin", &O::margin)
        .def_readwrite("window", &O::window)
        .def_readwrite("plant", &O::plant)
        .def_readwrite("rate", &O::rate)
        .def_readwrite("controller", &O::controller)
        .def_readwrite("natural_frequency", &O::natural_frequency)
        .def_readwrite("acceleration_gain", &O::acceleration_gain)
        .def_readwrite("encoder_noise", &O::encoder_noise)
        .def_readwrite("accel_noise_density", &O::accel_noise_density)
        .def_readwrite("accel_bandwidth", &O::accel_bandwidth)
        .def_readwrite("accel_baseline", &O::accel_baseline)
        .def_readwrite("no_accelerometer", &O::no_accelerometer)
        .def_readwrite("amplitude", &O::amplitude)
        .def_readwrite("identify_payload", &O::identify_payload)
        .def_readwrite("iterations", &O::iterations)
        .def_readwrite("iteration_gain", &O::iteration_gain)
        .def_readwrite("drive_model", &O::drive_model)
        .def_readwrite("drive_specimen", &O::drive_specimen)
        .def_readwrite("excitation_duration", &O::excitation_duration)
        .def_readwrite("jobs", &O::jobs)
        .def_readwrite("max_rms_percent", &O::max_rms_percent)
        .def_readwrite("max_peak_percent", &O::max_peak_percent)
        .def_readwrite("min_spectrum_percent", &O::min_spectrum_percent)
        .def_readwrite("payload_mass", &O::payload_mass)
        .def_readwrite("noise_pose", &O::noise_pose)
        .def_readwrite("noise_rate", &O::noise_rate)
        .def_readwrite("seed", &O::seed)
        .def_readwrite("accuracy", &O::accuracy)
        .def_readwrite("out_dir", &O::out_dir)
        .def_property_readonly_static("_fields", [](const py::object&) {
            return py::make_tuple("record", "record_y", "record_theta", "time_scale", "highpass", "margin", "window",
                                  "plant", "rate", "controller", "natural_frequency", "acceleration_gain",
                                  "encoder_noise", "accel_noise_density", "accel_bandwidth", "accel_baseline",
                                  "no_accelerometer", "amplitude", "identify_payload", "iterations", "iteration_gain",
                                  "drive_model", "drive_specimen", "excitation_duration", "jobs", "max_rms_percent",
                                  "max_peak_percent", "min_spectrum_percent", "payload_mass", "noise_pose",
                                  "noise_rate", "seed", "accuracy");
        });
    m.def(
        "_run_shake",
        [](const O& options, const py::object& progress) {
            const app::ShakeResult r =
                runJob(progress, [&](app::Observer& observer) { return app::runShake(options, observer); });
            return py::make_tuple(r.table.columns, rowsArray(r.table), r.metrics_json, r.text);
        },
        py::arg("options"), py::arg("progress") = py::none());
}

void bindIdentify(py::module_& m) {
    using O = app::IdentifyOptions;
    py::class_<O>(m, "IdentifyOptions")
        .def(py::init<>())
        .def_readwrite("robot", &O::robot)
        .def_readwrite("data", &O::data)
        .def_readwrite("payload", &O::payload)
        .def_readwrite("base", &O::base)
        .def_readwrite("friction", &O::friction)
        .def_readwrite("held_forces", &O::held_forces)
        .def_readwrite("cutoff", &O::cutoff)
        .def_readwrite("holdout", &O::holdout)
        .def_readwrite("calibration", &O::calibration)
        .def_readwrite("prior", &O::prior)
        .def_readwrite("output", &O::output)
        .def_readwrite("figure", &O::figure)
        .def_property_readonly_static("_fields", [](const py::object&) {
            return py::make_tuple("data", "payload", "base", "friction", "held_forces", "cutoff", "holdout",
                                  "calibration", "prior");
        });
    m.def(
        "_run_identify",
        [](const O& options, const py::object& progress) {
            const app::IdentifyResult r =
                runJob(progress, [&](app::Observer& observer) { return app::runIdentify(options, observer); });
            return py::make_tuple(r.text, r.yaml);
        },
        py::arg("options"), py::arg("progress") = py::none());
}

void bindExcite(py::module_& m) {
    using O = app::ExciteOptions;
    py::class_<O>(m, "ExciteOptions")
        .def(py::init<>())
        .def_readwrite("robot", &O::robot)
        .def_readwrite("payload_guess", &O::payload_guess)
        .def_readwrite("base", &O::base)
        .def_readwrite("friction", &O::friction)
        .def_readwrite("duration", &O::duration)
        .def_readwrite("frequency", &O::frequency)
        .def_readwrite("harmonics", &O::harmonics)
        .def_readwrite("margin", &O::margin)
        .def_readwrite("max_condition", &O::max_condition)
        .def_readwrite("evaluations", &O::evaluations)
        .def_readwrite("random", &O::random)
        .def_readwrite("samples", &O::samples)
        .def_readwrite("check_samples", &O::check_samples)
        .def_readwrite("seed", &O::seed)
        .def_readwrite("optimizer", &O::optimizer)
        .def_readwrite("output", &O::output)
        .def_property_readonly_static("_fields", [](const py::object&) {
            return py::make_tuple("payload_guess", "base", "friction", "duration", "frequency", "harmonics", "margin",
                                  "max_condition", "evaluations", "random", "samples", "check_samples", "seed",
                                  "optimizer");
        });
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
    py::class_<O, app::SamplingOptions>(m, "AnimateOptions")
        .def(py::init<>())
        .def_readwrite("robot", &O::robot)
        .def_readwrite("motion", &O::motion)
        .def_readwrite("slow_motion", &O::slow_motion)
        .def_readwrite("magnify", &O::magnify)
        .def_readwrite("frame", &O::frame)
        .def_readwrite("output", &O::output)
        .def_readwrite("png", &O::png)
        .def_readwrite("svg", &O::svg)
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
            py::arg("columns"), py::arg("data"), py::arg("name"), "The motion as a table in memory")
        .def_property_readonly_static("_fields", [](const py::object&) {
            return py::make_tuple("trajectory", "motion", "duration", "rate", "slow_motion", "magnify", "frame");
        });
    m.def(
        "_run_animate",
        [](const O& options, const py::object& progress) {
            const app::AnimateResult r =
                runJob(progress, [&](app::Observer& observer) { return app::runAnimate(options, observer); });
            return r.html;
        },
        py::arg("options"), py::arg("progress") = py::none());
}

}  // namespace

void bindPurpose(py::module_& m) {
    bindShake(m);
    bindIdentify(m);
    bindExcite(m);
    bindAnimate(m);
}

}  // namespace nocdyn::python
