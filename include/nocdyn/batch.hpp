// Batch inverse dynamics of the general model: many pose-space samples of any planar
// parallel robot at once, the lean per-sample kernel (inverseDynamicsFast) in one loop,
// optionally split over std::threads.
//
// Layout: inputs are N x 3 arrays, row k = sample k ([theta, x_c, y_c], its rate, its
// acceleration; or [x_c, y_c, theta], the order of the CSV tables and of Python, with
// PoseColumns::x_y_theta: the columns are then read in that order by the same gathers, no
// copy); outputs are N x n arrays (n = model.actuators), row k = sample k's u, du,
// ddu and tau. Eigen's default column-major storage makes each column one coordinate of every
// sample (structure of arrays); any strides work, row-major included (NumPy's C- and
// F-ordered arrays and their strided views map onto these Refs without a copy).
//
// Values equal inverseDynamicsFast's (the same kernel). A sample the kernel rejects takes the
// full path, which gives its exact Status; a failed sample's outputs are NaN. Nothing is
// allocated per sample; the threaded variant starts its threads on every call (tens of
// microseconds), worth it for large batches.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/model.hpp"
#include "nocdyn/status.hpp"

namespace nocdyn {

/// Outcome of a batch: how many samples failed, the first of them and its Status (exactly
/// what inverseDynamics returns for that sample).
struct BatchResult {
    static constexpr Eigen::Index npos = std::numeric_limits<Eigen::Index>::max();
    Eigen::Index failed = 0;
    Eigen::Index first_failure = npos;
    Status status;  ///< of sample first_failure; ok when failed == 0
    /// With ActuatorLimits::check: the first computed sample beyond an actuated joint's range
    /// or velocity limit or an actuator's effort (npos: none), and that Status (the codes of
    /// checkJointLimits and checkEffort). Its outputs are written all the same.
    Eigen::Index first_beyond_limits = npos;
    Status limits;
    [[nodiscard]] bool ok() const { return failed == 0; }
};

/// The outcome of a batch run in consecutive chunks (chunks[0] first): the failures added up,
/// the first failure and the first sample beyond limits those of the earliest chunk with one.
[[nodiscard]] BatchResult combineChunks(const std::vector<BatchResult>& chunks);

/// Which limits a batch checks on each computed sample.
/// - ignore: none.
/// - check: from the sample's u, du and tau, the actuated joints' ranges and velocity limits
///   (limb by limb, joint by joint, as checkJointLimits) and then every actuator's effort (as
///   checkEffort), inside the kernel. A passive joint's limits are not seen (they need its q).
/// - every_joint: every joint's range and velocity limit, then every actuator's effort, as
///   `nocdyn inverse-dynamics` checks a sample: as `check` when every limited joint is actuated
///   (limitsOnActuatedJointsOnly), else by the full path (checkJointLimits, checkEffort) at each
///   computed sample after the kernel, on the calling thread.
enum class ActuatorLimits { ignore, check, every_joint };

/// Whether every joint with a range or velocity limit is actuated: then u, du and tau are all
/// that the limits of a sample need.
[[nodiscard]] bool limitsOnActuatedJointsOnly(const Model& model);

/// checkJointLimits, then checkEffort, of a sample the full path computed into `data`.
[[nodiscard]] Status checkSampleLimits(const Model& model, const Data& data);

/// ActuatorLimits::check of one computed sample (u, du, tau of size n): the first limit
/// exceeded, or ok.
[[nodiscard]] Status checkActuatorLimits(const Model& model, const ActuatorVector& u, const ActuatorVector& du,
                                         const ActuatorVector& tau);

/// The order of the three pose columns of a batch's arrays: the core's twist order
/// [theta, x, y], or the tables' and Python's [x, y, theta].
enum class PoseColumns { theta_x_y, x_y_theta };

/// The column that holds the core's pose coordinate i (0 theta, 1 x, 2 y) in `order`.
[[nodiscard]] constexpr int poseColumn(PoseColumns order, int i) {
    return order == PoseColumns::theta_x_y ? i : (i + 2) % 3;
}

/// An N x m array of any (non-negative) strides: Eigen's default layout, a row-major one or a
/// strided view of either, referred to without a copy.
using BatchInput = Eigen::Ref<const Eigen::ArrayXXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;
using BatchOutput = Eigen::Ref<Eigen::ArrayXXd, 0, Eigen::Stride<Eigen::Dynamic, Eigen::Dynamic>>;

/// Inverse dynamics of N samples: (p, dp, ddp), N x 3 each -> u, du, ddu, tau, N x n each.
/// `threads`: 1 runs on the calling thread; 0 uses one per hardware thread; more splits the
/// samples into that many contiguous chunks (the calling thread runs one), capped at the
/// hardware threads and at one chunk per 8 samples.
/// The four outputs must have the same stride from one actuator to the next. `order`: the
/// order of p's, dp's and ddp's columns. `limits`: see ActuatorLimits (checked on the values
/// still in registers, no pass over the outputs; after a chunk's first violation, no more).
/// Throws nocdyn::Error when the arrays' sizes disagree (before any sample is computed).
BatchResult inverseDynamicsBatch(const Model& model, const BatchInput& p, const BatchInput& dp, const BatchInput& ddp,
                                 BatchOutput u, BatchOutput du, BatchOutput ddu, BatchOutput tau, unsigned threads = 1,
                                 PoseColumns order = PoseColumns::theta_x_y,
                                 ActuatorLimits limits = ActuatorLimits::ignore);

/// The first of N samples (p, dp, ddp, N x 3 each in `order`) beyond a limit checkSampleLimits
/// finds, by the full path at each sample, its Status in `status`; a sample out of reach or
/// singular is skipped (its own computation reports it). BatchResult::npos: none.
[[nodiscard]] Eigen::Index firstSampleBeyondLimits(const Model& model, const BatchInput& p, const BatchInput& dp,
                                                   const BatchInput& ddp, PoseColumns order, Status& status);

/// A batch's failure in words, the same for every front end: "sample K: <reason> (F of N
/// samples failed)", K numbered from 1 (row K - 1 of the arrays); empty when none failed.
[[nodiscard]] std::string describeFailure(const Model& model, const BatchResult& result, Eigen::Index samples);

/// A batch's first sample beyond a limit in words: "sample K: <reason>", K numbered from 1;
/// empty when none.
[[nodiscard]] std::string describeLimits(const Model& model, const BatchResult& result);

/// How many samples the batch computes at once (a packet, one value per lane of a vector):
/// eight where the CPU has AVX-512 (x86-64-v4, found at run time), else four. `automatic` is
/// the default; `four` and `eight` force a width for the process, for tests and benchmarks
/// that compare the two (eight is four where the CPU or the build lacks it).
enum class BatchPackets { automatic, four, eight };

/// Sets the packet width of every later batch in this process; returns the width (4 or 8).
int setBatchPackets(BatchPackets packets);

/// The packet width the batch runs with: 4 or 8.
[[nodiscard]] int batchPacketWidth();

/// Row k of a batch's pose array in the core's twist order [theta, x, y].
[[nodiscard]] inline Vector3 poseRow(const BatchInput& a, Eigen::Index k, PoseColumns order) {
    return {a(k, poseColumn(order, 0)), a(k, poseColumn(order, 1)), a(k, poseColumn(order, 2))};
}

}  // namespace nocdyn
