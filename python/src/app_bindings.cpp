#include "app_bindings.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "app/design.hpp"
#include "app/inverse_dynamics.hpp"
#include "app/pose_spatial.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"
#include "app/observer.hpp"
#include "app/options.hpp"
#include "app/outputs.hpp"
#include "app/pose.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/output.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/robot_yaml.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::python {

/// A (rows, columns) float64 array owning the collector's values (no copy).
py::array_t<double> tableArray(app::TableCollector& table) {
    auto* values = new std::vector<double>(std::move(table.values()));
    const py::capsule owner(values, [](void* p) { delete static_cast<std::vector<double>*>(p); });
    const auto columns = static_cast<py::ssize_t>(table.names().size());
    const py::ssize_t rows = columns == 0 ? 0 : static_cast<py::ssize_t>(values->size()) / columns;
    return py::array_t<double>(
        {rows, columns}, {columns * static_cast<py::ssize_t>(sizeof(double)), static_cast<py::ssize_t>(sizeof(double))},
        values->data(), owner);
}

/// An io::Table's rows as a (rows, columns) float64 array.
py::array_t<double> rowsArray(const io::Table& table) {
    const auto columns = static_cast<py::ssize_t>(table.columns.size());
    py::array_t<double> out({static_cast<py::ssize_t>(table.rows.size()), columns});
    auto view = out.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < view.shape(0); ++i) {
        for (py::ssize_t j = 0; j < columns; ++j)
            view(i, j) = table.rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
    }
    return out;
}

namespace {

/// The least one sample of the inverse dynamics takes: t, x, y, theta, their rates and
/// accelerations, kinetic and u, du, ddu, tau of three actuators, float64 each.
constexpr double kHeldBytesPerSample = 8.0 * (11 + 4 * 3);

py::dict poseDict(const app::PoseResult& r) {
    const auto limbs = static_cast<py::ssize_t>(r.limbs.size());
    const auto n = static_cast<py::ssize_t>(r.actuators.size());
    py::array_t<double> q({limbs, py::ssize_t{3}}), cond_J(limbs), u(n), range_used(n);
    py::array_t<double> reactions({limbs, py::ssize_t{3}, py::ssize_t{3}});
    py::list actuators;
    for (py::ssize_t j = 0; j < limbs; ++j) {
        const app::PoseLimb& l = r.limbs[static_cast<std::size_t>(j)];
        for (py::ssize_t k = 0; k < 3; ++k) q.mutable_at(j, k) = l.q(k);
        cond_J.mutable_at(j) = l.cond_J;
    }
    for (py::ssize_t a = 0; a < n; ++a) {
        const app::PoseActuator& x = r.actuators[static_cast<std::size_t>(a)];
        u.mutable_at(a) = x.u;
        range_used.mutable_at(a) = x.range_used;
        actuators.append(py::dict(py::arg("actuator") = x.actuator, py::arg("limb") = x.limb,
                                  py::arg("joint") = x.joint, py::arg("u") = x.u,
                                  py::arg("range_used") = x.range_used));
    }
    for (const app::PoseReaction& j : r.reactions) {
        for (py::ssize_t c = 0; c < 3; ++c) reactions.mutable_at(j.limb - 1, j.joint - 1, c) = j.f(c);
    }
    // pose: x, y, theta; a two-DOF robot's x, y (its tool point)
    const Eigen::VectorXd pose = r.pose.head(r.task_dimension);
    py::dict out(py::arg("robot") = r.robot, py::arg("pose") = pose, py::arg("q") = q, py::arg("cond_J") = cond_J,
                 py::arg("u") = u, py::arg("range_used") = range_used, py::arg("A") = r.A, py::arg("cond_A") = r.cond_A,
                 py::arg("coordinates") = r.coordinates, py::arg("I") = r.I, py::arg("within_limits") = r.within_limits,
                 py::arg("tau") = r.tau, py::arg("reactions") = reactions, py::arg("actuators") = actuators);
    if (r.compliance) {
        const app::PoseCompliance& c = *r.compliance;
        // n_t x n_t: a two-DOF robot's over x, y
        out["stiffness"] = c.K;
        out["natural_frequencies"] = c.frequencies;
        out["mode_shapes"] = c.mode_shapes;
        if (c.elastodynamic_frequencies) out["elastodynamic_frequencies"] = *c.elastodynamic_frequencies;
        out["first_frequency"] = c.first_frequency;
        out["first_frequency_model"] = std::string(nameOf(c.first_frequency_model));
    }
    return out;
}

}  // namespace

void bindApplication(py::module_& m) {
    m.def(
        "_refuse_output_over_input",
        [](const std::string& command, const std::vector<std::tuple<std::string, std::string, std::string>>& paths) {
            app::CommandPaths gathered;
            for (const auto& [role, name, path] : paths) {
                if (role == "input")
                    gathered.input(name, path);
                else if (role == "output")
                    gathered.output(name, path);
                else if (role == "folder")
                    gathered.outputFolder(name, path);
                else
                    throw Error("_refuse_output_over_input: unknown role '" + role + "'");
            }
            app::refuseOutputOverInput(command, gathered);
        },
        py::arg("command"), py::arg("paths"),
        "Raises ValueError when an output of a call (role 'output', or 'folder' for an output folder) would "
        "replace one of its inputs (role 'input') or another of its outputs");
    py::class_<app::RobotSource>(m, "RobotSource", "The robot of a command: a file and its overrides, or a robot")
        .def(py::init<>())
        .def_readwrite("path", &app::RobotSource::path)
        .def_property(
            "set",
            [](const app::RobotSource& s) {
                py::dict out;
                for (const io::Parameter& p : s.set) out[py::str(p.name)] = p.value;
                return out;
            },
            [](app::RobotSource& s, const py::dict& values) {
                s.set.clear();
                for (const auto& [name, value] : values) {
                    app::addOverride(s.set, io::Parameter{py::str(name), value.cast<double>()});
                }
            })
        .def(
            "use_yaml",
            [](app::RobotSource& s, const std::string& text, const std::string& source) {
                s.description = io::parseRobotDescription(text, source);
            },
            py::arg("text"), py::arg("source"), "The robot of this YAML text instead of a file");

    m.def(
        "_write_table",
        [](const std::string& path, const std::vector<std::string>& columns,
           const py::array_t<double, py::array::c_style | py::array::forcecast>& data) {
            if (data.ndim() != 2 || data.shape(1) != static_cast<py::ssize_t>(columns.size())) {
                throw Error("output: expected a (rows, " + std::to_string(columns.size()) + ") table");
            }
            io::Table table{columns, {}};
            for (py::ssize_t i = 0; i < data.shape(0); ++i) {
                table.rows.emplace_back(data.data(i, 0), data.data(i, 0) + data.shape(1));
            }
            const py::gil_scoped_release release;
            io::OutputFile out(path);
            io::writeCsv(out, table);
            out.commit();
        },
        py::arg("path"), py::arg("columns"), py::arg("data"),
        "Writes a table as the command line's CSV (a unique temporary file, then renamed).");

    m.def(
        "_write_text",
        [](const std::string& path, const std::string& text) {
            const py::gil_scoped_release release;
            io::writeTextFile(path, text);
        },
        py::arg("path"), py::arg("text"), "Writes text to a file (a unique temporary file, then renamed).");

    // the ranges the jobs accept (app/*.hpp), for what Python checks before a job runs
    m.def("_ranges", [] {
        py::dict out;
        const auto add = [&](const char* name, const app::Range& r) { out[name] = py::make_tuple(r.lo, r.hi, r.unit); };
        add("rate", app::kRateRange);
        add("duration", app::kDurationRange);
        add("design_theta", app::kDesignThetaRange);
        add("design_resolution", app::kDesignResolutionRange);
        add("design_threads", app::kDesignThreadsRange);
        return out;
    });
    py::class_<app::SamplingOptions>(m, "SamplingOptions")
        .def(py::init<>())
        .def_readwrite("trajectory", &app::SamplingOptions::trajectory)
        .def_readwrite("duration", &app::SamplingOptions::duration)
        .def_readwrite("rate", &app::SamplingOptions::rate)
        .def(
            "use_trajectory", [](app::SamplingOptions& o, const PoseTrajectory& t) { o.given_trajectory = t; },
            py::arg("trajectory"), "This trajectory (a nocdyn.Trajectory's core) instead of a file");

    OptionsClass<app::PoseOptions>(m, "PoseOptions")
        .field("robot", &app::PoseOptions::robot)
        .option("x", &app::PoseOptions::x)
        .option("y", &app::PoseOptions::y)
        .option("theta", &app::PoseOptions::theta);
    m.def(
        "_run_pose",
        [](const app::PoseOptions& options, const py::object& progress) {
            const app::PoseResult result =
                runJob(progress, [&](app::Observer& observer) { return app::runPose(options, observer); });
            return poseDict(result);
        },
        py::arg("options"), py::arg("progress") = py::none());

    OptionsClass<app::InverseDynamicsOptions, app::SamplingOptions>(m, "InverseDynamicsOptions")
        .field("robot", &app::InverseDynamicsOptions::robot)
        .inherited("trajectory")
        .inherited("duration")
        .inherited("rate")
        .option("allow_limits", &app::InverseDynamicsOptions::allow_limits)
        .option("reactions", &app::InverseDynamicsOptions::reactions);
    m.def(
        "_run_inverse_dynamics",
        [](const app::InverseDynamicsOptions& options, const py::object& progress) {
            // every sample is held (the command line streams them to a file): what would take more
            // than kMaxHeldBytes is refused before any is computed
            app::validate(static_cast<const app::SamplingOptions&>(options));
            if (app::isSpatialRobot(options.robot)) {  // a spatial robot file (space: spatial)
                const spatial::Model model(io::loadSpatialRobotDescription(options.robot.path, options.robot.set));
                return runSpatialInverseDynamics(model, options, progress);
            }
            const double samples = static_cast<double>(
                sampleGrid(app::chooseDuration(options.duration, app::trajectoryOf(options)), options.rate).count);
            if (samples * kHeldBytesPerSample > kMaxHeldBytes) {
                throw Error(text::format(
                    "%.6g samples of at least %.0f bytes would hold %.3g GB in memory, more than "
                    "the %.0f MB allowed: give a shorter duration or a lower rate (the command "
                    "line's inverse-dynamics streams any number to a file)",
                    samples, kHeldBytesPerSample, samples * kHeldBytesPerSample / 1e9, kMaxHeldBytes / 1e6));
            }
            auto table = std::make_shared<app::TableCollector>();
            (void)runJob(progress,
                         [&](app::Observer& observer) { return app::runInverseDynamics(options, *table, observer); });
            return py::make_tuple(table->names(), tableArray(*table));
        },
        py::arg("options"), py::arg("progress") = py::none());
    bindPurpose(m);  // after SamplingOptions, a base of its options
    bindSimulation(m);
    bindReport(m);
    bindAnalysis(m);
}

}  // namespace nocdyn::python
