// Bindings of the design sweeps (design.hpp, io/design.hpp) for nocdyn.designs: a chunk of
// designs of a parametric robot file evaluated on C++ threads with the GIL released, so that
// Python threads, processes and Dask workers evaluate in parallel, and the Pareto front of a
// table by the library's paretoFront, the one the command line writes.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "nocdyn/analysis/design.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/tables/design.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/model.hpp"
#include "expose.hpp"

namespace py = pybind11;

namespace {

nocdyn::io::ParameterSet parameterSet(const std::vector<std::pair<std::string, double>>& pairs) {
    nocdyn::io::ParameterSet set;
    for (const auto& [name, value] : pairs) set.push_back({name, value});
    return set;
}

nocdyn::tables::DesignFamily family(const std::string& text, const std::string& source,
                                    const std::vector<std::pair<std::string, double>>& fixed,
                                    const std::vector<std::string>& names) {
    nocdyn::tables::DesignFamily f;
    f.text = text;
    f.source = source;
    f.fixed = parameterSet(fixed);
    for (const std::string& n : names) f.ranges.push_back({n, -INFINITY, INFINITY});
    return f;
}

}  // namespace

namespace nocdyn::python {

void exposeDesign(py::module_& m) {
    m.def(
        "_robot_file_parameters",
        [](const std::string& text, const std::string& source,
           const std::vector<std::pair<std::string, double>>& overrides) {
            std::vector<std::pair<std::string, double>> out;
            for (const io::Parameter& p : io::robotFileParameters(text, source, parameterSet(overrides)))
                out.emplace_back(p.name, p.value);
            return out;
        },
        py::arg("text"), py::arg("source"), py::arg("overrides"));
    m.def(
        "_convert",
        [](const std::string& text, const std::string& source,
           const std::vector<std::pair<std::string, double>>& overrides) {
            const RobotDescription robot = io::parseRobotDescription(text, source, parameterSet(overrides));
            const Model model(robot);  // as `nocdyn convert`: the home posture must be regular
            return io::descriptionToYaml(robot);
        },
        py::arg("text"), py::arg("source"), py::arg("overrides"));
    m.def(
        "_design_metric_names",
        [](const std::vector<std::string>& metrics) {
            std::vector<std::tuple<std::string, std::string, bool>> out;
            for (const std::string& text : metrics) {
                const DesignMetric d = parseDesignMetric(text);
                out.emplace_back(d.name(), d.unit(), d.larger_is_better());
            }
            return out;
        },
        py::arg("metrics"));
    m.def(
        "_evaluate_designs",
        [](const std::string& text, const std::string& source, const std::vector<std::pair<std::string, double>>& fixed,
           const std::vector<std::string>& names,
           const py::array_t<double, py::array::c_style | py::array::forcecast>& points,
           const std::vector<std::string>& metric_names, std::optional<double> theta, int resolution,
           std::optional<PoseTrajectory> trajectory, double duration, double rate, int threads) {
            if (points.ndim() != 2 || static_cast<std::size_t>(points.shape(1)) != names.size())
                throw Error("points: expected shape (N, " + std::to_string(names.size()) + ")");
            const auto n = static_cast<std::size_t>(points.shape(0));
            if (n > kMaxDesigns) throw Error("points: at most " + std::to_string(kMaxDesigns) + " designs at once");
            const tables::DesignFamily f = family(text, source, fixed, names);
            std::vector<DesignMetric> metrics;
            for (const std::string& t : metric_names) metrics.push_back(parseDesignMetric(t));
            DesignOptions options;
            options.workspace.resolution = resolution;
            options.workspace_theta_at_home = !theta.has_value();
            options.workspace.theta = theta.value_or(0.0);
            options.trajectory = std::move(trajectory);
            options.duration = duration;
            options.rate = rate;
            std::vector<std::vector<double>> rows(n, std::vector<double>(names.size()));
            const auto view = points.unchecked<2>();
            for (std::size_t i = 0; i < n; ++i) {
                for (std::size_t k = 0; k < names.size(); ++k)
                    rows[i][k] = view(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k));
            }
            std::vector<DesignEvaluation> results(n);
            {
                const py::gil_scoped_release release;
                (void)evaluateInParallel(
                    n, threads,
                    [&](std::size_t i) { return tables::evaluateFamilyDesign(f, rows[i], metrics, options); },
                    [&](std::size_t i, DesignEvaluation&& e) { results[i] = std::move(e); });
            }
            py::array_t<double> values({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(metrics.size())});
            auto out = values.mutable_unchecked<2>();
            py::array_t<bool> feasible(static_cast<py::ssize_t>(n));
            auto ok = feasible.mutable_unchecked<1>();
            std::vector<std::string> reasons(n);
            for (std::size_t i = 0; i < n; ++i) {
                for (std::size_t k = 0; k < metrics.size(); ++k)
                    out(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) = results[i].values[k];
                ok(static_cast<py::ssize_t>(i)) = results[i].feasible;
                reasons[i] = results[i].reason;
            }
            return py::make_tuple(values, feasible, reasons);
        },
        py::arg("text"), py::arg("source"), py::arg("fixed"), py::arg("names"), py::arg("points"), py::arg("metrics"),
        py::arg("theta"), py::arg("resolution"), py::arg("trajectory"), py::arg("duration"), py::arg("rate"),
        py::arg("threads"));
    m.def(
        "_pareto_front",
        [](const py::array_t<double, py::array::c_style | py::array::forcecast>& values,
           const py::array_t<bool, py::array::c_style | py::array::forcecast>& feasible,
           const std::vector<bool>& larger_is_better) {
            const auto metrics = larger_is_better.size();
            if (values.ndim() != 2 || static_cast<std::size_t>(values.shape(1)) != metrics)
                throw Error("values: expected shape (N, " + std::to_string(metrics) + ")");
            if (feasible.ndim() != 1 || feasible.shape(0) != values.shape(0))
                throw Error("feasible: expected shape (" + std::to_string(values.shape(0)) + ",)");
            const std::span<const double> v(values.data(), static_cast<std::size_t>(values.size()));
            const std::span<const bool> ok(feasible.data(), static_cast<std::size_t>(feasible.size()));
            const py::gil_scoped_release release;
            return paretoFront(v, ok, larger_is_better);
        },
        py::arg("values"), py::arg("feasible"), py::arg("larger_is_better"));
}

}  // namespace nocdyn::python
