// The application layer (app/) bound for the Python package: every command's options struct
// (its fields and defaults), its run function (GIL released, progress and Ctrl-C through an
// observer) and its typed result as NumPy arrays. No argv, no captured streams, no files.
#pragma once

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace nocdyn::python {

/// Adds the options types, _run_<command> functions and helpers to the compiled module.
void bindApplication(py::module_& m);

}  // namespace nocdyn::python
