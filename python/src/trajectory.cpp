// The Trajectory class of the compiled module (trajectory.hpp): harmonic trajectories (the
// paper's eqs. 33-34, a YAML file, harmonics given in code) and sampled ones (CSV), evaluated at
// arrays of times; and the CSV layouts' column names (io/layouts.hpp) of the tables Python writes.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cctype>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "expose.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::python {

namespace {

AxisMotion axisMotion(double offset, const std::vector<std::array<double, 3>>& harmonics) {
    AxisMotion m;
    m.offset = offset;
    for (const auto& h : harmonics) m.harmonics.push_back({h[0], h[1], h[2]});
    return m;
}

std::vector<std::array<double, 3>> harmonicsOf(const AxisMotion& m) {
    std::vector<std::array<double, 3>> out;
    for (const Harmonic& h : m.harmonics) out.push_back({h.amplitude, h.frequency, h.phase});
    return out;
}

/// p, dp/dt and d2p/dt2 at each time of t, three (N, 3) arrays.
py::tuple evaluateTrajectory(const PoseTrajectory& trajectory, const ContiguousInput& t) {
    if (t.ndim() != 1) throw Error("t: expected a one-dimensional array of times");
    const py::ssize_t n = t.shape(0);
    RowArray P({n, py::ssize_t{3}}), dP({n, py::ssize_t{3}}), ddP({n, py::ssize_t{3}});
    auto tp = t.unchecked<1>();
    auto a = P.mutable_unchecked<2>(), b = dP.mutable_unchecked<2>(), c = ddP.mutable_unchecked<2>();
    for (py::ssize_t k = 0; k < n; ++k) {
        Pose p, dp, ddp;
        trajectory.evaluate(tp(k), p, dp, ddp);
        for (int i = 0; i < 3; ++i) {
            a(k, i) = p(twistIndex(i));
            b(k, i) = dp(twistIndex(i));
            c(k, i) = ddp(twistIndex(i));
        }
    }
    return py::make_tuple(P, dP, ddP);
}

}  // namespace

void exposeTrajectory(py::module_& m) {
    py::class_<PoseTrajectory>(m, "Trajectory")
        .def(py::init([](const std::string& name, double theta_offset, const std::vector<std::array<double, 3>>& theta,
                         double x_offset, const std::vector<std::array<double, 3>>& x, double y_offset,
                         const std::vector<std::array<double, 3>>& y, std::optional<double> duration) {
                 PoseTrajectory t;
                 t.name = name;
                 t.theta = axisMotion(theta_offset, theta);
                 t.x = axisMotion(x_offset, x);
                 t.y = axisMotion(y_offset, y);
                 t.duration = duration;
                 return t;
             }),
             py::arg("name"), py::arg("theta_offset"), py::arg("theta"), py::arg("x_offset"), py::arg("x"),
             py::arg("y_offset"), py::arg("y"), py::arg("duration"))
        .def_static(
            "load",
            [](const std::string& path) {
                // samples (.csv, any case) or the harmonic YAML format, as --trajectory takes them
                std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : std::string();
                for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
                return ext == ".csv" ? io::loadTrajectoryCsv(path) : io::loadTrajectory(path);
            },
            py::arg("path"))
        .def_static(
            "from_csv",
            [](const std::string& text, const std::string& source) { return io::parseTrajectoryCsv(text, source); },
            py::arg("text"), py::arg("source") = "<string>")
        .def_static(
            "from_yaml",
            [](const std::string& text, const std::string& source) { return io::parseTrajectory(text, source); },
            py::arg("text"), py::arg("source") = "<string>")
        .def_static("paper1", &paperTrajectory1)
        .def_static("paper2", &paperTrajectory2)
        .def_readonly("name", &PoseTrajectory::name)
        .def_readonly("duration", &PoseTrajectory::duration)
        .def_property_readonly("highest_frequency", [](const PoseTrajectory& t) { return highestFrequency(t); })
        .def("_axis",
             [](const PoseTrajectory& t, const std::string& axis) {
                 const AxisMotion& a = axis == "theta" ? t.theta : axis == "x" ? t.x : t.y;
                 return py::make_tuple(a.offset, harmonicsOf(a));
             })
        .def("_evaluate", &evaluateTrajectory, py::arg("t"));

    // the CSV layouts (io/layouts.hpp): the header of a table Python writes itself
    m.def(
        "_column_names",
        [](const std::string& table, int actuators, int limbs, std::vector<std::string> parameters,
           std::vector<std::string> metrics, bool optional) {
            const io::LayoutSizes sizes{actuators, limbs, std::move(parameters), std::move(metrics), optional};
            return io::columnNames(io::tableId(table), sizes);
        },
        py::arg("table"), py::arg("actuators") = 0, py::arg("limbs") = 0,
        py::arg("parameters") = std::vector<std::string>{}, py::arg("metrics") = std::vector<std::string>{},
        py::arg("optional") = false);
}

}  // namespace nocdyn::python
