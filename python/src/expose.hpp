// The compiled module's parts, one per concept, each adding its classes and functions to the
// module (module.cpp calls them in order, as Pinocchio's expose-*.cpp).
#pragma once

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace nocdyn::python {

/// nocdyn.Error (a ValueError) for nocdyn::Error (module.cpp).
void exposeErrors(py::module_& m);

/// The Robot class: construction, description, drawing (robot.cpp).
void exposeRobot(py::module_& m);

/// Robot's algorithms at one sample: inverse dynamics (and its NOC matrices), derivatives,
/// linearisation, direct kinematics, the state from actuator values, regressor, payload
/// (robot_algorithms.cpp). After exposeRobot.
void exposeRobotAlgorithms(py::module_& m);

/// Robot's stiffness and natural frequencies (stiffness.cpp). After exposeRobot.
void exposeStiffness(py::module_& m);

/// Robot's batches over sample arrays (batch.cpp). After exposeRobot.
void exposeBatch(py::module_& m);

/// The Trajectory class and the CSV layouts' column names (trajectory.cpp).
void exposeTrajectory(py::module_& m);

/// The design sweeps' chunks (design.cpp).
void exposeDesign(py::module_& m);

/// Spatial robots and their inverse dynamics over sample arrays (spatial.cpp).
void exposeSpatial(py::module_& m);

}  // namespace nocdyn::python
