// Robot's stiffness and natural frequencies at a pose (analysis/stiffness.hpp): the Cartesian
// stiffness K of the virtual joint method, the lumped modes (K v = w^2 M v) and, with elastic
// bodies, the elastodynamic modes, every pose-indexed array in the reported order x, y, theta.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <utility>
#include <vector>

#include "arrays.hpp"
#include "expose.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/error.hpp"

namespace nocdyn::python {

namespace {

/// A two-DOF robot's (motion: translation) K_t, M_t and lumped modes over x, y at p = [x, y]
/// (TaskModes: theta moves no body and loads no limb). Its elastic bodies are refused.
py::dict taskStiffnessAt(const Robot& robot, const py::handle& p, bool elastodynamic) {
    const Model& model = *robot.model;
    const auto a = py::array_t<double, py::array::forcecast>::ensure(p);
    if (!a || a.ndim() != 1 || a.shape(0) != 2) throw Error("p: expected 2 values [x, y] for a two-DOF robot");
    const StiffnessModel compliance(model);
    if (!compliance.any) throw Error("the robot file declares no compliance (a joint's stiffness): the robot is rigid");
    if (elastodynamic || compliance.any_elastic) {
        throw Error(
            "the elastic bodies and elastodynamic modes of a two-DOF robot (motion: translation) are not "
            "modelled yet");
    }
    Data data(model);
    StiffnessData K;
    LumpedModes lumped;
    const Pose p3(model.home(0), a.at(0), a.at(1));
    if (const Status status = stiffnessAndModes(model, compliance, data, p3, K, lumped); !status) {
        throw Error(describe(status, model));
    }
    TaskModes modes;
    taskModes(model, data, K, lumped, modes);
    if (!(modes.K.allFinite() && modes.frequency.allFinite() && modes.shape.allFinite())) {
        throw Error("the stiffness or the natural frequencies are not finite at this pose");
    }
    if (const std::string w = contrastWarning(K); !w.empty()) {
        if (PyErr_WarnEx(PyExc_RuntimeWarning, w.c_str(), 3) != 0) throw py::error_already_set();
    }
    py::dict out;
    py::list coordinates;
    for (int r = 0; r < 2; ++r) coordinates.append(coordinateLabel(r));
    out["coordinates"] = coordinates;
    out["matrix"] = toArray(Eigen::MatrixXd(modes.K));
    out["free_directions"] = py::list();  // theta's is no direction of the task
    out["frequencies"] = toArray(std::vector<double>(modes.frequency.begin(), modes.frequency.end()));
    out["mode_shapes"] = toArray(Eigen::MatrixXd(modes.shape));
    out["mass_matrix"] = toArray(Eigen::MatrixXd(modes.M));
    out["lumped_holds"] = true;
    return out;
}

/// K, the lumped modes and (when `elastodynamic`) the elastodynamic modes at pose p, every
/// pose-indexed array in kReportedCoordinates' order. Warns (RuntimeWarning) when
/// K's contrast costs digits and, when `frequencies` are asked of a robot with elastic bodies,
/// when the lumped model does not hold at p.
/// `lumped_asked`: the lumped model was asked for by name, so the mismatch warning says the
/// elastodynamic frequencies are the ones to use rather than that they are used. The dict's
/// "lumped_holds" is false where the lumped model does not hold (then the elastodynamic keys are
/// there, the default answer's).
py::dict stiffnessAt(const Robot& robot, const py::handle& p, bool elastodynamic, bool frequencies, bool lumped_asked) {
    const Model& model = *robot.model;
    if (model.task_dimension == 2) return taskStiffnessAt(robot, p, elastodynamic);
    const Pose p3 = vector3(p, "p");
    const StiffnessModel compliance(model);
    if (!compliance.any) {
        throw Error(
            "the robot file declares no compliance (a joint's stiffness or an elastic body): the robot is "
            "rigid");
    }
    Data data(model);
    StiffnessData K;
    LumpedModes modes;
    if (const Status status = stiffnessAndModes(model, compliance, data, p3, K, modes); !status) {
        throw Error(describe(status, model));
    }
    if (!(K.K.allFinite() && modes.frequency.allFinite() && modes.shape.allFinite())) {
        throw Error("the stiffness or the natural frequencies are not finite at this pose");
    }
    std::vector<std::string> warnings;
    if (std::string w = contrastWarning(K); !w.empty()) warnings.push_back(std::move(w));
    // with elastic bodies the elastodynamic model is computed too: it says whether the lumped
    // one holds at this pose
    ElastodynamicModes e;
    const bool elastic = elastodynamic || (frequencies && compliance.any_elastic);
    if (elastic) {
        if (const Status status = elastodynamicModes(model, compliance, data, e); !status) {
            throw Error(describe(status, model));
        }
        if (!(e.frequency.allFinite() && e.platform_shape.allFinite())) {
            throw Error("the elastodynamic frequencies are not finite at this pose");
        }
        if (std::string w = lumpedMismatchWarning(modes, e, !lumped_asked); !w.empty())
            warnings.push_back(std::move(w));
        if (elastodynamic || (!lumped_asked && !lumpedHolds(modes, e))) {
            if (std::string w = elastodynamicPrecisionWarning(e); !w.empty()) warnings.push_back(std::move(w));
        }
    }
    for (const std::string& w : warnings) {
        if (PyErr_WarnEx(PyExc_RuntimeWarning, w.c_str(), 3) != 0) throw py::error_already_set();
    }
    py::dict out;
    py::list coordinates, free;
    for (int r = 0; r < 3; ++r) coordinates.append(coordinateLabel(r));
    for (int i = 0; i < K.free_directions; ++i) {
        const Vector3 v = K.free.col(i);
        py::dict d;
        d["direction"] = toArray(reported(v));
        d["description"] = describeDirection(v);
        free.append(d);
    }
    out["coordinates"] = coordinates;
    out["matrix"] = toArray(reported(K.K));
    out["free_directions"] = free;
    out["frequencies"] = toArray(modes.frequency);
    // the shapes' rows are pose coordinates, their columns the modes (ascending): rows only
    Matrix3 shapes;
    for (int i = 0; i < 3; ++i) shapes.col(i) = reported(Vector3(modes.shape.col(i)));
    out["mode_shapes"] = toArray(shapes);
    out["mass_matrix"] = toArray(reported(modes.M));
    out["lumped_holds"] = !elastic || lumpedHolds(modes, e);
    if (elastic) {
        py::array_t<double> f(e.frequency.size());
        for (Eigen::Index i = 0; i < e.frequency.size(); ++i) f.mutable_at(i) = e.frequency(i);
        py::array_t<double> shapes({py::ssize_t{3}, static_cast<py::ssize_t>(e.dofs)});
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < e.dofs; ++c) {
                shapes.mutable_at(r, c) = e.platform_shape(kReportedCoordinates[static_cast<std::size_t>(r)].index, c);
            }
        }
        out["elastodynamic_frequencies"] = f;
        out["elastodynamic_platform_shapes"] = shapes;
    }
    return out;
}

}  // namespace

void exposeStiffness(py::module_& m) {
    py::class_<Robot>(m.attr("Robot"))
        .def("_stiffness", &stiffnessAt, py::arg("p"), py::arg("elastodynamic") = false, py::arg("frequencies") = false,
             py::arg("lumped_asked") = false);
}

}  // namespace nocdyn::python
