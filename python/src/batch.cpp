// The batches of the Robot class (Robot._*_batch): N samples over NumPy arrays read in place
// whatever their memory order, computed by the library's batch calls (batch.hpp,
// derivatives.hpp, reactions.hpp, regressor) with the GIL released. Their errors are the
// library's words (describeFailure, describeLimits): samples numbered from 1.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "expose.hpp"
#include "nocdyn/batch.hpp"
#include "nocdyn/derivatives.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/reactions.hpp"
#include "nocdyn/sim/identification.hpp"

namespace nocdyn::python {

namespace {

/// CPU time of the calling thread [s] (the batch runs on it: wall time would count the
/// other processes of a shared machine).
double threadCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
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

/// Throws the batch's failure (with `check`), then its first sample beyond a limit.
void raiseOutcome(const Model& model, const BatchResult& result, Eigen::Index samples, bool check) {
    if (check && !result.ok()) throw Error(describeFailure(model, result, samples));
    if (const std::string limits = describeLimits(model, result); !limits.empty()) throw Error(limits);
}

/// The caller's u, du, ddu and tau (n rows, one column per actuator), viewed in place; all four
/// in one memory order.
struct ActuatorOutputs {
    StridedMap u, du, ddu, tau;
};
ActuatorOutputs actuatorOutputs(const Model& model, py::ssize_t n, const py::array& u, const py::array& du,
                                const py::array& ddu, const py::array& tau) {
    const ArrayView vu = viewOf(u, "u", n, model.actuators, true), vdu = viewOf(du, "du", n, model.actuators, true);
    const ArrayView vddu = viewOf(ddu, "ddu", n, model.actuators, true),
                    vtau = viewOf(tau, "tau", n, model.actuators, true);
    if (vu.col_stride != vdu.col_stride || vu.col_stride != vddu.col_stride || vu.col_stride != vtau.col_stride) {
        throw Error("out: u, du, ddu and tau must have the same memory order (all C- or all F-ordered)");
    }
    return {map(vu), map(vdu), map(vddu), map(vtau)};
}

/// The batch over arrays viewed in place into the caller's u, du, ddu, tau, the GIL released
/// while it runs. check_limits: ActuatorLimits::every_joint, as `nocdyn inverse-dynamics`.
void inverseDynamicsBatchArrays(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp,
                                const py::array& u, const py::array& du, const py::array& ddu, const py::array& tau,
                                unsigned threads, bool check, bool check_limits) {
    const Model& model = *robot.model;
    const SampleMaps in(p, dp, ddp);
    const py::ssize_t n = in.rows;
    ActuatorOutputs out = actuatorOutputs(model, n, u, du, ddu, tau);
    const ActuatorLimits limits = check_limits ? ActuatorLimits::every_joint : ActuatorLimits::ignore;
    const BatchResult result = inSlices(n, [&](Eigen::Index begin, Eigen::Index rows) {
        auto u_rows = out.u.middleRows(begin, rows), du_rows = out.du.middleRows(begin, rows);
        auto ddu_rows = out.ddu.middleRows(begin, rows), tau_rows = out.tau.middleRows(begin, rows);
        return inverseDynamicsBatch(model, in.p.middleRows(begin, rows), in.dp.middleRows(begin, rows),
                                    in.ddp.middleRows(begin, rows), u_rows, du_rows, ddu_rows, tau_rows, threads,
                                    kPythonPose, limits);
    });
    raiseOutcome(model, result, n, check);
}

/// The batch of a two-DOF robot (motion: translation) over (N, 2) arrays [x, y] of the tool
/// point and its rates, read in place whatever their memory order, into the caller's u, du,
/// ddu, tau: each slice lifted through the task map E into one column-major (rows x 3) buffer
/// per input ([x, y, theta = home(0)], rates [dx, dy, 0]: the kernel's contiguous layout),
/// allocated once per call, then the batch as for a three-DOF robot.
void inverseDynamicsTaskBatchArrays(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp,
                                    const py::array& u, const py::array& du, const py::array& ddu, const py::array& tau,
                                    unsigned threads, bool check, bool check_limits) {
    const Model& model = *robot.model;
    if (model.task_dimension != 2)
        throw Error("p: arrays of shape (N, 2) are for a two-DOF robot (motion: translation)");
    const ArrayView vp = viewOf(p, "p", -1, 2, false);
    const py::ssize_t n = vp.rows;
    const ConstStridedMap mp = constMap(vp), mdp = constMap(viewOf(dp, "dp", n, 2, false)),
                          mddp = constMap(viewOf(ddp, "ddp", n, 2, false));
    ActuatorOutputs out = actuatorOutputs(model, n, u, du, ddu, tau);
    const ActuatorLimits limits = check_limits ? ActuatorLimits::every_joint : ActuatorLimits::ignore;
    // the lifted slice in Python's pose order [x, y, theta]: theta's column set once
    const Eigen::Index buffer_rows = std::min<Eigen::Index>(n, Eigen::Index{1} << 16);
    Eigen::ArrayXXd lp(buffer_rows, 3), ldp(buffer_rows, 3), lddp(buffer_rows, 3);
    lp.col(2).setConstant(model.home(0));
    ldp.col(2).setZero();
    lddp.col(2).setZero();
    const BatchResult result = inSlices(n, [&](Eigen::Index begin, Eigen::Index rows) {
        lp.topLeftCorner(rows, 2) = mp.middleRows(begin, rows);
        ldp.topLeftCorner(rows, 2) = mdp.middleRows(begin, rows);
        lddp.topLeftCorner(rows, 2) = mddp.middleRows(begin, rows);
        auto u_rows = out.u.middleRows(begin, rows), du_rows = out.du.middleRows(begin, rows);
        auto ddu_rows = out.ddu.middleRows(begin, rows), tau_rows = out.tau.middleRows(begin, rows);
        return inverseDynamicsBatch(model, lp.topRows(rows), ldp.topRows(rows), lddp.topRows(rows), u_rows, du_rows,
                                    ddu_rows, tau_rows, threads, kPythonPose, limits);
    });
    raiseOutcome(model, result, n, check);
}

/// The derivatives of N samples, each (N, n, 3), the GIL released while they run: (d_p, d_dp,
/// d_ddp); with `check` the first failed sample raises (failed rows are NaN).
py::tuple inverseDynamicsDerivativesBatchArrays(const Robot& robot, const py::array& p, const py::array& dp,
                                                const py::array& ddp, unsigned threads, bool check) {
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
    raiseOutcome(model, result, n, check);
    return py::make_tuple(d_p.array, d_dp.array, d_ddp.array);
}

/// The actuator variables' derivatives of N samples, the GIL released while they run: (u, du,
/// ddu (N, n) each, u_p, du_p, du_dp, ddu_p, ddu_dp, ddu_ddp (N, n, 3) each).
py::tuple actuatorDerivativesBatchArrays(const Robot& robot, const py::array& p, const py::array& dp,
                                         const py::array& ddp, unsigned threads, bool check) {
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
    raiseOutcome(model, result, n, check);
    return py::make_tuple(u.array, du.array, ddu.array, u_p.array, du_p.array, du_dp.array, ddu_p.array, ddu_dp.array,
                          ddu_ddp.array);
}

/// The joint reactions of N samples into `out`, (N, 9 limbs) (a view of the (N, limbs, 3, 3)
/// array), the GIL released while they run. With `check` the first failed sample and the first
/// not finite raise; with `check_limits` the first beyond a limit (full path at every sample).
/// `single`: one sample, whose errors name no sample.
void reactionsBatchArrays(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp,
                          const py::array& out, unsigned threads, bool check, bool check_limits, bool single) {
    const Model& model = *robot.model;
    const SampleMaps in(p, dp, ddp);
    const py::ssize_t n = in.rows;
    StridedMap mout = map(viewOf(out, "out", n, 9 * model.limbs, true));
    BatchResult result = inSlices(n, [&](Eigen::Index begin, Eigen::Index rows) {
        auto out_rows = mout.middleRows(begin, rows);
        return reactionsBatch(model, in.p.middleRows(begin, rows), in.dp.middleRows(begin, rows),
                              in.ddp.middleRows(begin, rows), out_rows, threads, kPythonPose);
    });
    const auto say = [&](Eigen::Index k, const std::string& what) {
        throw Error(single ? what : "sample " + std::to_string(k + 1) + ": " + what);
    };
    if (check && !result.ok()) {
        if (single) throw Error(describe(result.status, model));
        throw Error(describeFailure(model, result, n));
    }
    if (check) {
        for (Eigen::Index k = 0; k < n; ++k)
            if (!mout.row(k).isFinite().all()) say(k, "the reactions is not finite (the input is too large)");
    }
    if (!check_limits) return;
    {
        const py::gil_scoped_release release;
        result.first_beyond_limits = firstSampleBeyondLimits(model, in.p, in.dp, in.ddp, kPythonPose, result.limits);
    }
    if (result.first_beyond_limits != BatchResult::npos)
        say(result.first_beyond_limits, describe(result.limits, model));
}

/// The stacked regressor of N samples: (N n, P), rows k n .. k n + n - 1 those of sample k.
/// Raises "sample K: <reason>" at the first sample out of reach, singular or not finite.
RowArray regressorBatch(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp) {
    const Model& model = *robot.model;
    const SampleMaps in(p, dp, ddp);
    const auto n = static_cast<py::ssize_t>(model.actuators), P = static_cast<py::ssize_t>(parameterCount(model));
    RowArray out({in.rows * n, P});
    double* o = out.mutable_data();
    Eigen::Index failed = -1;
    Status status;
    {
        const py::gil_scoped_release release;
        Data data(model);
        RegressorMatrix Y;
        for (Eigen::Index k = 0; k < in.rows && failed < 0; ++k) {
            status = inverseDynamicsRegressor(model, data, coreRow(in.p, k), coreRow(in.dp, k), coreRow(in.ddp, k), Y);
            if (!status) {
                failed = k;
                break;
            }
            for (py::ssize_t a = 0; a < n; ++a)
                for (py::ssize_t c = 0; c < P; ++c) o[(k * n + a) * P + c] = Y(a, c);
            if (!Y.allFinite()) {
                throw Error("sample " + std::to_string(k + 1) +
                            ": the regressor is not finite (the input is too large)");
            }
        }
    }
    if (failed >= 0) throw Error("sample " + std::to_string(failed + 1) + ": " + describe(status, model));
    return out;
}

/// The C++ batch over Eigen's own column-major arrays, timed from C++ (the reference the
/// Python batch is compared with in bench/python_batch.py): CPU seconds of the calling thread
/// per call, best of `repeat` after one untimed call (outputs allocated and touched once, as
/// with preallocated outputs).
double timeCppBatch(const Robot& robot, const py::array& p, const py::array& dp, const py::array& ddp, int repeat) {
    const Model& model = *robot.model;
    const SampleMaps in(p, dp, ddp);
    const Eigen::ArrayXXd P = in.p, dP = in.dp, ddP = in.ddp;
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

}  // namespace

void exposeBatch(py::module_& m) {
    py::class_<Robot>(m.attr("Robot"))
        .def("_inverse_dynamics_batch", &inverseDynamicsBatchArrays, py::arg("p"), py::arg("dp"), py::arg("ddp"),
             py::arg("u"), py::arg("du"), py::arg("ddu"), py::arg("tau"), py::arg("threads") = 1,
             py::arg("check") = true, py::arg("check_limits") = true)
        .def("_inverse_dynamics_task_batch", &inverseDynamicsTaskBatchArrays, py::arg("p"), py::arg("dp"),
             py::arg("ddp"), py::arg("u"), py::arg("du"), py::arg("ddu"), py::arg("tau"), py::arg("threads") = 1,
             py::arg("check") = true, py::arg("check_limits") = true)
        .def("_inverse_dynamics_derivatives_batch", &inverseDynamicsDerivativesBatchArrays, py::arg("p"), py::arg("dp"),
             py::arg("ddp"), py::arg("threads") = 1, py::arg("check") = true)
        .def("_actuator_derivatives_batch", &actuatorDerivativesBatchArrays, py::arg("p"), py::arg("dp"),
             py::arg("ddp"), py::arg("threads") = 1, py::arg("check") = true)
        .def("_reactions_batch", &reactionsBatchArrays, py::arg("p"), py::arg("dp"), py::arg("ddp"), py::arg("out"),
             py::arg("threads") = 1, py::arg("check") = true, py::arg("check_limits") = true, py::arg("single") = false)
        .def("_regressor_batch", &regressorBatch, py::arg("p"), py::arg("dp"), py::arg("ddp"))
        .def("_time_cpp_batch", &timeCppBatch, py::arg("p"), py::arg("dp"), py::arg("ddp"), py::arg("repeat") = 1)
        .def_static("_thread_cpu_seconds", &threadCpuSeconds);
}

}  // namespace nocdyn::python
