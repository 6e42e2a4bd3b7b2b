// forward-kinematics, simulate, control and frequency-response bound for the Python package:
// their options structs, _run_<command> functions (GIL released, an observer per call) and
// typed results as NumPy arrays and dicts.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>

#include "app/control.hpp"
#include "app/forward_kinematics.hpp"
#include "app/frequency_response.hpp"
#include "app/simulate.hpp"
#include "app_bindings.hpp"
#include "nocdyn/io/csv.hpp"
#include "report/plot.hpp"

namespace nocdyn::python {

namespace {

/// The assembly modes as forward-kinematics --json gives them (poses x, y, theta).
py::dict forwardKinematicsDict(const app::ForwardKinematicsResult& r) {
    py::list solutions;
    for (const app::ForwardKinematicsSolution& s : r.solutions) {
        solutions.append(py::dict(py::arg("pose") = py::dict(py::arg("x") = s.pose(0), py::arg("y") = s.pose(1),
                                                             py::arg("theta") = s.pose(2)),
                                  py::arg("working") = s.working, py::arg("branch") = s.branch,
                                  py::arg("u_error") = s.u_error, py::arg("condition") = s.condition));
    }
    return py::dict(py::arg("robot") = r.robot, py::arg("u") = r.u, py::arg("within_limits") = r.outside == 0,
                    py::arg("solutions_all_branches") = r.solutions_all_branches,
                    py::arg("solutions_working_branches") = r.solutions_working_branches,
                    py::arg("degenerate") = r.degenerate, py::arg("solutions") = solutions);
}

}  // namespace

void bindSimulation(py::module_& m) {
    py::class_<app::ForwardKinematicsOptions>(m, "ForwardKinematicsOptions")
        .def(py::init<>())
        .def_readwrite("u", &app::ForwardKinematicsOptions::u)
        .def_readwrite("robot", &app::ForwardKinematicsOptions::robot)
        .def_readwrite("all_branches", &app::ForwardKinematicsOptions::all_branches)
        .def_property_readonly_static("_fields", [](const py::object&) { return py::make_tuple("u", "all_branches"); });
    m.def(
        "_run_forward_kinematics",
        [](const app::ForwardKinematicsOptions& options, const py::object& progress) {
            return forwardKinematicsDict(runJob(
                progress, [&](app::Observer& observer) { return app::runForwardKinematics(options, observer); }));
        },
        py::arg("options"), py::arg("progress") = py::none());

    py::class_<app::SimulateOptions>(m, "SimulateOptions")
        .def(py::init<>())
        .def_readwrite("forces", &app::SimulateOptions::forces)
        .def_readwrite("robot", &app::SimulateOptions::robot)
        .def_readwrite("interpolation", &app::SimulateOptions::interpolation)
        .def_readwrite("duration", &app::SimulateOptions::duration)
        .def_readwrite("rate", &app::SimulateOptions::rate)
        .def_readwrite("atol", &app::SimulateOptions::atol)
        .def_readwrite("rtol", &app::SimulateOptions::rtol)
        .def_readwrite("assembly_mode", &app::SimulateOptions::assembly_mode)
        .def_readwrite("partial", &app::SimulateOptions::partial)
        .def_readwrite("reactions", &app::SimulateOptions::reactions)
        .def(
            "use_forces",
            [](app::SimulateOptions& o, const std::vector<std::string>& columns,
               const py::array_t<double, py::array::c_style | py::array::forcecast>& data) {
                if (data.ndim() != 2 || data.shape(1) != static_cast<py::ssize_t>(columns.size())) {
                    throw app::OptionError(
                        "forces", "expected a (rows, " + std::to_string(columns.size()) + ") table of numbers");
                }
                if (data.shape(0) == 0) throw app::OptionError("forces", "no rows");
                io::Table table{columns, {}};
                for (py::ssize_t i = 0; i < data.shape(0); ++i) {
                    table.rows.emplace_back(data.data(i, 0), data.data(i, 0) + data.shape(1));
                }
                o.forces_table = std::move(table);
            },
            py::arg("columns"), py::arg("data"), "The forces of this table (columns t, tau1..taun) instead of a file")
        .def_property_readonly_static("_fields", [](const py::object&) {
            return py::make_tuple("forces", "interpolation", "duration", "rate", "atol", "rtol", "assembly_mode",
                                  "partial", "reactions");
        });
    m.def(
        "_run_simulate",
        [](const app::SimulateOptions& options, const py::object& progress) {
            auto table = std::make_shared<app::TableCollector>();
            const app::SimulateResult result =
                runJob(progress, [&](app::Observer& observer) { return app::runSimulate(options, *table, observer); });
            return py::make_tuple(table->names(), tableArray(*table), app::summaryLine(result), result.stopped);
        },
        py::arg("options"), py::arg("progress") = py::none());

    py::class_<app::FrequencyResponseOptions>(m, "FrequencyResponseOptions")
        .def(py::init<>())
        .def_readwrite("robot", &app::FrequencyResponseOptions::robot)
        .def_readwrite("pose", &app::FrequencyResponseOptions::pose)
        .def_readwrite("rate", &app::FrequencyResponseOptions::rate)
        .def_readwrite("output_kind", &app::FrequencyResponseOptions::output_kind)
        .def_readwrite("compliance", &app::FrequencyResponseOptions::compliance)
        .def_readwrite("f_min", &app::FrequencyResponseOptions::f_min)
        .def_readwrite("f_max", &app::FrequencyResponseOptions::f_max)
        .def_readwrite("points", &app::FrequencyResponseOptions::points)
        .def_readwrite("closed_loop", &app::FrequencyResponseOptions::closed_loop)
        .def_readwrite("payload", &app::FrequencyResponseOptions::payload)
        .def_readwrite("controller_rate", &app::FrequencyResponseOptions::controller_rate)
        .def_readwrite("natural_frequency", &app::FrequencyResponseOptions::natural_frequency)
        .def_property_readonly_static("_fields", [](const py::object&) {
            return py::make_tuple("pose", "rate", "output_kind", "compliance", "f_min", "f_max", "points",
                                  "closed_loop", "payload", "controller_rate", "natural_frequency");
        });
    m.def(
        "_run_frequency_response",
        [](const app::FrequencyResponseOptions& options, const std::string& summary, const std::string& figure) {
            const app::FrequencyResponseResult result = runJob(py::none(), [&](app::Observer& observer) {
                app::FrequencyResponseResult r = app::runFrequencyResponse(options, observer);
                // the files asked for, written safely (a unique temporary file renamed into place)
                if (!summary.empty()) io::writeTextFile(summary, r.summary);
                if (!figure.empty()) report::renderFigure(app::bodeFigure(r), figure);
                return r;
            });
            return py::make_tuple(result.columns, Eigen::MatrixXd(result.table), result.summary);
        },
        py::arg("options"), py::arg("summary") = std::string(), py::arg("figure") = std::string());

    py::class_<app::ControlOptions, app::SamplingOptions>(m, "ControlOptions")
        .def(py::init<>())
        .def_readwrite("robot", &app::ControlOptions::robot)
        .def_readwrite("controller", &app::ControlOptions::controller)
        .def_readwrite("plant", &app::ControlOptions::plant)
        .def_readwrite("natural_frequency", &app::ControlOptions::natural_frequency)
        .def_readwrite("payload_mass", &app::ControlOptions::payload_mass)
        .def_readwrite("payload_inertia", &app::ControlOptions::payload_inertia)
        .def_readwrite("payload_com", &app::ControlOptions::payload_com)
        .def_readwrite("noise_pose", &app::ControlOptions::noise_pose)
        .def_readwrite("noise_rate", &app::ControlOptions::noise_rate)
        .def_readwrite("noise_tau", &app::ControlOptions::noise_tau)
        .def_readwrite("measure", &app::ControlOptions::measure)
        .def_readwrite("noise_u", &app::ControlOptions::noise_u)
        .def_readwrite("noise_du", &app::ControlOptions::noise_du)
        .def_readwrite("seed", &app::ControlOptions::seed)
        .def_readwrite("no_saturation", &app::ControlOptions::no_saturation)
        .def_readwrite("sensor_log", &app::ControlOptions::sensor_log)
        .def_property_readonly_static("_fields", [](const py::object&) {
            return py::make_tuple("trajectory", "controller", "plant", "rate", "duration", "natural_frequency",
                                  "payload_mass", "payload_inertia", "payload_com", "noise_pose", "noise_rate",
                                  "noise_tau", "measure", "noise_u", "noise_du", "seed", "no_saturation");
        });
    m.def(
        "_run_control",
        [](app::ControlOptions options, const std::string& log, const std::string& figure, const py::object& progress) {
            options.sensor_log = !log.empty();
            const app::ControlResult result = runJob(progress, [&](app::Observer& observer) {
                app::ControlResult r = app::runControl(options, observer);
                // the files asked for, written safely (a unique temporary file renamed into place)
                if (!log.empty()) io::writeCsvFile(log, r.log);
                if (!figure.empty()) report::renderFigure(app::trackingFigure(r), figure);
                return r;
            });
            const auto rows = static_cast<py::ssize_t>(result.table.rows.size());
            const auto columns = static_cast<py::ssize_t>(result.table.columns.size());
            py::array_t<double> data({rows, columns});
            for (py::ssize_t i = 0; i < rows; ++i) {
                for (py::ssize_t k = 0; k < columns; ++k) {
                    data.mutable_at(i, k) = result.table.rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
                }
            }
            return py::make_tuple(result.table.columns, data, result.text);
        },
        py::arg("options"), py::arg("log") = std::string(), py::arg("figure") = std::string(),
        py::arg("progress") = py::none());
}

}  // namespace nocdyn::python
