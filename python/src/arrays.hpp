// NumPy arrays to and from the library's types for the compiled module: views of float64 arrays
// of any memory order, poses in the user's order [x, y, theta] (the core keeps its twist order
// [theta, x, y]: the order changes here, at the boundary), and vectors and matrices as new arrays.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

#include "nocdyn/batch.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/pose_order.hpp"

namespace py = pybind11;

namespace nocdyn::python {

using StridedMap = Eigen::Map<Eigen::ArrayXXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
using ConstStridedMap = Eigen::Map<const Eigen::ArrayXXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
using RowArray = py::array_t<double, py::array::c_style>;
/// An input read through data(): pybind11 copies any other memory order or dtype into a
/// C-ordered float64 array (a strided view read as contiguous would give wrong numbers).
using ContiguousInput = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The robot: a validated Model, shared by the Python objects that use it, and the Data of the
/// per-sample calls (used only while the GIL is held, so by one thread at a time).
struct Robot {
    std::shared_ptr<const Model> model;
    std::shared_ptr<Data> data;
    explicit Robot(RobotDescription description)
        : model(std::make_shared<const Model>(std::move(description))), data(std::make_shared<Data>(*model)) {}
};

/// A float64 array of shape (rows, cols) (rows = -1: any), viewed in place whatever its strides
/// (C- or F-ordered, or a strided view of either).
struct ArrayView {
    double* data = nullptr;
    Eigen::Index rows = 0, cols = 0;
    Eigen::Index row_stride = 0, col_stride = 0;  // in elements
};

/// Throws TypeError for another dtype than float64 and nocdyn::Error for another shape, a
/// read-only array where `writeable`, or strides that are negative or not whole elements.
ArrayView viewOf(const py::array& a, const char* name, py::ssize_t rows, py::ssize_t cols, bool writeable);

// Eigen's Stride is (outer, inner): for its column-major ArrayXXd, outer runs across columns
// and inner down a column (from one row to the next).
inline ConstStridedMap constMap(const ArrayView& v) {
    return {v.data, v.rows, v.cols, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(v.col_stride, v.row_stride)};
}
inline StridedMap map(const ArrayView& v) {
    return {v.data, v.rows, v.cols, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(v.col_stride, v.row_stride)};
}

// The vocabulary of every array Python passes or receives: a pose p, its rates dp, ddp and
// every row or column that runs over pose coordinates in the tables' order [x, y, theta]; the
// batches gather it by PoseColumns::x_y_theta.
inline constexpr PoseColumns kPythonPose = PoseColumns::x_y_theta;

/// The core's coordinate (0 theta, 1 x, 2 y) at Python's index c (0 x, 1 y, 2 theta), as
/// pose_order.hpp's userPose and corePose map them.
constexpr int twistIndex(int c) { return (c + 1) % 3; }
static_assert(poseColumn(kPythonPose, twistIndex(0)) == 0 && poseColumn(kPythonPose, twistIndex(2)) == 2);

/// Row k of an (N, 3) map in Python's pose order, in the core's twist order.
inline Vector3 coreRow(const ConstStridedMap& a, Eigen::Index k) {
    Vector3 v;
    for (int i = 0; i < 3; ++i) v(i) = a(k, poseColumn(kPythonPose, i));
    return v;
}

/// A pose (or its rate) from anything NumPy reads as three floats [x, y, theta], in the core's
/// twist order.
Eigen::Vector3d vector3(const py::handle& x, const char* name);

/// A pose (or its rate) of the core as Python's [x, y, theta].
py::array_t<double> poseArray(const Eigen::Vector3d& v);
/// A pose (or its rate) of the core in the robot's task coordinates: [x, y, theta], or [x, y]
/// for a two-DOF robot (motion: translation, E^T p: theta is no coordinate of it).
py::array_t<double> taskPoseArray(const Model& model, const Eigen::Vector3d& v);

/// m with its rows (`rows`) and/or columns (`cols`) that run over pose coordinates, in blocks
/// of three (p, then dp), put in Python's order.
Eigen::MatrixXd inPythonOrder(const Eigen::MatrixXd& m, bool rows, bool cols);

/// n values, one per actuator, from anything NumPy reads as floats.
ActuatorVector actuatorVector(const Model& model, const py::handle& x, const char* name);

py::array_t<double> toArray(const ActuatorVector& v);
py::array_t<double> toArray(const Eigen::Vector3d& v);
py::array_t<double> toArray(const Matrix3& m);
py::array_t<double> toArray(const std::vector<double>& v);
/// A matrix as a new C-ordered (rows, cols) array.
RowArray toArray(const Eigen::MatrixXd& m);

/// A new C-ordered (N, n) array (per_actuator 1) or (N, n, per_actuator) one, and the N x
/// (n per_actuator) map of it the batches write, row k = sample k.
struct RowMajorOutput {
    RowArray array;
    StridedMap map;
    RowMajorOutput(py::ssize_t rows, py::ssize_t actuators, py::ssize_t per_actuator);
};

/// The N x 3 inputs p, dp, ddp of a batch read in place, whatever their memory order.
struct SampleMaps {
    py::ssize_t rows;
    ConstStridedMap p, dp, ddp;
    SampleMaps(const py::array& p_, const py::array& dp_, const py::array& ddp_)
        : SampleMaps(viewOf(p_, "p", -1, 3, false), dp_, ddp_) {}

private:
    SampleMaps(const ArrayView& vp, const py::array& dp_, const py::array& ddp_)
        : rows(vp.rows),
          p(constMap(vp)),
          dp(constMap(viewOf(dp_, "dp", vp.rows, 3, false))),
          ddp(constMap(viewOf(ddp_, "ddp", vp.rows, 3, false))) {}
};

}  // namespace nocdyn::python
