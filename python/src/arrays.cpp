// NumPy arrays to and from the library's types (arrays.hpp).
#include "arrays.hpp"

#include <string>

#include "nocdyn/error.hpp"

namespace nocdyn::python {

ArrayView viewOf(const py::array& a, const char* name, py::ssize_t rows, py::ssize_t cols, bool writeable) {
    if (!a.dtype().is(py::dtype::of<double>())) {
        throw py::type_error(std::string(name) + ": expected an array of float64, got dtype " +
                             std::string(py::str(a.dtype())) + " (convert it with numpy.asarray(x, dtype=float))");
    }
    if (a.ndim() != 2 || (rows >= 0 && a.shape(0) != rows) || a.shape(1) != cols) {
        std::string shape = "(";
        for (py::ssize_t i = 0; i < a.ndim(); ++i) {
            if (i > 0) shape += ", ";
            shape += std::to_string(a.shape(i));
        }
        shape += a.ndim() == 1 ? ",)" : ")";
        throw Error(std::string(name) + ": expected shape (" + (rows >= 0 ? std::to_string(rows) : std::string("N")) +
                    ", " + std::to_string(cols) + "), got " + shape);
    }
    if (writeable && !a.writeable()) throw Error(std::string(name) + ": the output array is read-only");
    constexpr auto item = static_cast<py::ssize_t>(sizeof(double));
    const py::ssize_t s0 = a.strides(0), s1 = a.strides(1);
    if (s0 < 0 || s1 < 0 || s0 % item != 0 || s1 % item != 0) {
        throw Error(std::string(name) + ": strides (" + std::to_string(s0) + ", " + std::to_string(s1) +
                    ") bytes are not supported (negative or not whole elements); pass numpy.ascontiguousarray(" + name +
                    ")");
    }
    ArrayView v;
    v.data = static_cast<double*>(const_cast<void*>(a.data()));
    v.rows = a.shape(0);
    v.cols = a.shape(1);
    v.row_stride = s0 / item;
    v.col_stride = s1 / item;
    return v;
}

Eigen::Vector3d vector3(const py::handle& x, const char* name) {
    const auto a = py::array_t<double, py::array::forcecast>::ensure(x);
    if (!a || a.ndim() != 1 || a.shape(0) != 3) throw Error(std::string(name) + ": expected 3 values [x, y, theta]");
    return corePose(Vector3(a.at(0), a.at(1), a.at(2)));
}

py::array_t<double> poseArray(const Eigen::Vector3d& v) {
    const Vector3 user = userPose(v);
    py::array_t<double> a(3);
    for (int c = 0; c < 3; ++c) a.mutable_at(c) = user(c);
    return a;
}

py::array_t<double> taskPoseArray(const Model& model, const Eigen::Vector3d& v) {
    if (model.task_dimension == 3) return poseArray(v);
    const Vector3 user = userPose(v);
    py::array_t<double> a(2);
    a.mutable_at(0) = user(0);
    a.mutable_at(1) = user(1);
    return a;
}

Eigen::MatrixXd inPythonOrder(const Eigen::MatrixXd& m, bool rows, bool cols) {
    const auto at = [](Eigen::Index i) { return i / 3 * 3 + twistIndex(static_cast<int>(i % 3)); };
    Eigen::MatrixXd out(m.rows(), m.cols());
    for (Eigen::Index r = 0; r < m.rows(); ++r)
        for (Eigen::Index c = 0; c < m.cols(); ++c) out(r, c) = m(rows ? at(r) : r, cols ? at(c) : c);
    return out;
}

ActuatorVector actuatorVector(const Model& model, const py::handle& x, const char* name) {
    const auto a = py::array_t<double, py::array::forcecast>::ensure(x);
    if (!a || a.ndim() != 1 || a.shape(0) != model.actuators) {
        throw Error(std::string(name) + ": expected " + std::to_string(model.actuators) + " values (one per actuator)");
    }
    ActuatorVector v(model.actuators);
    for (int i = 0; i < model.actuators; ++i) v(i) = a.at(i);
    return v;
}

py::array_t<double> toArray(const ActuatorVector& v) {
    py::array_t<double> a(v.size());
    for (Eigen::Index i = 0; i < v.size(); ++i) a.mutable_at(i) = v(i);
    return a;
}

py::array_t<double> toArray(const Eigen::Vector3d& v) {
    py::array_t<double> a(3);
    for (int i = 0; i < 3; ++i) a.mutable_at(i) = v(i);
    return a;
}

py::array_t<double> toArray(const Matrix3& m) {
    py::array_t<double> a({3, 3});
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) a.mutable_at(i, j) = m(i, j);
    return a;
}

py::array_t<double> toArray(const std::vector<double>& v) {
    py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) a.mutable_at(static_cast<py::ssize_t>(i)) = v[i];
    return a;
}

RowArray toArray(const Eigen::MatrixXd& m) {
    RowArray a({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
    auto o = a.mutable_unchecked<2>();
    for (Eigen::Index r = 0; r < m.rows(); ++r)
        for (Eigen::Index c = 0; c < m.cols(); ++c) o(r, c) = m(r, c);
    return a;
}

RowMajorOutput::RowMajorOutput(py::ssize_t rows, py::ssize_t actuators, py::ssize_t per_actuator)
    : array(per_actuator == 1 ? std::vector<py::ssize_t>{rows, actuators}
                              : std::vector<py::ssize_t>{rows, actuators, per_actuator}),
      map(array.mutable_data(), rows, actuators * per_actuator,
          Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, actuators * per_actuator)) {}

}  // namespace nocdyn::python
