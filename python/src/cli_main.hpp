// The `nocdyn` command line bound for `python -m nocdyn` (cli_main.cpp).
#pragma once

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace nocdyn::python {

/// Adds _main and _options_json to the compiled module.
void bindCommandLine(py::module_& m);

}  // namespace nocdyn::python
