// The compiled part of the Python package `nocdyn` (pybind11), one file per concept: arrays.cpp
// (NumPy to the library's types), robot.cpp (the model), robot_algorithms.cpp and stiffness.cpp
// (its algorithms at one sample), batch.cpp (over sample arrays), trajectory.cpp, design.cpp
// (the design sweeps' chunks), spatial.cpp (spatial robots), app_bindings*.cpp (every command's job: options, run,
// typed result) and cli_main.cpp (the command line, for `python -m nocdyn`). The Pythonic layer and the docstrings
// users read are in ../nocdyn/.
#include <pybind11/pybind11.h>

#include "app_bindings.hpp"
#include "cli_main.hpp"
#include "expose.hpp"
#include "nocdyn/error.hpp"

namespace nocdyn::python {

void exposeErrors(py::module_& m) { py::register_exception<Error>(m, "Error", PyExc_ValueError); }

}  // namespace nocdyn::python

PYBIND11_MODULE(_nocdyn, m) {
    using namespace nocdyn::python;
    m.doc() = "Compiled core of the nocdyn package (use `import nocdyn`).";
    m.attr("__version__") = NOCDYN_VERSION;
    exposeErrors(m);
    exposeRobot(m);
    exposeRobotAlgorithms(m);
    exposeStiffness(m);
    exposeBatch(m);
    exposeTrajectory(m);
    exposeDesign(m);
    exposeSpatial(m);
    bindApplication(m);
    bindCommandLine(m);
}
