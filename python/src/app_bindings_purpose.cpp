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
    OptionsClass<O>(m, "ShakeOptions")
        .field("robot", &O::robot)
        .field("out_dir", &O::out_dir)
        .option("record", &O::record)
        .option("record_y", &O::record_y)
        .option("record_theta", &O::record_theta)
        .option("time_scale", &O::time_scale_text)
        .option("highpass", &O::highpass)
        .option("margin", &O::margin)
        .option("window", &O::window)
        .option("plant", &O::plant)
        .option("rate", &O::rate)
        .option("controller", &O::controller)
        .option("natural_frequency", &O::natural_frequency)
        .option("acceleration_gain", &O::acceleration_gain)
        .option("encoder_noise", &O::encoder_noise)
        .option("accel_noise_density", &O::accel_noise_density)
        .option("accel_bandwidth", &O::accel_bandwidth)
        .option("accel_baseline", &O::accel_baseline)
        .option("no_accelerometer", &O::no_accelerometer)
        .option("amplitude", &O::amplitude)
        .option("identify_payload", &O::identify_payload)
        .option("iterations", &O::iterations)
        .option("iteration_gain", &O::iteration_gain)
        .option("drive_model", &O::drive_model)
        .option("drive_specimen", &O::drive_specimen)
        .option("excitation_duration", &O::excitation_duration)
        .option("jobs", &O::jobs)
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
            const app::ShakeResult r =
                runJob(progress, [&](app::Observer& observer) { return app::runShake(options, observer); });
            return py::make_tuple(r.table.columns, rowsArray(r.table), r.metrics_json, r.text);
        },
        py::arg("options"), py::arg("progress") = py::none());
}

void bindIdentify(py::module_& m) {
    using O = app::IdentifyOptions;
    OptionsClass<O>(m, "IdentifyOptions")
        .field("robot", &O::robot)
        .field("output", &O::output)
        .field("figure", &O::figure)
        .option("data", &O::data)
        .option("payload", &O::payload)
        .option("base", &O::base)
        .option("friction", &O::friction)
        .option("held_forces", &O::held_forces)
        .option("cutoff", &O::cutoff)
        .option("holdout", &O::holdout)
        .option("calibration", &O::calibration)
        .option("prior", &O::prior);
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
    OptionsClass<O>(m, "ExciteOptions")
        .field("robot", &O::robot)
        .field("output", &O::output)
        .option("payload_guess", &O::payload_guess)
        .option("base", &O::base)
        .option("friction", &O::friction)
        .option("duration", &O::duration)
        .option("frequency", &O::frequency)
        .option("harmonics", &O::harmonics)
        .option("margin", &O::margin)
        .option("max_condition", &O::max_condition)
        .option("evaluations", &O::evaluations)
        .option("random", &O::random)
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
        .field("output", &O::output)
        .field("png", &O::png)
        .field("svg", &O::svg)
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
