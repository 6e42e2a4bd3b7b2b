// The command line's commands, bound for the Python package (cli_commands.cpp).
#pragma once

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace nocdyn::python {

/// Adds _run_command, _options_json and _main to the compiled module.
void bindCommands(py::module_& m);

}  // namespace nocdyn::python
