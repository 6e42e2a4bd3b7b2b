// The `nocdyn` command line inside the Python process, for `python -m nocdyn` and the `nocdyn`
// command pip installs (nocdyn/__main__.py). The Python functions do not go through it: they
// stand on the application layer (app_bindings.cpp).
#include "cli_main.hpp"

#include <pybind11/stl.h>

#include <array>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "app.hpp"

namespace nocdyn::python {

namespace {

/// The signal dispositions the command line replaces (it removes its temporary files on them),
/// put back when it returns: the interpreter's Ctrl-C is a KeyboardInterrupt again.
class SignalDispositions {
public:
    SignalDispositions() {
        for (std::size_t i = 0; i < kSignals.size(); ++i) ::sigaction(kSignals[i], nullptr, &saved_[i]);
    }
    ~SignalDispositions() {
        for (std::size_t i = 0; i < kSignals.size(); ++i) ::sigaction(kSignals[i], &saved_[i], nullptr);
    }
    SignalDispositions(const SignalDispositions&) = delete;
    SignalDispositions& operator=(const SignalDispositions&) = delete;

private:
    static constexpr std::array<int, 3> kSignals{SIGINT, SIGTERM, SIGHUP};
    std::array<struct sigaction, 3> saved_{};
};

}  // namespace

void bindCommandLine(py::module_& m) {
    m.def("_options_json", &cli::optionsJson, "Every command's options as JSON (as `nocdyn --help-json`).");
    m.def(
        "_main",
        [](const std::vector<std::string>& argv) {
            std::vector<const char*> pointers;
            pointers.reserve(argv.size());
            for (const std::string& a : argv) pointers.push_back(a.c_str());
            std::fflush(stdout);
            const SignalDispositions keep;
            const int status = cli::runCommandLine(static_cast<int>(pointers.size()), pointers.data());
            std::cout.flush();
            std::fflush(stdout);
            return status;
        },
        py::arg("argv"),
        "The `nocdyn` command line with these arguments (argv[0] the program); the exit status. The "
        "process's signal dispositions are as before when it returns.");
}

}  // namespace nocdyn::python
