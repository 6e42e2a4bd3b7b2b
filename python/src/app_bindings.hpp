// The application layer (app/) bound for the Python package: every command's options struct
// (its fields and defaults), its run function (GIL released, progress and Ctrl-C through an
// observer) and its typed result as NumPy arrays. No argv, no captured streams, no files.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "app/inverse_dynamics.hpp"
#include "app/observer.hpp"
#include "app/options.hpp"
#include "app/table.hpp"
#include "nocdyn/choice.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/printable.hpp"
#include "nocdyn/spatial.hpp"

namespace py = pybind11;

namespace nocdyn::python {

/// A job's observer for Python: progress to the callback (GIL held), Ctrl-C (a pending signal)
/// stops the job with the KeyboardInterrupt, warnings kept and issued as Python warnings once
/// the job returns. One per call: two threads run two jobs with nothing shared.
class PythonObserver final : public app::Observer {
public:
    explicit PythonObserver(py::object callback) : callback_(std::move(callback)) {}

    void progress(double done, double total, std::string_view /*unit*/) override {
        const py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        if (!callback_.is_none()) callback_(done, total);
    }
    void step(std::string_view /*what*/, int index, int total) override {
        progress(static_cast<double>(index - 1), static_cast<double>(total), "steps");
    }
    void warning(std::string_view text) override { warnings_.emplace_back(text); }
    bool stopRequested() override {
        const py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
        return false;
    }
    /// With the GIL held: each warning as a RuntimeWarning (an error when warnings are errors).
    void issueWarnings() {
        for (const std::string& text : warnings_) {
            if (PyErr_WarnEx(PyExc_RuntimeWarning, text.c_str(), 2) != 0) throw py::error_already_set();
        }
        warnings_.clear();
    }

private:
    py::object callback_;
    std::vector<std::string> warnings_;
};

/// An application options struct as a Python class, each field bound once: `option` binds a
/// field and records its name in the class's `_fields` (the keywords the Python functions take,
/// in this order; python/nocdyn/commands.py), `field` binds one that is not such a keyword (the
/// robot, the output paths), `property` binds a keyword through a getter and a setter,
/// `inherited` records a field that a base's class binds.
template <class Options, class... Bases>
class OptionsClass {
public:
    OptionsClass(py::module_& m, const char* name)
        : class_(m, name), names_(std::make_shared<std::vector<std::string>>()) {
        class_.def(py::init<>());
        class_.def_property_readonly_static("_fields", [names = names_](const py::object&) {
            py::tuple fields(names->size());
            for (std::size_t i = 0; i < names->size(); ++i) fields[i] = py::str((*names)[i]);
            return fields;
        });
    }
    template <class T, class Owner>
    OptionsClass& option(const char* name, T Owner::*member) {
        bind(name, member);
        names_->emplace_back(name);
        return *this;
    }
    template <class T, class Owner>
    OptionsClass& field(const char* name, T Owner::*member) {
        bind(name, member);
        return *this;
    }
    /// A keyword whose Python value is not a field's own (a flag that sets a choice): bound
    /// through getter and setter, recorded in `_fields` as `option` records a field.
    template <class Getter, class Setter>
    OptionsClass& property(const char* name, Getter&& getter, Setter&& setter) {
        class_.def_property(name, std::forward<Getter>(getter), std::forward<Setter>(setter));
        names_->emplace_back(name);
        return *this;
    }
    OptionsClass& inherited(const char* name) {
        names_->emplace_back(name);
        return *this;
    }
    /// A method of the class (py::class_::def).
    template <class... Arguments>
    OptionsClass& def(Arguments&&... arguments) {
        class_.def(std::forward<Arguments>(arguments)...);
        return *this;
    }

private:
    /// A field as a Python attribute; a choice (an enum with a name table, nocdyn/choice.hpp) as
    /// its name, a name not in the table refused with OptionError naming the field.
    template <class T, class Owner>
    void bind(const char* name, T Owner::*member) {
        if constexpr (std::is_enum_v<T>) {
            class_.def_property(
                name, [member](const Options& o) { return std::string(nameOf(o.*member)); },
                [member, name](Options& o, const std::string& word) {
                    const std::optional<T> value = choiceNamed<T>(word);
                    if (!value) {
                        throw app::OptionError(name,
                                               "expected " + choiceList<T>() + ", got '" + text::printable(word) + "'");
                    }
                    o.*member = *value;
                });
        } else {
            class_.def_readwrite(name, member);
        }
    }

    py::class_<Options, Bases...> class_;
    std::shared_ptr<std::vector<std::string>> names_;  // shared with the _fields getter
};

/// Runs job(observer) with the GIL released, then issues its warnings.
template <class Job>
auto runJob(const py::object& progress, Job&& job) {
    PythonObserver observer(progress);
    auto result = [&] {
        const py::gil_scoped_release release;
        return job(observer);
    }();
    observer.issueWarnings();
    return result;
}

/// A (rows, columns) float64 array owning the collector's values (no copy).
py::array_t<double> tableArray(app::TableCollector& table);

/// An io::Table's rows as a (rows, columns) float64 array.
py::array_t<double> rowsArray(const io::Table& table);

/// Most memory a table held for Python takes [bytes] (every sample is held; the command line
/// streams them to a file).
inline constexpr double kMaxHeldBytes = 8e8;

/// The inverse dynamics of a spatial robot along options.trajectory (a spatial trajectory file),
/// sampled as options says: (columns, (rows, columns) array). What would hold more than
/// kMaxHeldBytes is refused before any sample is computed (spatial.cpp).
py::tuple runSpatialInverseDynamics(const spatial::Model& model, const app::InverseDynamicsOptions& options,
                                    const py::object& progress);

/// Adds the options types, _run_<command> functions and helpers to the compiled module.
void bindApplication(py::module_& m);

/// forward-kinematics, simulate, control, frequency-response (app_bindings_sim.cpp).
void bindSimulation(py::module_& m);

/// shake, identify, excite, animate (app_bindings_purpose.cpp).
void bindPurpose(py::module_& m);

/// reproduce, and validate when both engines are built in (app_bindings_report.cpp).
void bindReport(py::module_& m);

/// envelope, workspace, loads, regressor, convert, design (app_bindings_analysis.cpp).
void bindAnalysis(py::module_& m);

}  // namespace nocdyn::python
