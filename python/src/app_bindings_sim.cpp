// forward-kinematics, simulate, control and frequency-response bound for the Python package:
// their options structs, _run_<command> functions (GIL released, an observer per call) and
// typed results as NumPy arrays and dicts.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>

#include "app/forward_kinematics.hpp"
#include "app_bindings.hpp"

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
}

}  // namespace nocdyn::python
