// The paper's results (`reproduce`) and the engines' check (`validate`, built with both engines)
// bound as their options structs and run functions (app/).
#include <pybind11/stl.h>

#include <string>

#include "app/reproduce.hpp"
#include "app_bindings.hpp"
#ifdef NOCDYN_HAS_ENGINES
#include "app/validate.hpp"
#endif

namespace nocdyn::python {

void bindReport(py::module_& m) {
    using R = app::ReproduceOptions;
    OptionsClass<R>(m, "ReproduceOptions")
        .option("out_dir", &R::out_dir)
        .option("closed_loop_duration", &R::closed_loop_duration)
        .option("identification_duration", &R::identification_duration);
    m.def(
        "_run_reproduce",
        [](const R& options, const py::object& progress) {
            app::OutputFolder files(options.out_dir, app::OutputFolder::Wording::output_folder);
            const app::ReproduceResult result =
                runJob(progress, [&](app::Observer& observer) { return app::runReproduce(options, observer, files); });
            return result.folder.string();
        },
        py::arg("options"), py::arg("progress") = py::none());
#ifdef NOCDYN_HAS_ENGINES
    using V = app::ValidateOptions;
    OptionsClass<V, app::SamplingOptions>(m, "ValidateOptions")
        .field("robot", &V::robot)
        .option("engine", &V::engine)
        .inherited("trajectory")
        .inherited("duration")
        .inherited("rate");
    m.def(
        "_run_validate",
        [](const V& options, const py::object& progress) {
            const app::ValidateResult result =
                runJob(progress, [&](app::Observer& observer) { return app::runValidate(options, observer); });
            const std::string text = "nocdyn validate: " + result.robot + ", " + result.trajectory + ", " +
                                     std::to_string(result.samples) + " samples\n" + result.agreement;
            return py::make_tuple(result.table.columns, rowsArray(result.table), text);
        },
        py::arg("options"), py::arg("progress") = py::none());
#endif
}

}  // namespace nocdyn::python
