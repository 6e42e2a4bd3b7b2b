// The compiled part of the Python package `nocdyn` (pybind11): the general model (model.hpp)
// and its algorithms over NumPy arrays. The Pythonic layer and the docstrings users read are in
// ../nocdyn/__init__.py; this file converts arrays, checks them, releases the GIL around long
// computations, and turns nocdyn::Error (and failing Status values) into nocdyn.Error with the
// CLI's messages.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <ctime>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app_bindings.hpp"
#include "cli_main.hpp"
#include "nocdyn/batch.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/analysis/linearization.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "nocdyn/drawing.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/analysis/envelope.hpp"
#include "nocdyn/analysis/stiffness.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/sim/forward_dynamics.hpp"
#include "nocdyn/sim/control.hpp"
#include "nocdyn/sim/identification.hpp"
#include "nocdyn/tables/calibration.hpp"
#include "nocdyn/io/examples.hpp"
#include "nocdyn/io/layouts.hpp"
#include "nocdyn/io/robot_file.hpp"
#include "nocdyn/io/trajectory_yaml.hpp"
#include "nocdyn/kinematics.hpp"
#include "nocdyn/model.hpp"
#include "nocdyn/pose_order.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/text.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/trajectory.hpp"

namespace py = pybind11;

namespace nocdyn::python {

namespace {

using StridedMap = Eigen::Map<Eigen::ArrayXXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
using ConstStridedMap = Eigen::Map<const Eigen::ArrayXXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
using RowArray = py::array_t<double, py::array::c_style>;
/// An input read through data(): pybind11 copies any other memory order or dtype into a
/// C-ordered float64 array (a strided view read as contiguous would give wrong numbers).
using ContiguousInput = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A float64 array of shape (rows, cols) (rows = -1: any), viewed in place whatever its strides
/// (C- or F-ordered, or a strided view of either). Throws TypeError for another dtype and
/// nocdyn::Error for another shape, or strides that are negative or not whole elements.
struct ArrayView {
    double* data = nullptr;
    Eigen::Index rows = 0, cols = 0;
    Eigen::Index row_stride = 0, col_stride = 0;  // in elements
};

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

// Eigen's Stride is (outer, inner): for its column-major ArrayXXd, outer runs across columns
// and inner down a column (from one row to the next).
ConstStridedMap constMap(const ArrayView& v) {
    return {v.data, v.rows, v.cols, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(v.col_stride, v.row_stride)};
}
StridedMap map(const ArrayView& v) {
    return {v.data, v.rows, v.cols, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(v.col_stride, v.row_stride)};
}

// The vocabulary of every array Python passes or receives: a pose p, its rates dp, ddp and
// every row or column that runs over pose coordinates in the tables' order [x, y, theta]. The
// core keeps its twist order [theta, x, y]; the order changes here, at the boundary, and in the
// batches' gathers (PoseColumns::x_y_theta).
constexpr PoseColumns kPythonPose = PoseColumns::x_y_theta;

/// The core's coordinate (0 theta, 1 x, 2 y) at Python's index c (0 x, 1 y, 2 theta), as
/// pose_order.hpp's userPose and corePose map them.
constexpr int twistIndex(int c) { return (c + 1) % 3; }
static_assert(poseColumn(kPythonPose, twistIndex(0)) == 0 && poseColumn(kPythonPose, twistIndex(2)) == 2);

/// A pose (or its rate) from anything NumPy reads as three floats [x, y, theta], in the core's
/// twist order.
Eigen::Vector3d vector3(const py::handle& x, const char* name) {
    const auto a = py::array_t<double, py::array::forcecast>::ensure(x);
    if (!a || a.ndim() != 1 || a.shape(0) != 3) throw Error(std::string(name) + ": expected 3 values [x, y, theta]");
    return corePose(Vector3(a.at(0), a.at(1), a.at(2)));
}

/// A pose (or its rate) of the core as Python's [x, y, theta].
py::array_t<double> poseArray(const Eigen::Vector3d& v) {
    const Vector3 user = userPose(v);
    py::array_t<double> a(3);
    for (int c = 0; c < 3; ++c) a.mutable_at(c) = user(c);
    return a;
}

/// m with its rows (`rows`) and/or columns (`cols`) that run over pose coordinates, in blocks
/// of three (p, then dp), put in Python's order.
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

/// The robot: a validated Model, shared by the Python objects that use it, and the Data of the
/// per-sample calls (used only while the GIL is held, so by one thread at a time).
struct Robot {
    std::shared_ptr<const Model> model;
    std::shared_ptr<Data> data;
    explicit Robot(RobotDescription description)
        : model(std::make_shared<const Model>(std::move(description))), data(std::make_shared<Data>(*model)) {}
};

/// CPU time of the calling thread [s] (the batch runs on it: wall time would count the
/// other processes of a shared machine).
double threadCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// --- inverse dynamics ---------------------------------------------------------------

/// The command line's checks of a computed sample (analysis/sampling.cpp, `nocdyn
/// inverse-dynamics`): every joint's range and velocity limits, then every actuator's effort.
Status sampleLimits(const Model& model, const Data& data) {
    if (const Status s = checkJointLimits(model, data); !s) return s;
    return checkEffort(model, data);
}

/// Whether every joint with a range or velocity limit is actuated: then u and du (the actuated
/// joints' q and rate) are all that checkJointLimits reads that can fail.
bool limitsOnActuatedJointsOnly(const Model& model) {
    for (int j = 0; j < model.limbs; ++j) {
        const LimbModel& limb = model.limb[static_cast<std::size_t>(j)];
        for (std::size_t k = 0; k < 3; ++k) {
            const JointLimits& lim = limb.limits[k];
            if (limb.actuator[k] < 0 && !(lim.lower == -INFINITY && lim.upper == INFINITY && lim.velocity == INFINITY))
                return false;
        }
    }
    return true;
}

py::tuple inverseDynamicsSample(const Robot& robot, const py::handle& p, const py::handle& dp, const py::handle& ddp,
                                bool matrices, bool check_limits, bool check) {
    const Model& model = *robot.model;
    const Pose p3 = vector3(p, "p");
    const Twist dp3 = vector3(dp, "dp"), ddp3 = vector3(ddp, "ddp");
    Data data(model);
    // the limits of passive joints need every joint's q and rate: the full path
    const bool actuated_only = limitsOnActuatedJointsOnly(model);
    const bool full = matrices || (check_limits && !actuated_only);
    const Status status =
        full ? inverseDynamics(model, data, p3, dp3, ddp3) : inverseDynamicsFast(model, data, p3, dp3, ddp3);
    if (!status) throw Error(describe(status, model));
    if (check_limits) {
        const Status limits =
            actuated_only ? checkActuatorLimits(model, data.u, data.du, data.tau) : sampleLimits(model, data);
        if (!limits) throw Error(describe(limits, model));
    }
    // finite input whose results overflow (huge rates or accelerations): an error, as the
    // batch's failed sample (check=False returns them)
    if (check) {
        const int n = model.actuators;
        bool finite = data.u.head(n).allFinite() && data.du.head(n).allFinite() && data.ddu.head(n).allFinite() &&
                      data.tau.head(n).allFinite();
        if (matrices) {
            finite = finite && data.I.allFinite() && data.C.allFinite();
            for (int i = 0; finite && i < model.bodies; ++i) finite = data.T[static_cast<std::size_t>(i)].allFinite();
        }
        if (!finite) throw Error("the inverse dynamics is not finite (the input is too large)");
    }
    if (!matrices) return py::make_tuple(toArray(data.u), toArray(data.du), toArray(data.ddu), toArray(data.tau));
    // the independent coordinates are the pose when redundant: I, C and T's columns then in
    // Python's pose order; T_i's rows are body i's twist, [v_x, v_y, omega] in that order too
    const bool pose_coordinates = model.coordinates == Coordinates::platform;
    py::array_t<double> T({static_cast<py::ssize_t>(model.bodies), py::ssize_t{3}, py::ssize_t{3}});
    for (int i = 0; i < model.bodies; ++i) {
        const Eigen::MatrixXd Ti = inPythonOrder(data.T[static_cast<std::size_t>(i)], true, pose_coordinates);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) T.mutable_at(i, r, c) = Ti(r, c);
    }
    const Matrix3 I = inPythonOrder(data.I, pose_coordinates, pose_coordinates);
    const Matrix3 C = inPythonOrder(data.C, pose_coordinates, pose_coordinates);
    return py::make_tuple(toArray(data.u), toArray(data.du), toArray(data.ddu), toArray(data.tau), toArray(I),
                          toArray(C), T);
}

/// The first sample of N, computed by a batch, beyond a limit sampleLimits checks, and that
/// Status (index -1: none; a failed sample, NaN, is skipped), by the full path at each sample:
/// for a model with a limited passive joint (the batch's own check sees only the actuated ones).
std::pair<Eigen::Index, Status> passiveLimits(const Model& model, const ConstStridedMap& p, const ConstStridedMap& dp,
                                              const ConstStridedMap& ddp, const ConstStridedMap& tau) {
    Data data(model);
    const auto row = [](const ConstStridedMap& a, Eigen::Index k) {
        Vector3 v;
        for (int i = 0; i < 3; ++i) v(i) = a(k, poseColumn(kPythonPose, i));
        return v;
    };
    for (Eigen::Index k = 0; k < p.rows(); ++k) {
        if (std::isnan(tau(k, 0)) || !inverseDynamics(model, data, row(p, k), row(dp, k), row(ddp, k))) continue;
        if (const Status s = sampleLimits(model, data); !s) return {k, s};
    }
    return {-1, Status{}};
}

/// A batch over rows [0, n) in slices of 65536 rows, the GIL released over each and taken back
/// between them to look for Ctrl-C (a long batch stops within a slice, tens of milliseconds).
/// Each row is computed alone, so the rows are those of one call; the outcome is combineChunks'
/// of the slices, their sample indices made absolute. run(begin, rows) runs one slice.
template <class Run>
BatchResult inSlices(Eigen::Index n, Run&& run) {
    constexpr Eigen::Index kSliceRows = Eigen::Index{1} << 16;
    std::vector<BatchResult> parts;
    Eigen::Index begin = 0;
    do {
        const Eigen::Index rows = std::min(kSliceRows, n - begin);
        BatchResult r;
        {
            const py::gil_scoped_release release;
            r = run(begin, rows);
        }
        if (r.first_failure != BatchResult::npos) r.first_failure += begin;
        if (r.first_beyond_limits != BatchResult::npos) r.first_beyond_limits += begin;
        parts.push_back(r);
        begin += rows;
        if (begin < n && PyErr_CheckSignals() != 0) throw py::error_already_set();
    } while (begin < n);
    return combineChunks(parts);
}

/// The batch over arrays viewed in place, the GIL released while it runs. Returns
/// (failed, first_failure, message of the first failure or "").
py::tuple inverseDynamicsBatchArrays(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp,
                                     const py::array& u, const py::array& du, const py::array& ddu,
                                     const py::array& tau, unsigned threads, bool check_limits) {
    const Model& model = *robot.model;
    const ArrayView vp = viewOf(p, "p", -1, 3, false);
    const py::ssize_t n = vp.rows;
    const ArrayView vdp = viewOf(dp, "dp", n, 3, false), vddp = viewOf(ddp, "ddp", n, 3, false);
    const ArrayView vu = viewOf(u, "u", n, model.actuators, true), vdu = viewOf(du, "du", n, model.actuators, true);
    const ArrayView vddu = viewOf(ddu, "ddu", n, model.actuators, true),
                    vtau = viewOf(tau, "tau", n, model.actuators, true);
    if (vu.col_stride != vdu.col_stride || vu.col_stride != vddu.col_stride || vu.col_stride != vtau.col_stride) {
        throw Error("out: u, du, ddu and tau must have the same memory order (all C- or all F-ordered)");
    }
    std::pair<Eigen::Index, Status> limits{-1, Status{}};
    // limits of actuated joints only: checked inside the batch, on the values in registers
    const bool actuated_only = limitsOnActuatedJointsOnly(model);
    const ConstStridedMap mp = constMap(vp), mdp = constMap(vdp), mddp = constMap(vddp);
    StridedMap mu = map(vu), mdu = map(vdu), mddu = map(vddu), mtau = map(vtau);
    const BatchResult result = inSlices(n, [&](Eigen::Index begin, Eigen::Index rows) {
        auto u_rows = mu.middleRows(begin, rows), du_rows = mdu.middleRows(begin, rows);
        auto ddu_rows = mddu.middleRows(begin, rows), tau_rows = mtau.middleRows(begin, rows);
        return inverseDynamicsBatch(model, mp.middleRows(begin, rows), mdp.middleRows(begin, rows),
                                    mddp.middleRows(begin, rows), u_rows, du_rows, ddu_rows, tau_rows, threads,
                                    kPythonPose,
                                    check_limits && actuated_only ? ActuatorLimits::check : ActuatorLimits::ignore);
    });
    {
        const py::gil_scoped_release release;
        if (check_limits && actuated_only && result.first_beyond_limits != BatchResult::npos) {
            limits = {result.first_beyond_limits, result.limits};
        } else if (check_limits && !actuated_only) {
            limits = passiveLimits(model, constMap(vp), constMap(vdp), constMap(vddp), constMap(vtau));
        }
    }
    const std::string message = result.ok() ? std::string() : describe(result.status, model);
    return py::make_tuple(static_cast<std::int64_t>(result.failed),
                          result.ok() ? std::int64_t{-1} : static_cast<std::int64_t>(result.first_failure), message,
                          static_cast<std::int64_t>(limits.first),
                          limits.first < 0 ? std::string() : describe(limits.second, model));
}

/// The first of N samples (p, dp, ddp (N, 3)) beyond a limit sampleLimits checks, by the full
/// path: (index or -1, message). Samples out of reach or singular are skipped (the caller's
/// own computation reports them).
py::tuple limitsBatchArrays(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp) {
    const Model& model = *robot.model;
    const ArrayView vp = viewOf(p, "p", -1, 3, false);
    const ArrayView vdp = viewOf(dp, "dp", vp.rows, 3, false), vddp = viewOf(ddp, "ddp", vp.rows, 3, false);
    Eigen::Index first = -1;
    Status status;
    {
        const py::gil_scoped_release release;
        const ConstStridedMap mp = constMap(vp), mdp = constMap(vdp), mddp = constMap(vddp);
        Data data(model);
        for (Eigen::Index k = 0; k < vp.rows && first < 0; ++k) {
            Vector3 pk, dpk, ddpk;
            for (int i = 0; i < 3; ++i) {
                const int c = poseColumn(kPythonPose, i);
                pk(i) = mp(k, c), dpk(i) = mdp(k, c), ddpk(i) = mddp(k, c);
            }
            if (!inverseDynamics(model, data, pk, dpk, ddpk)) continue;
            if (status = sampleLimits(model, data); !status) first = k;
        }
    }
    return py::make_tuple(static_cast<std::int64_t>(first), first < 0 ? std::string() : describe(status, model));
}

/// A matrix as a new (rows, cols) array.
py::array_t<double> matrixToArray(const Eigen::MatrixXd& m) {
    py::array_t<double> a({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
    for (Eigen::Index i = 0; i < m.rows(); ++i)
        for (Eigen::Index j = 0; j < m.cols(); ++j) a.mutable_at(i, j) = m(i, j);
    return a;
}

/// An actuator x pose derivative as an (n, 3) array, its columns in Python's pose order.
py::array_t<double> poseColumns(const ActuatorPoseJacobian& m) { return matrixToArray(inPythonOrder(m, false, true)); }

/// d tau/d p, d tau/d dp, d tau/d ddp of one sample, each (n, 3).
py::tuple inverseDynamicsDerivativesSample(const Robot& robot, const py::handle& p, const py::handle& dp,
                                           const py::handle& ddp) {
    const Model& model = *robot.model;
    InverseDynamicsDerivatives d;
    const Status status =
        inverseDynamicsDerivatives(model, *robot.data, vector3(p, "p"), vector3(dp, "dp"), vector3(ddp, "ddp"), d);
    if (!status) throw Error(describe(status, model));
    return py::make_tuple(poseColumns(d.d_p), poseColumns(d.d_dp), poseColumns(d.d_ddp));
}

/// u, du, ddu, each (n,), and d u/d p, d du/d p, d du/d dp, d ddu/d p, d ddu/d dp, d ddu/d ddp,
/// each (n, 3), of one sample.
py::tuple actuatorDerivativesSample(const Robot& robot, const py::handle& p, const py::handle& dp,
                                    const py::handle& ddp) {
    const Model& model = *robot.model;
    ActuatorVariableDerivatives d;
    const Status status =
        actuatorVariableDerivatives(model, *robot.data, vector3(p, "p"), vector3(dp, "dp"), vector3(ddp, "ddp"), d);
    if (!status) throw Error(describe(status, model));
    return py::make_tuple(toArray(d.u), toArray(d.du), toArray(d.ddu), poseColumns(d.u_p), poseColumns(d.du_p),
                          poseColumns(d.du_dp), poseColumns(d.ddu_p), poseColumns(d.ddu_dp), poseColumns(d.ddu_ddp));
}

/// A new C-ordered (N, n) array (per_actuator 1) or (N, n, per_actuator) one, and the N x
/// (n per_actuator) map of it the batches write, row k = sample k.
struct RowMajorOutput {
    RowArray array;
    StridedMap map;
    RowMajorOutput(py::ssize_t rows, py::ssize_t actuators, py::ssize_t per_actuator)
        : array(per_actuator == 1 ? std::vector<py::ssize_t>{rows, actuators}
                                  : std::vector<py::ssize_t>{rows, actuators, per_actuator}),
          map(array.mutable_data(), rows, actuators * per_actuator,
              Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>(1, actuators * per_actuator)) {}
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

/// (failed, first_failure or -1, message of the first failure or "") of a batch.
py::tuple batchOutcome(const Model& model, const BatchResult& result) {
    const std::string message = result.ok() ? std::string() : describe(result.status, model);
    return py::make_tuple(static_cast<std::int64_t>(result.failed),
                          result.ok() ? std::int64_t{-1} : static_cast<std::int64_t>(result.first_failure), message);
}

/// The derivatives of N samples, each (N, n, 3), the GIL released while they run. Returns
/// (d_p, d_dp, d_ddp, failed, first_failure, message of the first failure or "").
py::tuple inverseDynamicsDerivativesBatchArrays(const Robot& robot, const py::array& p, const py::array& dp,
                                                const py::array& ddp, unsigned threads) {
    const Model& model = *robot.model;
    const SampleMaps in(p, dp, ddp);
    const py::ssize_t n = in.rows;
    const auto a = static_cast<py::ssize_t>(model.actuators);
    RowMajorOutput d_p(n, a, 3), d_dp(n, a, 3), d_ddp(n, a, 3);
    const BatchResult result = inSlices(n, [&](Eigen::Index begin, Eigen::Index rows) {
        auto a_rows = d_p.map.middleRows(begin, rows), b_rows = d_dp.map.middleRows(begin, rows);
        auto c_rows = d_ddp.map.middleRows(begin, rows);
        return inverseDynamicsDerivativesBatch(model, in.p.middleRows(begin, rows), in.dp.middleRows(begin, rows),
                                               in.ddp.middleRows(begin, rows), a_rows, b_rows, c_rows, threads,
                                               kPythonPose);
    });
    return py::make_tuple(d_p.array, d_dp.array, d_ddp.array) + batchOutcome(model, result);
}

/// The actuator variables' derivatives of N samples, the GIL released while they run: (u, du,
/// ddu (N, n) each, u_p, du_p, du_dp, ddu_p, ddu_dp, ddu_ddp (N, n, 3) each, failed,
/// first_failure, message of the first failure or "").
py::tuple actuatorDerivativesBatchArrays(const Robot& robot, const py::array& p, const py::array& dp,
                                         const py::array& ddp, unsigned threads) {
    const Model& model = *robot.model;
    const SampleMaps in(p, dp, ddp);
    const py::ssize_t n = in.rows;
    const auto a = static_cast<py::ssize_t>(model.actuators);
    RowMajorOutput u(n, a, 1), du(n, a, 1), ddu(n, a, 1);
    RowMajorOutput u_p(n, a, 3), du_p(n, a, 3), du_dp(n, a, 3), ddu_p(n, a, 3), ddu_dp(n, a, 3), ddu_ddp(n, a, 3);
    BatchResult result;
    {
        const py::gil_scoped_release release;
        result = actuatorVariableDerivativesBatch(
            model, in.p, in.dp, in.ddp,
            {u.map, du.map, ddu.map, u_p.map, du_p.map, du_dp.map, ddu_p.map, ddu_dp.map, ddu_ddp.map}, threads,
            kPythonPose);
    }
    return py::make_tuple(u.array, du.array, ddu.array, u_p.array, du_p.array, du_dp.array, ddu_p.array, ddu_dp.array,
                          ddu_ddp.array) +
           batchOutcome(model, result);
}

/// The linearised model at (p, dp, tau): (A, B, C, D, inputs, model), the output "acceleration"
/// or "actuators"; compliance "auto" (the lumped compliant model, linearizeCompliant, when the
/// robot file declares compliance), "rigid" or "lumped" as `nocdyn frequency-response
/// --compliance`; inputs: per column of B "tau" (a force) or "uc" (a commanded drive position);
/// model: "rigid" or "lumped".
py::tuple linearizeSample(const Robot& robot, const py::handle& p, const py::handle& dp, const py::handle& tau,
                          const std::string& output, const std::string& compliance) {
    const Model& model = *robot.model;
    if (output != "acceleration" && output != "actuators") {
        throw Error("output: expected 'acceleration' or 'actuators', got '" + output + "'");
    }
    if (compliance != "auto" && compliance != "rigid" && compliance != "lumped") {
        throw Error("compliance: expected 'auto', 'rigid' or 'lumped', got '" + compliance + "'");
    }
    const analysis::StiffnessModel stiffness(model);
    const bool lumped = compliance == "lumped" || (compliance == "auto" && stiffness.any);
    if (lumped && !stiffness.any) {
        throw Error("compliance: the robot file declares no joint or drive stiffness and no elastic link");
    }
    const LinearOutput kind =
        output == "acceleration" ? LinearOutput::platform_acceleration : LinearOutput::actuator_variables;
    const Pose p3 = vector3(p, "p");
    const Twist dp3 = vector3(dp, "dp");
    const ActuatorVector tau_n = actuatorVector(model, tau, "tau");
    StateSpace ss;
    const Status status = lumped ? linearizeCompliant(model, stiffness, *robot.data, p3, dp3, tau_n, kind, ss)
                                 : linearize(model, *robot.data, p3, dp3, tau_n, kind, ss);
    if (!status) throw Error(describe(status, model));
    if (!(ss.A.allFinite() && ss.B.allFinite() && ss.C.allFinite() && ss.D.allFinite())) {
        throw Error("the linearised model is not finite at this operating point (the input is too large)");
    }
    py::list inputs;
    for (const LinearInput input : ss.inputs) inputs.append(name(input));
    // the state [p; dp] and the output ddp in Python's pose order
    const bool pose_output = output == "acceleration";
    return py::make_tuple(
        matrixToArray(inPythonOrder(ss.A, true, true)), matrixToArray(inPythonOrder(ss.B, true, false)),
        matrixToArray(inPythonOrder(ss.C, pose_output, true)), matrixToArray(inPythonOrder(ss.D, pose_output, false)),
        py::tuple(inputs), lumped ? "lumped" : "rigid");
}

/// The joint reactions of N samples into `out`, (N, 9 limbs) (a view of the (N, limbs, 3, 3)
/// array), the GIL released while they run. Returns (failed, first_failure, message).
py::tuple reactionsBatchArrays(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp,
                               const py::array& out, unsigned threads) {
    const Model& model = *robot.model;
    const ArrayView vp = viewOf(p, "p", -1, 3, false);
    const py::ssize_t n = vp.rows;
    const ArrayView vdp = viewOf(dp, "dp", n, 3, false), vddp = viewOf(ddp, "ddp", n, 3, false);
    const ArrayView vout = viewOf(out, "out", n, 9 * model.limbs, true);
    const ConstStridedMap mp = constMap(vp), mdp = constMap(vdp), mddp = constMap(vddp);
    StridedMap mout = map(vout);
    const BatchResult result = inSlices(n, [&](Eigen::Index begin, Eigen::Index rows) {
        auto out_rows = mout.middleRows(begin, rows);
        return reactionsBatch(model, mp.middleRows(begin, rows), mdp.middleRows(begin, rows),
                              mddp.middleRows(begin, rows), out_rows, threads, kPythonPose);
    });
    const std::string message = result.ok() ? std::string() : describe(result.status, model);
    return py::make_tuple(static_cast<std::int64_t>(result.failed),
                          result.ok() ? std::int64_t{-1} : static_cast<std::int64_t>(result.first_failure), message);
}

/// The C++ batch over Eigen's own column-major arrays, timed from C++ (the reference the
/// Python batch is compared with in bench/python_batch.py): CPU seconds of the calling thread
/// per call, best of `repeat` after one untimed call (outputs allocated and touched once, as
/// with preallocated outputs).
double timeCppBatch(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp, int repeat) {
    const Model& model = *robot.model;
    const ArrayView vp = viewOf(p, "p", -1, 3, false);
    const Eigen::ArrayXXd P = constMap(vp), dP = constMap(viewOf(dp, "dp", vp.rows, 3, false)),
                          ddP = constMap(viewOf(ddp, "ddp", vp.rows, 3, false));
    Eigen::ArrayXXd u(P.rows(), model.actuators), du(u.rows(), u.cols()), ddu(u.rows(), u.cols()),
        tau(u.rows(), u.cols());
    const py::gil_scoped_release release;
    inverseDynamicsBatch(model, P, dP, ddP, u, du, ddu, tau, 1, kPythonPose);  // untimed: the outputs' pages mapped
    double best = INFINITY;
    for (int r = 0; r < repeat; ++r) {
        const double start = threadCpuSeconds();
        const BatchResult result = inverseDynamicsBatch(model, P, dP, ddP, u, du, ddu, tau, 1, kPythonPose);
        const double elapsed = threadCpuSeconds() - start;
        if (!result.ok()) throw Error(describe(result.status, model));
        best = std::min(best, elapsed);
    }
    return best;
}

// --- trajectories -----------------------------------------------------------------------

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

/// Most memory trajectory_dynamics holds [bytes].
constexpr double kMaxHeldBytes = 8e8;

/// The CLI's `inverse-dynamics`: sampleInverseDynamics at the grid of (duration, rate), with
/// the same checks and messages. Returns a dict of arrays named as the CSV's columns.
py::dict sampleTrajectory(const Robot& robot, const PoseTrajectory& trajectory, double rate,
                          std::optional<double> duration, bool allow_limits) {
    const Model& model = *robot.model;
    const double d = duration ? *duration : (trajectory.duration ? *trajectory.duration : 0.2);
    const SampleGrid grid = sampleGrid(d, rate);
    requireRateAboveNyquist(trajectory, grid.rate);
    const auto n = static_cast<py::ssize_t>(grid.count);
    const auto m = static_cast<py::ssize_t>(model.actuators);
    // every sample held: t, kinetic, p, dp, ddp, u, du, ddu, tau
    const double bytes = static_cast<double>(grid.count) * static_cast<double>(11 + 4 * m) * 8.0;
    if (bytes > kMaxHeldBytes) {
        throw Error(
            text::format("%.6g samples would hold %.3g GB in memory, more than the %.0f MB allowed: give a "
                         "shorter duration or a lower rate",
                         static_cast<double>(grid.count), bytes / 1e9, kMaxHeldBytes / 1e6));
    }
    py::array_t<double> t(n), kinetic(n);
    RowArray P({n, py::ssize_t{3}}), dP({n, py::ssize_t{3}}), ddP({n, py::ssize_t{3}});
    RowArray u({n, m}), du({n, m}), ddu({n, m}), tau({n, m});
    double* tt = t.mutable_data();
    double* kk = kinetic.mutable_data();
    double *pp = P.mutable_data(), *dpp = dP.mutable_data(), *ddpp = ddP.mutable_data();
    double *uu = u.mutable_data(), *duu = du.mutable_data(), *dduu = ddu.mutable_data(), *taup = tau.mutable_data();
    py::ssize_t k = 0;
    LimitSummary summary;
    {
        const py::gil_scoped_release release;
        summary =
            streamInverseDynamics(model, trajectory, grid, allow_limits ? LimitPolicy::record : LimitPolicy::error,
                                  [&](const InverseDynamicsSample& s) {
                                      tt[k] = s.t;
                                      kk[k] = s.kinetic;
                                      for (int i = 0; i < 3; ++i) {
                                          pp[3 * k + i] = s.p(twistIndex(i));
                                          dpp[3 * k + i] = s.dp(twistIndex(i));
                                          ddpp[3 * k + i] = s.ddp(twistIndex(i));
                                      }
                                      for (py::ssize_t i = 0; i < m; ++i) {
                                          uu[m * k + i] = s.u(i);
                                          duu[m * k + i] = s.du(i);
                                          dduu[m * k + i] = s.ddu(i);
                                          taup[m * k + i] = s.tau(i);
                                      }
                                      // Ctrl-C: every 65536 samples (a few ms), the GIL taken back
                                      if ((++k & 0xFFFF) == 0) {
                                          const py::gil_scoped_acquire acquire;
                                          if (PyErr_CheckSignals() != 0) throw py::error_already_set();
                                      }
                                  });
    }
    py::dict out;
    out["t"] = t;
    out["p"] = P;
    out["dp"] = dP;
    out["ddp"] = ddP;
    out["u"] = u;
    out["du"] = du;
    out["ddu"] = ddu;
    out["tau"] = tau;
    out["kinetic"] = kinetic;
    out["warnings"] = summary.limit_violations;
    return out;
}

// --- direct kinematics, forward dynamics, envelope ----------------------------------------

py::dict forwardKinematics(const Robot& robot, const py::handle& u, double tolerance) {
    const Model& model = *robot.model;
    const ActuatorVector uu = actuatorVector(model, u, "u");
    Data data(model);
    AssemblyModes modes;
    DirectKinematicsOptions options;
    options.tolerance = tolerance;
    const Status status = directKinematics(model, data, uu, modes, options);
    if (!status) throw Error(describe(status, model));
    py::list list;
    for (const AssemblyMode& mode : modes) {
        py::dict d;
        d["pose"] = poseArray(mode.p);
        std::vector<int> branch(mode.branch.begin(), mode.branch.begin() + model.limbs);
        d["branch"] = branch;
        d["working"] = mode.working;
        d["u_error"] = mode.u_error;
        d["condition"] = mode.condition;
        list.append(d);
    }
    py::dict out;
    out["modes"] = list;
    out["degenerate"] = modes.degenerate;
    out["truncated"] = modes.truncated;
    return out;
}

/// The state with actuator values u and rates du (None: at rest), by the library call the
/// command line's simulate uses (stateFromActuators).
py::dict stateFromActuatorValues(const Robot& robot, const py::handle& u, const py::handle& du, int assembly_mode) {
    const Model& model = *robot.model;
    const ActuatorVector uu = actuatorVector(model, u, "u");
    const ActuatorVector dd = du.is_none() ? ActuatorVector() : actuatorVector(model, du, "du");
    if (assembly_mode < 0) throw Error("assembly_mode: expected 0 (the nearest home) or a mode number from 1");
    Data data(model);
    ActuatorStart start;
    if (const Status status = stateFromActuators(model, data, uu, dd, assembly_mode, start); !status) {
        throw Error(describe(status, model));
    }
    py::dict out;
    out["p"] = poseArray(start.p);
    out["dp"] = poseArray(start.dp);
    out["mode"] = start.mode;
    out["working"] = start.working;
    out["modes"] = start.modes;
    return out;
}

Interpolation interpolationOf(const std::string& name) {
    if (name == "hold") return Interpolation::hold;
    if (name == "linear") return Interpolation::linear;
    if (name == "cubic") return Interpolation::cubic;
    throw Error("interpolation: '" + name + "' is not one of hold, linear, cubic");
}

/// Forward dynamics from (p0, dp0) under forces tau(times) (interpolated), the state read at
/// `t_out` (increasing, >= 0). Stops with nocdyn.Error "t = ... s: <reason>" on failure.
py::dict simulate(const Robot& robot, const py::handle& p0, const py::handle& dp0, const ContiguousInput& force_times,
                  const ContiguousInput& forces, const std::string& interpolation, const ContiguousInput& t_out,
                  double rtol, double atol, double max_step) {
    const Model& model = *robot.model;
    const int n = model.actuators;
    if (force_times.ndim() != 1 || forces.ndim() != 2 || forces.shape(0) != force_times.shape(0) ||
        forces.shape(1) != n) {
        throw Error("forces: expected shape (len(force_times), " + std::to_string(n) + ")");
    }
    if (t_out.ndim() != 1 || t_out.shape(0) < 1) throw Error("t: expected a non-empty one-dimensional array of times");
    std::vector<double> times(force_times.data(), force_times.data() + force_times.shape(0));
    std::vector<ActuatorVector> tau(times.size(), ActuatorVector(n));
    auto f = forces.unchecked<2>();
    for (std::size_t s = 0; s < times.size(); ++s)
        for (int i = 0; i < n; ++i) tau[s](i) = f(static_cast<py::ssize_t>(s), i);
    ForceSignal signal(std::move(times), tau, interpolationOf(interpolation), "forces");
    SimulatorOptions options;
    options.relative_tolerance = rtol;
    options.absolute_tolerance = atol;
    options.max_step = max_step;
    // Ctrl-C: every 1024 steps, the GIL taken back to look for a pending signal
    options.poll = [] {
        const py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    };
    Simulator simulator(model, options);
    const auto to = t_out.unchecked<1>();
    const py::ssize_t count = to.shape(0);
    for (py::ssize_t k = 0; k < count; ++k) {
        if (!std::isfinite(to(k)) || to(k) < 0.0 || (k > 0 && to(k) <= to(k - 1))) {
            throw Error("t: times must be finite, non-negative and increasing (t[" + std::to_string(k) + "])");
        }
    }
    if (const Status s = simulator.reset(vector3(p0, "p0"), vector3(dp0, "dp0"), 0.0); !s) {
        throw Error("t = 0 s: " + describe(s, model));
    }
    simulator.setForces(std::move(signal));
    const auto m = static_cast<py::ssize_t>(n);
    RowArray P({count, py::ssize_t{3}}), dP({count, py::ssize_t{3}}), U({count, m}), dU({count, m}), Tau({count, m});
    auto pp = P.mutable_unchecked<2>(), dpp = dP.mutable_unchecked<2>(), uu = U.mutable_unchecked<2>(),
         duu = dU.mutable_unchecked<2>(), tt = Tau.mutable_unchecked<2>();
    Status failure;
    {
        const py::gil_scoped_release release;
        for (py::ssize_t k = 0; k < count && failure.ok(); ++k) {
            failure = simulator.advance(to(k) - simulator.time());
            if (!failure) break;
            for (int i = 0; i < 3; ++i) {
                pp(k, i) = simulator.pose()(twistIndex(i));
                dpp(k, i) = simulator.poseRate()(twistIndex(i));
            }
            for (int i = 0; i < n; ++i) {
                uu(k, i) = simulator.u()(i);
                duu(k, i) = simulator.du()(i);
                tt(k, i) = simulator.tau()(i);
            }
        }
    }
    if (!failure) throw Error("t = " + std::to_string(simulator.time()) + " s: " + describe(failure, model));
    py::dict out;
    out["t"] = t_out;
    out["p"] = P;
    out["dp"] = dP;
    out["u"] = U;
    out["du"] = dU;
    out["tau"] = Tau;
    return out;
}

// --- stiffness and natural frequencies ----------------------------------------------

/// K, the lumped modes and (when `elastodynamic`) the elastodynamic modes at pose p, every
/// pose-indexed array in analysis::kReportedCoordinates' order. Warns (RuntimeWarning) when
/// K's contrast costs digits and, when `frequencies` are asked of a robot with elastic bodies,
/// when the lumped model does not hold at p.
/// `lumped_asked`: the lumped model was asked for by name, so the mismatch warning says the
/// elastodynamic frequencies are the ones to use rather than that they are used. The dict's
/// "lumped_holds" is false where the lumped model does not hold (then the elastodynamic keys are
/// there, the default answer's).
py::dict stiffnessAt(const Robot& robot, const py::handle& p, bool elastodynamic, bool frequencies, bool lumped_asked) {
    const Model& model = *robot.model;
    const Pose p3 = vector3(p, "p");
    const analysis::StiffnessModel compliance(model);
    if (!compliance.any) {
        throw Error(
            "the robot file declares no compliance (a joint's stiffness or an elastic body): the robot is "
            "rigid");
    }
    Data data(model);
    analysis::StiffnessData K;
    analysis::LumpedModes modes;
    if (const Status status = analysis::stiffnessAndModes(model, compliance, data, p3, K, modes); !status) {
        throw Error(describe(status, model));
    }
    if (!(K.K.allFinite() && modes.frequency.allFinite() && modes.shape.allFinite())) {
        throw Error("the stiffness or the natural frequencies are not finite at this pose");
    }
    std::vector<std::string> warnings;
    if (std::string w = analysis::contrastWarning(K); !w.empty()) warnings.push_back(std::move(w));
    // with elastic bodies the elastodynamic model is computed too: it says whether the lumped
    // one holds at this pose
    analysis::ElastodynamicModes e;
    const bool elastic = elastodynamic || (frequencies && compliance.any_elastic);
    if (elastic) {
        if (const Status status = analysis::elastodynamicModes(model, compliance, data, e); !status) {
            throw Error(describe(status, model));
        }
        if (!(e.frequency.allFinite() && e.platform_shape.allFinite())) {
            throw Error("the elastodynamic frequencies are not finite at this pose");
        }
        if (std::string w = analysis::lumpedMismatchWarning(modes, e, !lumped_asked); !w.empty())
            warnings.push_back(std::move(w));
        if (elastodynamic || (!lumped_asked && !analysis::lumpedHolds(modes, e))) {
            if (std::string w = analysis::elastodynamicPrecisionWarning(e); !w.empty())
                warnings.push_back(std::move(w));
        }
    }
    for (const std::string& w : warnings) {
        if (PyErr_WarnEx(PyExc_RuntimeWarning, w.c_str(), 3) != 0) throw py::error_already_set();
    }
    py::dict out;
    py::list coordinates, free;
    for (int r = 0; r < 3; ++r) coordinates.append(analysis::coordinateLabel(r));
    for (int i = 0; i < K.free_directions; ++i) {
        const Vector3 v = K.free.col(i);
        py::dict d;
        d["direction"] = toArray(analysis::reported(v));
        d["description"] = analysis::describeDirection(v);
        free.append(d);
    }
    out["coordinates"] = coordinates;
    out["matrix"] = toArray(analysis::reported(K.K));
    out["free_directions"] = free;
    out["frequencies"] = toArray(modes.frequency);
    // the shapes' rows are pose coordinates, their columns the modes (ascending): rows only
    Matrix3 shapes;
    for (int i = 0; i < 3; ++i) shapes.col(i) = analysis::reported(Vector3(modes.shape.col(i)));
    out["mode_shapes"] = toArray(shapes);
    out["mass_matrix"] = toArray(analysis::reported(modes.M));
    out["lumped_holds"] = !elastic || analysis::lumpedHolds(modes, e);
    if (elastic) {
        py::array_t<double> f(e.frequency.size());
        for (Eigen::Index i = 0; i < e.frequency.size(); ++i) f.mutable_at(i) = e.frequency(i);
        py::array_t<double> shapes({py::ssize_t{3}, static_cast<py::ssize_t>(e.dofs)});
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < e.dofs; ++c) {
                shapes.mutable_at(r, c) =
                    e.platform_shape(analysis::kReportedCoordinates[static_cast<std::size_t>(r)].index, c);
            }
        }
        out["elastodynamic_frequencies"] = f;
        out["elastodynamic_platform_shapes"] = shapes;
    }
    return out;
}

/// The envelope's points as dicts, and the band's third bound: (points, the first natural
/// frequency [Hz] or None, the summary line that names it or says why it is unknown).
py::tuple envelope(const Robot& robot, const std::vector<std::string>& axes, double min_frequency, double max_frequency,
                   int frequencies, int samples_per_period, double relative_tolerance, double amplification) {
    const Model& model = *robot.model;
    EnvelopeOptions options;
    options.min_frequency = min_frequency;
    options.max_frequency = max_frequency;
    options.frequencies = frequencies;
    options.samples_per_period = samples_per_period;
    options.relative_tolerance = relative_tolerance;
    options.amplification = amplification;
    std::vector<EnvelopeAxis> which;
    for (const std::string& a : axes) {
        if (a == "theta")
            which.push_back(EnvelopeAxis::theta);
        else if (a == "x")
            which.push_back(EnvelopeAxis::x);
        else if (a == "y")
            which.push_back(EnvelopeAxis::y);
        else
            throw Error("axis: '" + a + "' is not one of x, y, theta");
    }
    // Ctrl-C between the bisection's periods (EnvelopeOptions::poll) and between points
    const auto interrupted = [] {
        const py::gil_scoped_acquire acquire;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    };
    options.poll = interrupted;
    options.progress = [&interrupted](int, int) { interrupted(); };
    std::vector<EnvelopePoint> points;
    EnvelopeResonance resonance;
    {
        const py::gil_scoped_release release;
        points = operatingEnvelope(model, options);  // as `nocdyn envelope` computes it
        resonance = envelopeResonance(model, amplification);
    }
    py::list out;
    for (const EnvelopePoint& e : points) {
        if (std::find(which.begin(), which.end(), e.axis) == which.end()) continue;
        py::dict d;
        d["axis"] = axisName(e.axis);
        d["frequency"] = e.frequency;
        d["amplitude"] = e.amplitude;
        d["limit"] = limitName(e.limit);
        // numbered from 1 as `nocdyn envelope` writes them, 0 when not applicable
        d["limb"] = e.limb + 1;
        d["joint"] = e.joint + 1;
        d["actuator"] = e.actuator + 1;
        d["kinematic_amplitude"] = e.kinematic_amplitude;
        d["peak_effort_ratio"] = e.peak_effort_ratio;
        out.append(d);
    }
    // (f_1, {axis: band end}) when known
    py::object first = py::none();
    if (resonance.known) {
        py::dict band_end;
        for (const EnvelopeAxis axis : kEnvelopeAxes)
            band_end[axisName(axis)] = resonance.band_end[static_cast<std::size_t>(axis)];
        first = py::make_tuple(resonance.frequency, band_end);
        // the elastodynamic model's f_1 and modes where the lumped one does not hold at home
        if (!resonance.warning.empty() && PyErr_WarnEx(PyExc_RuntimeWarning, resonance.warning.c_str(), 3) != 0) {
            throw py::error_already_set();
        }
    }
    return py::make_tuple(out, first, resonance.known ? std::string() : resonance.reason);
}

// --- identification ----------------------------------------------------------------------

/// Y of one sample: (n, P), tau = Y pi.
RowArray regressorSample(const Robot& robot, const py::handle& p, const py::handle& dp, const py::handle& ddp) {
    const Model& model = *robot.model;
    Data data(model);
    RegressorMatrix Y;
    const Status status =
        inverseDynamicsRegressor(model, data, vector3(p, "p"), vector3(dp, "dp"), vector3(ddp, "ddp"), Y);
    if (!status) throw Error(describe(status, model));
    RowArray out({static_cast<py::ssize_t>(Y.rows()), static_cast<py::ssize_t>(Y.cols())});
    auto o = out.mutable_unchecked<2>();
    for (Eigen::Index r = 0; r < Y.rows(); ++r)
        for (Eigen::Index c = 0; c < Y.cols(); ++c) o(r, c) = Y(r, c);
    return out;
}

/// The stacked regressor of N samples: (N n, P), rows k n .. k n + n - 1 those of sample k.
/// Raises "sample K: <reason>" at the first sample out of reach or singular.
RowArray regressorBatch(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp) {
    const Model& model = *robot.model;
    const ArrayView vp = viewOf(p, "p", -1, 3, false);
    const ArrayView vdp = viewOf(dp, "dp", vp.rows, 3, false), vddp = viewOf(ddp, "ddp", vp.rows, 3, false);
    const auto n = static_cast<py::ssize_t>(model.actuators), P = static_cast<py::ssize_t>(parameterCount(model));
    RowArray out({static_cast<py::ssize_t>(vp.rows) * n, P});
    double* o = out.mutable_data();
    Eigen::Index failed = -1;
    Status status;
    {
        const py::gil_scoped_release release;
        const ConstStridedMap mp = constMap(vp), mdp = constMap(vdp), mddp = constMap(vddp);
        Data data(model);
        RegressorMatrix Y;
        for (Eigen::Index k = 0; k < vp.rows && failed < 0; ++k) {
            Vector3 pk, dpk, ddpk;
            for (int i = 0; i < 3; ++i) {
                const int c = poseColumn(kPythonPose, i);
                pk(i) = mp(k, c), dpk(i) = mdp(k, c), ddpk(i) = mddp(k, c);
            }
            status = inverseDynamicsRegressor(model, data, pk, dpk, ddpk, Y);
            if (!status) {
                failed = k;
                break;
            }
            for (py::ssize_t a = 0; a < n; ++a)
                for (py::ssize_t c = 0; c < P; ++c) o[(k * n + a) * P + c] = Y(a, c);
        }
    }
    if (failed >= 0) throw Error("sample " + std::to_string(failed) + ": " + describe(status, model));
    return out;
}

/// An (N, n) float64 array (any memory order) copied into an Eigen matrix.
Eigen::MatrixXd actuatorColumns(const py::array& a, const char* name, py::ssize_t rows, int n) {
    return constMap(viewOf(a, name, rows, n, false)).matrix();
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

/// identifyPayload on arrays: t (N,), u and tau (N, n), du and ddu (N, n) or None; prior: the
/// bounds [mass, com_x, com_y, inertia] as (lower, upper) pairs, infinite where open. The GIL
/// is released while the motion is reconstructed and the least squares solved.
py::dict identifyPayloadArrays(const Robot& robot, const ContiguousInput& t, const py::array& u, const py::array& tau,
                               const std::optional<py::array>& du, const std::optional<py::array>& ddu, bool friction,
                               bool held_forces, double cutoff, double holdout,
                               const std::array<std::array<double, 2>, 4>& prior) {
    const Model& model = *robot.model;
    if (t.ndim() != 1) throw Error("t: expected a one-dimensional array of times");
    const py::ssize_t N = t.shape(0);
    Measurements m;
    m.t.assign(t.data(), t.data() + N);
    m.u = actuatorColumns(u, "u", N, model.actuators);
    m.tau = actuatorColumns(tau, "tau", N, model.actuators);
    if (du.has_value() != ddu.has_value()) throw Error("du, ddu: give both or neither");
    if (du) {
        m.du = actuatorColumns(*du, "du", N, model.actuators);
        m.ddu = actuatorColumns(*ddu, "ddu", N, model.actuators);
    }
    const auto finite = [](const Eigen::MatrixXd& x, const char* name) {
        for (Eigen::Index r = 0; r < x.rows(); ++r)
            for (Eigen::Index c = 0; c < x.cols(); ++c)
                if (!std::isfinite(x(r, c)))
                    throw Error(std::string(name) + "[" + std::to_string(r) + ", " + std::to_string(c) +
                                "]: not a finite number");
    };
    for (py::ssize_t k = 0; k < N; ++k) {
        if (!std::isfinite(m.t[static_cast<std::size_t>(k)]))
            throw Error("t[" + std::to_string(k) + "]: not a finite number");
    }
    finite(m.u, "u");
    finite(m.tau, "tau");
    finite(m.du, "du");
    finite(m.ddu, "ddu");
    IdentificationOptions options;
    options.friction = friction;
    options.held_forces = held_forces;
    options.cutoff = cutoff;
    options.holdout = holdout;
    Bounds* bounds[4] = {&options.prior.mass, &options.prior.com_x, &options.prior.com_y, &options.prior.inertia};
    for (std::size_t i = 0; i < 4; ++i) *bounds[i] = Bounds{prior[i][0], prior[i][1]};
    PayloadResult r;
    {
        const py::gil_scoped_release release;
        const Motion motion = reconstructMotion(model, m, options);
        r = identifyPayload(model, motion, options);
    }
    py::dict out;
    out["mass"] = r.mass;
    out["com"] = toArray(std::vector<double>{r.com.x(), r.com.y()});
    out["inertia"] = r.inertia;
    out["mass_sd"] = r.mass_sd;
    out["com_sd"] = toArray(std::vector<double>{r.com_sd.x(), r.com_sd.y()});
    out["inertia_sd"] = r.inertia_sd;
    out["covariance"] = toArray(r.covariance);
    out["inertia_constrained"] = r.inertia_constrained;
    py::list active;
    for (const ActiveBound& b : r.active_bounds) {
        py::dict d;
        d["parameter"] = b.parameter;
        d["side"] = b.upper ? "upper" : "lower";
        d["bound"] = b.bound;
        d["unbounded"] = b.unbounded;
        active.append(d);
    }
    out["active_bounds"] = active;
    py::list joints;
    for (const Estimate& e : r.friction) {
        py::dict d;
        d["name"] = e.name;
        d["value"] = e.value;
        d["stddev"] = e.stddev;
        d["unit"] = e.unit;
        joints.append(d);
    }
    out["friction"] = joints;
    py::dict fit;
    fit["fit_samples"] = r.fit.fit_samples;
    fit["holdout_samples"] = r.fit.holdout_samples;
    fit["rms_fit"] = toArray(r.fit.rms_fit);
    fit["rms_holdout"] = toArray(r.fit.rms_holdout);
    fit["rms_measured"] = toArray(r.fit.rms_measured);
    fit["condition"] = r.fit.condition;
    fit["correlation_samples"] = r.fit.correlation_samples;
    fit["effective_samples"] = r.fit.effective_samples;
    fit["t"] = toArray(r.fit.t);
    fit["measured"] = toArray(r.fit.measured);
    fit["predicted"] = toArray(r.fit.predicted);
    out["fit"] = fit;
    return out;
}

py::dict loadPrior(const std::string& path) {
    const PayloadPrior prior = io::loadPayloadPrior(path);
    py::dict out;
    const auto side = [](double v) -> py::object { return std::isfinite(v) ? py::object(py::float_(v)) : py::none(); };
    const std::pair<const char*, const Bounds*> items[] = {
        {"mass", &prior.mass}, {"com_x", &prior.com_x}, {"com_y", &prior.com_y}, {"inertia", &prior.inertia}};
    for (const auto& [name, b] : items) {
        if (std::isfinite(b->lower) || std::isfinite(b->upper))
            out[name] = py::make_tuple(side(b->lower), side(b->upper));
    }
    return out;
}

}  // namespace

}  // namespace nocdyn::python

PYBIND11_MODULE(_nocdyn, m) {
    using namespace nocdyn;
    using namespace nocdyn::python;
    m.doc() = "Compiled core of the nocdyn package (use `import nocdyn`).";
    m.attr("__version__") = NOCDYN_VERSION;
    bindApplication(m);
    bindCommandLine(m);
    py::register_exception<Error>(m, "Error", PyExc_ValueError);

    py::class_<Robot>(m, "Robot")
        .def_static(
            "load", [](const std::string& path) { return Robot(io::loadRobotDescription(path)); }, py::arg("path"))
        .def_static(
            "from_yaml",
            [](const std::string& text, const std::string& source) {
                return Robot(io::parseRobotDescription(text, source));
            },
            py::arg("text"), py::arg("source") = "<string>")
        .def_static(
            "example", [](const std::string& name) { return Robot(io::exampleRobot(name)); }, py::arg("name"))
        .def_static("paper", [] { return Robot(io::exampleRobot("paper-3prr")); })
        .def_static("example_names", [] { return io::exampleRobotNames(); })
        .def_property_readonly("name", [](const Robot& r) { return r.model->description.name; })
        .def_property_readonly("source", [](const Robot& r) { return r.model->description.source; })
        .def_property_readonly("actuator_count", [](const Robot& r) { return r.model->actuators; })
        .def_property_readonly("limb_count", [](const Robot& r) { return r.model->limbs; })
        .def_property_readonly("bodies", [](const Robot& r) { return r.model->bodies; })
        .def_property_readonly("home", [](const Robot& r) { return poseArray(r.model->home); })
        .def_property_readonly("gravity",
                               [](const Robot& r) {
                                   return std::array{r.model->gravity(0), r.model->gravity(1)};
                               })
        .def_property_readonly("redundant",
                               [](const Robot& r) { return r.model->coordinates == Coordinates::platform; })
        .def("limb_info",
             [](const Robot& r) {
                 py::list out;
                 const Model& model = *r.model;
                 for (int j = 0; j < model.limbs; ++j) {
                     const LimbDescription& limb = model.description.limbs[static_cast<std::size_t>(j)];
                     py::dict d;
                     d["name"] = limb.name;
                     d["type"] = limb.type();
                     py::list joints;
                     for (const JointDescription& joint : limb.joints) joints.append(joint.actuated);
                     d["actuated"] = joints;
                     out.append(d);
                 }
                 return out;
             })
        .def(
            "_drawing",
            [](const Robot& r, const py::handle& pose) {
                // the geometry the animation page and the CLI's frames draw (drawing.hpp)
                Data data(*r.model);
                RobotDrawing drawing;
                if (const Status status = drawRobot(*r.model, data, vector3(pose, "pose"), drawing); !status)
                    throw Error(describe(status, *r.model));
                const auto point = [](const Vector2& v) { return py::make_tuple(v.x(), v.y()); };
                py::list limbs, platform;
                for (int j = 0; j < drawing.limbs; ++j) {
                    py::list joints;
                    for (const JointDrawing& joint : drawing.limb[static_cast<std::size_t>(j)].joint) {
                        py::dict d;
                        d["type"] = joint.type == JointType::prismatic ? "P" : "R";
                        d["actuator"] = joint.actuator;
                        d["position"] = point(joint.position);
                        d["rail_start"] = point(joint.rail_start);
                        d["rail_end"] = point(joint.rail_end);
                        joints.append(d);
                    }
                    limbs.append(joints);
                    platform.append(point(drawing.platform[static_cast<std::size_t>(j)]));
                }
                py::dict out;
                out["limbs"] = limbs;
                out["platform"] = platform;
                out["C"] = point(drawing.C);
                return out;
            },
            py::arg("pose"))
        .def("actuator_info",
             [](const Robot& r) {
                 py::list out;
                 const Model& model = *r.model;
                 for (int a = 0; a < model.actuators; ++a) {
                     const auto j = static_cast<std::size_t>(model.actuator_limb[static_cast<std::size_t>(a)]);
                     const auto k = static_cast<std::size_t>(model.actuator_joint[static_cast<std::size_t>(a)]);
                     const JointDescription& joint = model.description.limbs[j].joints[k];
                     py::dict d;
                     // numbered from 1, as the command line names them
                     d["limb"] = static_cast<int>(j) + 1;
                     d["limb_name"] = model.description.limbs[j].name;
                     d["joint"] = static_cast<int>(k) + 1;
                     d["type"] = joint.type == JointType::prismatic ? "P" : "R";
                     d["lower"] = joint.limits.lower;
                     d["upper"] = joint.limits.upper;
                     d["effort"] = joint.limits.effort;
                     d["velocity"] = joint.limits.velocity;
                     out.append(d);
                 }
                 return out;
             })
        .def("to_yaml", [](const Robot& r) { return io::descriptionToYaml(r.model->description); })
        .def("_inverse_dynamics_sample", &inverseDynamicsSample, py::arg("p"), py::arg("dp"), py::arg("ddp"),
             py::arg("matrices") = false, py::arg("check_limits") = true, py::arg("check") = true)
        .def("_inverse_dynamics_batch", &inverseDynamicsBatchArrays, py::arg("p"), py::arg("dp"), py::arg("ddp"),
             py::arg("u"), py::arg("du"), py::arg("ddu"), py::arg("tau"), py::arg("threads") = 1,
             py::arg("check_limits") = true)
        .def("_limits_batch", &limitsBatchArrays, py::arg("p"), py::arg("dp"), py::arg("ddp"))
        .def("_inverse_dynamics_derivatives_sample", &inverseDynamicsDerivativesSample, py::arg("p"), py::arg("dp"),
             py::arg("ddp"))
        .def("_inverse_dynamics_derivatives_batch", &inverseDynamicsDerivativesBatchArrays, py::arg("p"), py::arg("dp"),
             py::arg("ddp"), py::arg("threads") = 1)
        .def("_actuator_derivatives_sample", &actuatorDerivativesSample, py::arg("p"), py::arg("dp"), py::arg("ddp"))
        .def("_actuator_derivatives_batch", &actuatorDerivativesBatchArrays, py::arg("p"), py::arg("dp"),
             py::arg("ddp"), py::arg("threads") = 1)
        .def("_linearize", &linearizeSample, py::arg("p"), py::arg("dp"), py::arg("tau"),
             py::arg("output") = "acceleration", py::arg("compliance") = "rigid")
        .def("_reactions_batch", &reactionsBatchArrays, py::arg("p"), py::arg("dp"), py::arg("ddp"), py::arg("out"),
             py::arg("threads") = 1)
        .def("_time_cpp_batch", &timeCppBatch, py::arg("p"), py::arg("dp"), py::arg("ddp"), py::arg("repeat") = 1)
        .def_static("_thread_cpu_seconds", &threadCpuSeconds)
        .def("_sample_trajectory", &sampleTrajectory, py::arg("trajectory"), py::arg("rate"),
             py::arg("duration") = std::nullopt, py::arg("allow_limits") = false)
        .def("_forward_kinematics", &forwardKinematics, py::arg("u"), py::arg("tolerance") = 1e-9)
        .def("_state_from_actuators", &stateFromActuatorValues, py::arg("u"), py::arg("du"), py::arg("assembly_mode"))
        .def("_simulate", &simulate, py::arg("p0"), py::arg("dp0"), py::arg("force_times"), py::arg("forces"),
             py::arg("interpolation"), py::arg("t"), py::arg("rtol"), py::arg("atol"), py::arg("max_step"))
        .def("_parameter_names",
             [](const Robot& r) {
                 std::vector<std::string> names;
                 for (int c = 0; c < parameterCount(*r.model); ++c) names.push_back(parameterName(*r.model, c));
                 return names;
             })
        .def("_parameter_units",
             [](const Robot& r) {
                 std::vector<std::string> units;
                 for (int c = 0; c < parameterCount(*r.model); ++c) units.push_back(parameterUnit(*r.model, c));
                 return units;
             })
        .def("_standard_parameters",
             [](const Robot& r) {
                 const ParameterVector pi = standardParameters(*r.model);
                 return toArray(std::vector<double>(pi.data(), pi.data() + pi.size()));
             })
        .def(
            "_with_payload",
            [](const Robot& r, double mass, const std::array<double, 2>& com, double inertia) {
                return Robot(withPayload(r.model->description, Payload{mass, inertia, Vector2(com[0], com[1])}));
            },
            py::arg("mass"), py::arg("com"), py::arg("inertia"))
        .def("_regressor_sample", &regressorSample, py::arg("p"), py::arg("dp"), py::arg("ddp"))
        .def("_regressor_batch", &regressorBatch, py::arg("p"), py::arg("dp"), py::arg("ddp"))
        .def("_identify_payload", &identifyPayloadArrays, py::arg("t"), py::arg("u"), py::arg("tau"), py::arg("du"),
             py::arg("ddu"), py::arg("friction"), py::arg("held_forces"), py::arg("cutoff"), py::arg("holdout"),
             py::arg("prior"))
        .def_static("_load_prior", &loadPrior, py::arg("path"))
        .def("_stiffness", &stiffnessAt, py::arg("p"), py::arg("elastodynamic") = false, py::arg("frequencies") = false,
             py::arg("lumped_asked") = false)
        .def("_envelope", &envelope, py::arg("axes"), py::arg("min_frequency"), py::arg("max_frequency"),
             py::arg("frequencies"), py::arg("samples_per_period"), py::arg("relative_tolerance"),
             py::arg("amplification") = kDefaultAmplification);

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

    // --- design sweeps (python/src/design.cpp): chunks of designs evaluated with the GIL released
    void nocdyn_python_bind_design(py::module_ & m);
    nocdyn_python_bind_design(m);
}
