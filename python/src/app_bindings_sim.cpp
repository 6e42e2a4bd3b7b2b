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
#include "render/plot.hpp"

namespace nocdyn::python {

namespace {

/// The assembly modes as forward-kinematics --json gives them (poses x, y, theta; x, y for a
/// two-DOF robot).
py::dict forwardKinematicsDict(const app::ForwardKinematicsResult& r) {
    py::list solutions;
    for (const app::ForwardKinematicsSolution& s : r.solutions) {
        py::dict pose(py::arg("x") = s.pose(0), py::arg("y") = s.pose(1));
        if (r.task_dimension == 3) pose["theta"] = s.pose(2);
        solutions.append(py::dict(py::arg("pose") = pose, py::arg("working") = s.working, py::arg("branch") = s.branch,
                                  py::arg("u_error") = s.u_error, py::arg("condition") = s.condition));
    }
    return py::dict(py::arg("robot") = r.robot, py::arg("u") = r.u, py::arg("within_limits") = r.outside == 0,
                    py::arg("solutions_all_branches") = r.solutions_all_branches,
                    py::arg("solutions_working_branches") = r.solutions_working_branches,
                    py::arg("degenerate") = r.degenerate, py::arg("solutions") = solutions);
}

}  // namespace

void bindSimulation(py::module_& m) {
    OptionsClass<app::ForwardKinematicsOptions>(m, "ForwardKinematicsOptions")
        .field("robot", &app::ForwardKinematicsOptions::robot)
        .option("u", &app::ForwardKinematicsOptions::u)
        .option("all_branches", &app::ForwardKinematicsOptions::all_branches);
    m.def(
        "_run_forward_kinematics",
        [](const app::ForwardKinematicsOptions& options, const py::object& progress) {
            return forwardKinematicsDict(runJob(
                progress, [&](app::Observer& observer) { return app::runForwardKinematics(options, observer); }));
        },
        py::arg("options"), py::arg("progress") = py::none());

    OptionsClass<app::SimulateOptions>(m, "SimulateOptions")
        .field("robot", &app::SimulateOptions::robot)
        .option("forces", &app::SimulateOptions::forces)
        .option("interpolation", &app::SimulateOptions::interpolation)
        .option("duration", &app::SimulateOptions::duration)
        .option("rate", &app::SimulateOptions::rate)
        .option("atol", &app::SimulateOptions::atol)
        .option("rtol", &app::SimulateOptions::rtol)
        .option("max_step", &app::SimulateOptions::max_step)
        .option("assembly_mode", &app::SimulateOptions::assembly_mode)
        .option("partial", &app::SimulateOptions::partial)
        .option("reactions", &app::SimulateOptions::reactions)
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
            py::arg("columns"), py::arg("data"), "The forces of this table (columns t, tau1..taun) instead of a file");
    m.def(
        "_run_simulate",
        [](const app::SimulateOptions& options, const py::object& progress) {
            auto table = std::make_shared<app::TableCollector>();
            const app::SimulateResult result =
                runJob(progress, [&](app::Observer& observer) { return app::runSimulate(options, *table, observer); });
            return py::make_tuple(table->names(), tableArray(*table), app::summaryLine(result), result.stopped);
        },
        py::arg("options"), py::arg("progress") = py::none());

    OptionsClass<app::FrequencyResponseOptions>(m, "FrequencyResponseOptions")
        .field("robot", &app::FrequencyResponseOptions::robot)
        .option("pose", &app::FrequencyResponseOptions::pose)
        .option("rate", &app::FrequencyResponseOptions::rate)
        .option("output_kind", &app::FrequencyResponseOptions::output_kind)
        .option("compliance", &app::FrequencyResponseOptions::compliance)
        .option("min_frequency", &app::FrequencyResponseOptions::min_frequency)
        .option("max_frequency", &app::FrequencyResponseOptions::max_frequency)
        .option("points", &app::FrequencyResponseOptions::points)
        .option("closed_loop", &app::FrequencyResponseOptions::closed_loop)
        .option("payload_mass", &app::FrequencyResponseOptions::payload_mass)
        .option("controller_rate", &app::FrequencyResponseOptions::controller_rate)
        .option("natural_frequency", &app::FrequencyResponseOptions::natural_frequency)
        .option("amplification", &app::FrequencyResponseOptions::amplification);
    m.def(
        "_run_frequency_response",
        [](const app::FrequencyResponseOptions& options, const std::string& summary, const std::string& figure) {
            const app::FrequencyResponseResult result = runJob(py::none(), [&](app::Observer& observer) {
                app::FrequencyResponseResult r = app::runFrequencyResponse(options, observer);
                // the files asked for, written safely (a unique temporary file renamed into place)
                if (!summary.empty()) io::writeTextFile(summary, r.summary);
                if (!figure.empty()) render::renderFigure(app::bodeFigure(r), figure);
                return r;
            });
            return py::make_tuple(result.columns, Eigen::MatrixXd(result.table), result.summary);
        },
        py::arg("options"), py::arg("summary") = std::string(), py::arg("figure") = std::string());

    OptionsClass<app::ControlOptions, app::SamplingOptions>(m, "ControlOptions")
        .field("robot", &app::ControlOptions::robot)
        .field("sensor_log", &app::ControlOptions::sensor_log)
        .field("plant_given", &app::ControlOptions::plant_given)
        .inherited("trajectory")
        .option("controller", &app::ControlOptions::controller)
        .option("plant", &app::ControlOptions::plant)
        .inherited("rate")
        .inherited("duration")
        .option("natural_frequency", &app::ControlOptions::natural_frequency)
        .option("payload_mass", &app::ControlOptions::payload_mass)
        .option("payload_inertia", &app::ControlOptions::payload_inertia)
        .option("payload_com", &app::ControlOptions::payload_com)
        .option("noise_pose", &app::ControlOptions::noise_pose)
        .option("noise_rate", &app::ControlOptions::noise_rate)
        .option("noise_tau", &app::ControlOptions::noise_tau)
        .option("measure", &app::ControlOptions::measure)
        .option("noise_u", &app::ControlOptions::noise_u)
        .option("noise_du", &app::ControlOptions::noise_du)
        .option("seed", &app::ControlOptions::seed)
        .option("no_saturation", &app::ControlOptions::no_saturation);
    m.def(
        "_run_control",
        [](app::ControlOptions options, const std::string& log, const std::string& figure, const py::object& progress) {
            options.sensor_log = !log.empty();
            const app::ControlResult result = runJob(progress, [&](app::Observer& observer) {
                app::ControlResult r = app::runControl(options, observer);
                // the files asked for, written safely (a unique temporary file renamed into place)
                if (!log.empty()) io::writeCsvFile(log, r.log);
                if (!figure.empty()) render::renderFigure(app::trackingFigure(r), figure);
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
