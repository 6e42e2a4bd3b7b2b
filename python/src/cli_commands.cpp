// The command line's commands for the Python package: the very code `nocdyn <command>` runs
// (apps/nocdyn, the nocdyn_commands library), with its defaults and checks. The Python layer
// (../nocdyn/commands.py) turns keyword arguments into the command's options, lets it write its
// files into a temporary folder and reads them back as NumPy arrays.
#include "cli_commands.hpp"

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "app.hpp"
#include "common.hpp"

namespace nocdyn::python {

namespace {

/// Points one standard stream (1 or 2) at a temporary file for a scope and gives its text.
class Capture {
public:
    explicit Capture(int fd) : fd_(fd), file_(std::tmpfile()) {
        flush();
        if (file_ != nullptr) {
            saved_ = ::dup(fd_);
            if (saved_ >= 0) ::dup2(::fileno(file_), fd_);
        }
    }
    ~Capture() {
        restore();
        if (file_ != nullptr) std::fclose(file_);
    }
    Capture(const Capture&) = delete;
    Capture& operator=(const Capture&) = delete;

    std::string text() {
        restore();
        std::string out;
        if (file_ == nullptr) return out;
        std::rewind(file_);
        char buffer[4096];
        for (std::size_t read; (read = std::fread(buffer, 1, sizeof buffer, file_)) > 0;) out.append(buffer, read);
        return out;
    }

private:
    static void flush() {
        std::cout.flush();
        std::cerr.flush();
        std::fflush(stdout);
        std::fflush(stderr);
    }
    void restore() {
        if (saved_ < 0) return;
        flush();
        ::dup2(saved_, fd_);
        ::close(saved_);
        saved_ = -1;
    }
    int fd_;
    std::FILE* file_;
    int saved_ = -1;
};

/// A malformed argument: the command line's message (the option named as on the command line;
/// the Python layer renames it to the argument).
struct ParseFailure : std::exception {
    explicit ParseFailure(std::string text) : message(std::move(text)) {}
    const char* what() const noexcept override { return message.c_str(); }
    std::string message;
};

/// Runs `nocdyn <arguments>` with the GIL released, standard output and error captured (one
/// command at a time), the progress callback (done, total) called with the GIL held, and
/// Ctrl-C stopping the command. Returns (stdout, stderr).
std::pair<std::string, std::string> runCommand(const std::vector<std::string>& arguments,
                                               const std::function<void(double, double)>& progress) {
    std::string out, err;
    {
        py::gil_scoped_release release;
        // one command at a time: the captured streams and the progress observer are the process's
        static std::mutex one_at_a_time;
        const std::lock_guard<std::mutex> lock(one_at_a_time);
        Capture capture_out(1), capture_err(2);
        if (progress) {
            cli::setProgressObserver([&progress](double done, double total) {
                py::gil_scoped_acquire acquire;
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C stops the job
                progress(done, total);
            });
        } else {
            cli::setProgressObserver([](double, double) {
                py::gil_scoped_acquire acquire;
                if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            });
        }
        struct Reset {
            ~Reset() { cli::setProgressObserver({}); }
        } reset;
        try {
            cli::runCommand(arguments);
        } catch (const CLI::Success&) {
            // --help or --version: their text is the output
        } catch (const CLI::ParseError& e) {
            throw ParseFailure(e.what());
        }
        out = capture_out.text();
        err = capture_err.text();
    }
    return {std::move(out), std::move(err)};
}

}  // namespace

void bindCommands(py::module_& m) {
    static py::exception<ParseFailure> parse_error(m, "_ArgumentError", PyExc_ValueError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const ParseFailure& e) {
            parse_error(e.what());
        }
    });
    m.def("_run_command", &runCommand, py::arg("arguments"), py::arg("progress") = nullptr,
          "Runs `nocdyn <arguments>` in this process (GIL released): returns (stdout, stderr).");
}

}  // namespace nocdyn::python
