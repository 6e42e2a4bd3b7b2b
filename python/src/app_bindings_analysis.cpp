// The analysis commands bound for Python: envelope, workspace, loads, regressor, convert and
// design. Each takes its options struct and returns its typed result as NumPy arrays; files only
// where the caller names them, written by the library's safe writers.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "app/convert.hpp"
#include "app/design.hpp"
#include "app/design_outputs.hpp"
#include "app/envelope.hpp"
#include "app/loads.hpp"
#include "app/outputs.hpp"
#include "app/regressor.hpp"
#include "app/workspace.hpp"
#include "app_bindings.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/io/output.hpp"

namespace nocdyn::python {

namespace {

/// A table as the command line writes it: (columns, (rows, columns) float64 array, labels), a
/// column of categories NaN in the array and its words in labels[column] (as results.read_csv).
py::tuple tableTuple(const io::Table& table) {
    const auto columns = static_cast<py::ssize_t>(table.columns.size());
    const auto rows = static_cast<py::ssize_t>(table.rows.size());
    py::array_t<double> data({rows, columns});
    py::dict labels;
    for (py::ssize_t k = 0; k < columns; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        const bool words = kk < table.categories.size() && !table.categories[kk].empty();
        py::list column;
        for (py::ssize_t i = 0; i < rows; ++i) {
            const double v = table.rows[static_cast<std::size_t>(i)][kk];
            data.mutable_at(i, k) = words ? std::numeric_limits<double>::quiet_NaN() : v;
            if (words) column.append(table.categories[kk].at(static_cast<std::size_t>(v)));
        }
        if (words) labels[py::str(table.columns[kk])] = column;
    }
    return py::make_tuple(table.columns, data, labels);
}

/// The table as the command line's CSV at `path` (a unique temporary file, then renamed).
void writeCsvFile(const io::Table& table, const std::string& path) {
    io::OutputFile out(path);
    io::writeCsv(out, table);
    out.commit();
}

/// The text at `path` (none when empty), written safely.
void writeText(const std::string& text, const std::string& path) {
    if (!path.empty()) io::writeTextFile(path, text);
}

/// py::none() or a path: the file to write, empty for none.
std::string pathOrEmpty(const py::object& path) {
    return path.is_none() ? std::string() : py::str(path).cast<std::string>();
}

}  // namespace

void bindAnalysis(py::module_& m) {
    OptionsClass<app::EnvelopeOptions>(m, "EnvelopeOptions")
        .field("robot", &app::EnvelopeOptions::robot)
        .option("min_frequency", &app::EnvelopeOptions::min_frequency)
        .option("max_frequency", &app::EnvelopeOptions::max_frequency)
        .option("points", &app::EnvelopeOptions::points)
        .option("samples_per_period", &app::EnvelopeOptions::samples_per_period)
        .option("relative_tolerance", &app::EnvelopeOptions::relative_tolerance)
        .option("amplification", &app::EnvelopeOptions::amplification);
    m.def(
        "_run_envelope",
        [](const app::EnvelopeOptions& options, const py::object& progress, const py::object& output,
           const py::object& figure) {
            const std::string csv = pathOrEmpty(output), stem = pathOrEmpty(figure);
            const app::EnvelopeResult result = runJob(progress, [&](app::Observer& observer) {
                app::EnvelopeResult r = app::runEnvelope(options, observer);
                if (!csv.empty()) writeCsvFile(r.table, csv);
                if (!stem.empty()) app::writeEnvelopeFigure(r, stem);
                return r;
            });
            // (table, summary, first natural frequency [Hz] or None, {axis: band end [Hz]} or None,
            // why the resonance is unknown or "")
            const EnvelopeResonance& resonance = result.resonance;
            py::object first = py::none(), band_end = py::none();
            if (resonance.known) {
                first = py::float_(resonance.frequency);
                py::dict ends;
                for (const EnvelopeAxis axis : kEnvelopeAxes)
                    if (hasAxis(resonance.task_dimension, axis))
                        ends[axisName(axis)] = resonance.band_end[static_cast<std::size_t>(axis)];
                band_end = ends;
            }
            return py::make_tuple(tableTuple(result.table), result.summary, first, band_end,
                                  resonance.known ? std::string() : resonance.reason);
        },
        py::arg("options"), py::arg("progress") = py::none(), py::arg("output") = py::none(),
        py::arg("figure") = py::none());

    OptionsClass<app::WorkspaceOptions>(m, "WorkspaceOptions")
        .field("robot", &app::WorkspaceOptions::robot)
        .option("theta", &app::WorkspaceOptions::theta)
        .option("resolution", &app::WorkspaceOptions::resolution)
        .option("first_frequency", &app::WorkspaceOptions::first_frequency);
    m.def(
        "_run_workspace",
        [](const app::WorkspaceOptions& options, const py::object& progress, const py::object& output,
           const py::object& figure, const py::object& frequency_map) {
            const std::string csv = pathOrEmpty(output), stem = pathOrEmpty(figure),
                              frequency_stem = pathOrEmpty(frequency_map);
            app::WorkspaceOptions run = options;
            if (!frequency_stem.empty()) run.first_frequency = true;  // as the command line's --frequency-map
            const app::WorkspaceResult result = runJob(progress, [&](app::Observer& observer) {
                app::WorkspaceResult r = app::runWorkspace(run, observer);
                if (!csv.empty()) writeCsvFile(r.table, csv);
                if (!stem.empty()) app::writeWorkspaceFigure(r, stem);
                if (!frequency_stem.empty()) {
                    writeCsvFile(r.frequency_table, frequency_stem + ".csv");
                    app::writeFrequencyFigure(r, frequency_stem);
                }
                return r;
            });
            // f_1 per grid point as an (n, n) array indexed [ix, iy] (NaN where not feasible)
            py::object frequency = py::none();
            if (result.frequency) {
                const FirstFrequencyMap& f = *result.frequency;
                const auto n = static_cast<py::ssize_t>(result.map.n);
                py::array_t<double> first({n, n});
                std::copy(f.first.begin(), f.first.end(), first.mutable_data());
                frequency = py::dict(py::arg("first") = first, py::arg("lowest") = f.lowest,
                                     py::arg("lowest_at") = py::make_tuple(f.lowest_x, f.lowest_y, result.map.theta),
                                     py::arg("highest") = f.highest, py::arg("points") = f.points,
                                     py::arg("table") = tableTuple(result.frequency_table));
            }
            return py::make_tuple(tableTuple(result.table), result.summary, frequency);
        },
        py::arg("options"), py::arg("progress") = py::none(), py::arg("output") = py::none(),
        py::arg("figure") = py::none(), py::arg("frequency_map") = py::none());

    OptionsClass<app::RegressorOptions>(m, "RegressorOptions")
        .field("robot", &app::RegressorOptions::robot)
        .option("samples", &app::RegressorOptions::samples)
        .option("seed", &app::RegressorOptions::seed);
    m.def(
        "_run_regressor",
        [](const app::RegressorOptions& options, const py::object& progress, const py::object& output) {
            const std::string path = pathOrEmpty(output);
            const app::RegressorResult r = runJob(progress, [&](app::Observer& observer) {
                app::RegressorResult result = app::runRegressor(options, observer);
                writeText(result.text, path);
                return result;
            });
            return py::dict(py::arg("text") = r.text, py::arg("names") = r.names, py::arg("units") = r.units,
                            py::arg("pi") = r.pi, py::arg("rank") = r.base.rank,
                            py::arg("independent") = r.base.independent,
                            py::arg("unidentifiable") = r.base.unidentifiable, py::arg("K") = r.base.K,
                            py::arg("condition") = r.base.condition);
        },
        py::arg("options"), py::arg("progress") = py::none(), py::arg("output") = py::none());

    OptionsClass<app::ConvertOptions>(m, "ConvertOptions").field("robot", &app::ConvertOptions::robot);
    m.def(
        "_run_convert",
        [](const app::ConvertOptions& options, const py::object& progress, const py::object& output) {
            const std::string path = pathOrEmpty(output);
            return runJob(progress, [&](app::Observer& observer) {
                app::ConvertResult result = app::runConvert(options, observer);
                writeText(result.text, path);
                return result.text;
            });
        },
        py::arg("options"), py::arg("progress") = py::none(), py::arg("output") = py::none());

    OptionsClass<app::LoadsOptions, app::SamplingOptions>(m, "LoadsOptions")
        .field("robot", &app::LoadsOptions::robot)
        .inherited("trajectory")
        .inherited("duration")
        .inherited("rate")
        .option("envelope", &app::LoadsOptions::envelope)
        .option("min_frequency", &app::LoadsOptions::min_frequency)
        .option("max_frequency", &app::LoadsOptions::max_frequency)
        .option("points", &app::LoadsOptions::points);
    m.def(
        "_run_loads",
        [](const app::LoadsOptions& options, const py::object& progress, const py::object& output,
           const py::object& figure) {
            const std::string csv = pathOrEmpty(output), stem = pathOrEmpty(figure);
            const app::LoadsResult result = runJob(progress, [&](app::Observer& observer) {
                if (!stem.empty()) app::requireLoadsFigure(options);
                app::LoadsResult r = app::runLoads(options, observer);
                if (!csv.empty()) writeCsvFile(r.table, csv);
                if (!stem.empty()) app::writeLoadsFigure(options, r, stem);
                return r;
            });
            return py::make_tuple(tableTuple(result.table), result.text);
        },
        py::arg("options"), py::arg("progress") = py::none(), py::arg("output") = py::none(),
        py::arg("figure") = py::none());

    OptionsClass<app::DesignOptions>(m, "DesignOptions")
        .field("robot", &app::DesignOptions::robot)
        .field("out_dir", &app::DesignOptions::out_dir)
        .option("vary", &app::DesignOptions::vary)
        .option("metric", &app::DesignOptions::metric)
        .option("sweep", &app::DesignOptions::sweep)
        .option("samples", &app::DesignOptions::samples)
        .option("seed", &app::DesignOptions::seed)
        .option("threads", &app::DesignOptions::threads)
        .option("theta", &app::DesignOptions::theta)
        .option("resolution", &app::DesignOptions::resolution)
        .option("trajectory", &app::DesignOptions::trajectory)
        .option("duration", &app::DesignOptions::duration)
        .option("rate", &app::DesignOptions::rate)
        .option("no_figures", &app::DesignOptions::no_figures);
    m.def(
        "_run_design",
        [](const app::DesignOptions& options, const py::object& progress) {
            app::DesignFolder files(options.out_dir);
            const app::DesignResult r =
                runJob(progress, [&](app::Observer& observer) { return app::runDesign(options, observer, files); });
            const auto n = static_cast<py::ssize_t>(r.records.size());
            const auto d = static_cast<py::ssize_t>(r.names.size());
            const auto k = static_cast<py::ssize_t>(r.metrics.size());
            py::array_t<double> points({n, d}), values({n, k});
            py::array_t<bool> feasible(n);
            py::list reason;
            for (py::ssize_t i = 0; i < n; ++i) {
                const tables::DesignRecord& record = r.records[static_cast<std::size_t>(i)];
                for (py::ssize_t c = 0; c < d; ++c) points.mutable_at(i, c) = record.point[static_cast<std::size_t>(c)];
                for (py::ssize_t c = 0; c < k; ++c) {
                    values.mutable_at(i, c) = record.evaluation.feasible
                                                  ? record.evaluation.values[static_cast<std::size_t>(c)]
                                                  : std::numeric_limits<double>::quiet_NaN();
                }
                feasible.mutable_at(i) = record.evaluation.feasible;
                reason.append(record.evaluation.reason);
            }
            return py::dict(py::arg("names") = r.names, py::arg("metrics") = r.metrics, py::arg("points") = points,
                            py::arg("values") = values, py::arg("feasible") = feasible, py::arg("reason") = reason,
                            py::arg("front") = r.front, py::arg("resumed") = r.resumed);
        },
        py::arg("options"), py::arg("progress") = py::none());
}

}  // namespace nocdyn::python
