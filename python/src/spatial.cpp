// The spatial robots of the compiled module (nocdyn/spatial.hpp): a model read from a spatial
// robot file (`space: spatial`) and its inverse dynamics over arrays of samples.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "app/inverse_dynamics_spatial.hpp"
#include "app/pose_spatial.hpp"
#include "app_bindings.hpp"
#include "arrays.hpp"
#include "expose.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/analysis/assembly_modes.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/spatial.hpp"
#include "nocdyn/spatial_batch.hpp"
#include "nocdyn/spatial_limits.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/spatial_direct_kinematics.hpp"

namespace nocdyn::python {

namespace {

struct SpatialRobot {
    std::shared_ptr<const spatial::Model> model;
    std::shared_ptr<const SpatialRobotDescription> description;
    std::string source;  ///< the file's path or "<string>", for errors
};

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// (N, d) samples of p, dp, ddp (d the task dimension) as C-ordered float64 arrays.
Rows samples(const py::handle& x, const char* name, int d, py::ssize_t n) {
    Rows a = Rows::ensure(x);
    if (!a || a.ndim() != 2 || a.shape(1) != d || (n >= 0 && a.shape(0) != n)) {
        throw Error(std::string(name) + ": expected shape (N, " + std::to_string(d) + ")" +
                    (n >= 0 ? " with N = " + std::to_string(n) : std::string()));
    }
    return a;
}

/// u, du, ddu, tau of shape (N, n) by spatial::inverseDynamicsBatch over `threads` (as the
/// planar batch: 1 the calling thread, 0 one per hardware thread), the GIL released; a sample the
/// model refuses raises "sample K: reason" (K from 1) when `check` (the first in index order,
/// whatever the split), else its row is NaN; with `check_limits`, the first sample beyond a
/// joint's range or velocity or an actuator's effort raises "sample K: joint range exceeded: ..."
/// after the batch is computed.
py::tuple inverseDynamics(const SpatialRobot& robot, const py::handle& p, const py::handle& dp, const py::handle& ddp,
                          bool check, bool check_limits, unsigned threads) {
    const spatial::Model& model = *robot.model;
    const int d = model.task_dimension;
    const Rows P = samples(p, "p", d, -1);
    const py::ssize_t N = P.shape(0);
    const Rows dP = samples(dp, "dp", d, N), ddP = samples(ddp, "ddp", d, N);
    const int n = model.actuators;
    std::array<Rows, 4> out{Rows({N, static_cast<py::ssize_t>(n)}), Rows({N, static_cast<py::ssize_t>(n)}),
                            Rows({N, static_cast<py::ssize_t>(n)}), Rows({N, static_cast<py::ssize_t>(n)})};
    // C-ordered (N, m) arrays as column-major maps: row stride m, column stride 1
    const auto in = [N](const Rows& a, int m) {
        return ConstStridedMap(a.data(), N, m, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, m));
    };
    const auto to = [N, n](Rows& a) {
        return StridedMap(a.mutable_data(), N, n, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, n));
    };
    StridedMap u = to(out[0]), du = to(out[1]), ddu = to(out[2]), tau = to(out[3]);
    spatial::BatchOptions options;
    options.threads = threads;
    options.check_limits = check_limits;
    options.stop_at_failure = check;
    BatchResult result;
    {
        const py::gil_scoped_release release;
        result = spatial::inverseDynamicsBatch(model, in(P, d), in(dP, d), in(ddP, d), u, du, ddu, tau, options);
    }
    // a failure raised first unless a sample before it is beyond a limit
    if (!result.ok() && check && result.first_failure < result.first_beyond_limits) {
        throw Error("sample " + std::to_string(result.first_failure + 1) + ": " +
                    spatial::describe(result.status, model));
    }
    if (result.first_beyond_limits != BatchResult::npos) {
        throw Error("sample " + std::to_string(result.first_beyond_limits + 1) + ": " +
                    spatial::describeLimit(result.limits, model));
    }
    return py::make_tuple(out[0], out[1], out[2], out[3]);
}

/// Every assembly mode found for u (spatial_direct_kinematics.hpp): a dict of the method,
/// complete, starts and the modes (pose in the coordinates' order, working, home_branches,
/// u_error, condition), nearest home first.
py::dict forwardKinematics(const SpatialRobot& robot, const std::vector<double>& values) {
    const spatial::Model& model = *robot.model;
    spatial::ActuatorVector u(static_cast<Eigen::Index>(values.size()));
    for (std::size_t a = 0; a < values.size(); ++a) u(static_cast<Eigen::Index>(a)) = values[a];
    spatial::AssemblyModes modes;
    {
        const py::gil_scoped_release release;
        modes = spatial::assemblyModes(model, u);
    }
    py::list list;
    for (const spatial::AssemblyMode& mode : modes.modes) {
        py::dict m;
        m["pose"] = std::vector<double>(mode.p.data(), mode.p.data() + mode.p.size());
        m["working"] = mode.working;
        m["home_branches"] = mode.home_branches;
        m["u_error"] = mode.u_error;
        m["condition"] = mode.condition;
        list.append(m);
    }
    py::dict out;
    out["method"] = modes.method == spatial::DirectMethod::three_spheres ? "three spheres" : "many starts";
    out["complete"] = modes.complete;
    out["starts"] = modes.starts;
    out["modes"] = list;
    return out;
}

/// The tracker over samples of u (N, n) from the pose p0: the poses (N, d); a sample where it
/// stops raises "sample K: reason" (K from 1).
Rows track(const SpatialRobot& robot, const py::handle& u, const std::vector<double>& p0) {
    const spatial::Model& model = *robot.model;
    const int d = model.task_dimension, n = model.actuators;
    const Rows U = samples(u, "u", n, -1);
    if (static_cast<int>(p0.size()) != d) throw Error("p0: expected " + std::to_string(d) + " values");
    const py::ssize_t N = U.shape(0);
    Rows out({N, static_cast<py::ssize_t>(d)});
    double* to = out.mutable_data();
    const double* from = U.data();
    py::ssize_t failed = -1;
    Status failure;
    {
        const py::gil_scoped_release release;
        spatial::Data data(model);
        spatial::TaskVector p(d);
        for (int i = 0; i < d; ++i) p(i) = p0[static_cast<std::size_t>(i)];
        spatial::ActuatorVector uk(n);
        for (py::ssize_t k = 0; k < N && failed < 0; ++k) {
            for (int a = 0; a < n; ++a) uk(a) = from[k * n + a];
            if (const Status status = spatial::directKinematics(model, data, uk, p); !status) {
                failed = k;
                failure = status;
            }
            for (int i = 0; i < d; ++i) to[k * d + i] = p(i);
        }
    }
    if (failed >= 0) {
        throw Error("sample " + std::to_string(failed + 1) + ": " + spatial::describeDirect(failure, model));
    }
    return out;
}

/// The real assembly modes of a 6-UPS robot at the actuator values u (nocdyn/analysis/
/// assembly_modes.hpp): (poses (m, 6), u_error (m,), a dict of the counts and phc's times).
py::tuple homotopyModes(const SpatialRobot& robot, const py::handle& u, double timeout, unsigned seed,
                        const std::string& executable) {
    const spatial::Model& model = *robot.model;
    const Rows values = Rows::ensure(u);
    if (!values || values.ndim() != 1 || values.shape(0) != model.actuators) {
        throw Error("u: expected shape (" + std::to_string(model.actuators) + ",)");
    }
    spatial::ActuatorVector u_k(model.actuators);
    for (int a = 0; a < model.actuators; ++a) u_k(a) = values.data()[a];
    spatial::HomotopyOptions options;
    options.timeout = timeout;
    options.seed = seed;
    options.executable = executable;
    spatial::HomotopyModes result;
    {
        const py::gil_scoped_release release;
        result = spatial::homotopyModes(model, u_k, options);
    }
    const auto m = static_cast<py::ssize_t>(result.modes.size());
    Rows poses({m, static_cast<py::ssize_t>(6)}), errors({m});
    double *to = poses.mutable_data(), *error = errors.mutable_data();
    for (py::ssize_t k = 0; k < m; ++k) {
        const spatial::HomotopyMode& mode = result.modes[static_cast<std::size_t>(k)];
        for (int i = 0; i < 6; ++i) to[k * 6 + i] = mode.pose(i);
        error[k] = mode.u_error;
    }
    py::dict info;
    info["paths"] = result.paths;
    info["solutions"] = result.solutions;
    info["real_solutions"] = result.real_solutions;
    info["rejected"] = result.rejected;
    info["seconds"] = result.seconds;
    info["cpu_seconds"] = result.cpu_seconds;
    info["executable"] = result.executable;
    return py::make_tuple(poses, errors, info);
}

SpatialRobot make(const SpatialRobotDescription& description, const std::string& source) {
    return SpatialRobot{std::make_shared<const spatial::Model>(description),
                        std::make_shared<const SpatialRobotDescription>(description), source};
}

/// `nocdyn pose` of a spatial robot as a dict (pose, limbs' joint variables, actuators, A,
/// forces and every joint's reaction at rest under gravity).
py::dict pose(const SpatialRobot& robot, const std::vector<double>& p, const py::object& progress) {
    const app::SpatialPoseResult r = runJob(progress, [&](app::Observer& observer) {
        return app::runSpatialPose(*robot.description, robot.source, p, observer);
    });
    py::list limbs, actuators, reactions;
    for (const app::SpatialPoseLimb& l : r.limbs) {
        limbs.append(py::dict(py::arg("limb") = l.limb, py::arg("name") = l.name, py::arg("type") = l.type,
                              py::arg("q") = l.q, py::arg("joints") = l.of, py::arg("cond_J") = l.cond_J));
    }
    for (const app::SpatialPoseActuator& a : r.actuators) {
        actuators.append(py::dict(py::arg("actuator") = a.actuator, py::arg("limb") = a.limb,
                                  py::arg("joint") = a.joint, py::arg("u") = a.u,
                                  py::arg("range_used") = a.range_used));
    }
    for (const app::SpatialPoseReaction& j : r.reactions) {
        reactions.append(py::dict(py::arg("limb") = j.limb, py::arg("joint") = j.joint,
                                  py::arg("type") = std::string(1, j.type), py::arg("point") = j.point,
                                  py::arg("force") = j.force, py::arg("moment") = j.moment));
    }
    return py::dict(py::arg("robot") = r.robot, py::arg("coordinates") = r.coordinates, py::arg("pose") = r.pose,
                    py::arg("limbs") = limbs, py::arg("actuators") = actuators, py::arg("A") = r.A,
                    py::arg("cond_A") = r.cond_A, py::arg("max_condition") = r.max_condition, py::arg("tau") = r.tau,
                    py::arg("reactions") = reactions, py::arg("balance_residual") = r.balance_residual,
                    py::arg("within_limits") = r.within_limits, py::arg("limits") = r.limits);
}

}  // namespace

py::tuple runSpatialInverseDynamics(const spatial::Model& model, const app::InverseDynamicsOptions& options,
                                    const py::object& progress) {
    app::validate(static_cast<const app::SamplingOptions&>(options));
    if (options.reactions) {
        throw app::OptionError("reactions",
                               "the joint reactions are computed for planar robots only, not for a "
                               "spatial robot (space: spatial)");
    }
    const spatial::Trajectory trajectory = app::spatialTrajectoryOf(options, model.task_dimension);
    // every sample is held: what would take more than kMaxHeldBytes is refused before any is computed
    const double duration = options.duration ? *options.duration : trajectory.duration.value_or(0.2);
    const double samples = static_cast<double>(sampleGrid(duration, options.rate).count);
    const double bytes = 8.0 * static_cast<double>(2 + model.task_dimension + 4 * model.actuators);
    if (samples * bytes > kMaxHeldBytes) {
        throw Error(
            text::format("%.6g samples of %.0f bytes would hold %.3g GB in memory, more than the %.0f MB "
                         "allowed: give a shorter duration or a lower rate (the command line's "
                         "inverse-dynamics streams any number to a file)",
                         samples, bytes, samples * bytes / 1e9, kMaxHeldBytes / 1e6));
    }
    auto table = std::make_shared<app::TableCollector>();
    (void)runJob(progress, [&](app::Observer& observer) {
        return app::runSpatialInverseDynamics(model, trajectory, options, options.allow_limits, *table, observer);
    });
    return py::make_tuple(table->names(), tableArray(*table));
}

void exposeSpatial(py::module_& m) {
    m.def(
        "is_spatial_file", [](const std::string& path) { return io::isSpatial(io::readRobotFileText(path), path); },
        py::arg("path"));
    m.def("is_spatial_text", &io::isSpatial, py::arg("text"), py::arg("source"));
    py::class_<SpatialRobot>(m, "SpatialRobot")
        .def_static(
            "load", [](const std::string& path) { return make(io::loadSpatialRobotDescription(path), path); },
            py::arg("path"))
        .def_static(
            "from_yaml",
            [](const std::string& text, const std::string& source) {
                return make(io::parseSpatialRobotDescription(text, source), source);
            },
            py::arg("text"), py::arg("source") = "<string>")
        .def_property_readonly("name", [](const SpatialRobot& r) { return r.model->name; })
        .def_property_readonly("actuator_count", [](const SpatialRobot& r) { return r.model->actuators; })
        .def_property_readonly("limb_count", [](const SpatialRobot& r) { return r.model->limbs(); })
        .def_property_readonly("task_dimension", [](const SpatialRobot& r) { return r.model->task_dimension; })
        .def_property_readonly("coordinates", [](const SpatialRobot& r) { return r.model->coordinates(); })
        .def_property_readonly("home",
                               [](const SpatialRobot& r) {
                                   const spatial::TaskVector& h = r.model->home;
                                   return std::vector<double>(h.data(), h.data() + h.size());
                               })
        .def_property_readonly("limb_names",
                               [](const SpatialRobot& r) {
                                   std::vector<std::string> names;
                                   for (const spatial::Limb& limb : r.model->limb) names.push_back(limb.name);
                                   return names;
                               })
        .def("_forward_kinematics", &forwardKinematics, py::arg("u"))
        .def("_track", &track, py::arg("u"), py::arg("p0"))
        .def("_inverse_dynamics", &inverseDynamics, py::arg("p"), py::arg("dp"), py::arg("ddp"),
             py::arg("check") = true, py::arg("check_limits") = true, py::arg("threads") = 1)
        .def(
            "_run_inverse_dynamics",
            [](const SpatialRobot& r, const app::InverseDynamicsOptions& options, const py::object& progress) {
                return runSpatialInverseDynamics(*r.model, options, progress);
            },
            py::arg("options"), py::arg("progress") = py::none(),
            "nocdyn.inverse_dynamics of this robot: (columns, rows) along options.trajectory")
        .def("_pose", &pose, py::arg("pose"), py::arg("progress") = py::none())
        .def("_assembly_modes", &homotopyModes, py::arg("u"), py::arg("timeout"), py::arg("seed"),
             py::arg("executable"));
}

}  // namespace nocdyn::python
