// Batch inverse dynamics of a spatial robot: N samples (p, dp, ddp) by the per-sample path
// (spatial::inverseDynamics) over a range, optionally split over std::threads (parallel.hpp),
// one spatial::Data per thread, allocated once per chunk.
//
// Layout as batch.hpp's: inputs are N x d arrays (d = task_dimension), row k = sample k, the
// columns in the order of Model::coordinates() ([x, y, z, roll, pitch, yaw] or [x, y, z]);
// outputs are N x n arrays (n = model.actuators), row k = sample k's u, du, ddu and tau. Any
// strides work (a C-ordered NumPy array is a column-major map with row stride d, no copy).
//
// Values equal the per-sample path's on one Data carried from sample to sample. A chunk starts
// from a fresh Data, as the first sample of a serial run does: a limb solved in closed form (the
// U-P-S, R-U-S and R-U-U limbs of every shipped robot) gives the same bits whatever the split; a
// limb left to Newton starts from the previous sample's joint variables, which the first sample
// of a chunk has not (it starts from home), and may then differ to Newton's tolerance.
// A failed sample's outputs are NaN. Nothing is allocated per sample.
#pragma once

#include "nocdyn/batch.hpp"
#include "nocdyn/spatial.hpp"

namespace nocdyn::spatial {

/// How a spatial batch runs.
struct BatchOptions {
    /// 1: the calling thread; 0: one per hardware thread; more: that many contiguous chunks
    /// (the calling thread runs one), capped at the hardware threads and one chunk per 8 samples.
    unsigned threads = 1;
    /// checkLimits (spatial_limits.hpp) at every computed sample: BatchResult::first_beyond_limits
    /// and its Status (the codes of checkLimits). Its outputs are written all the same.
    bool check_limits = false;
    /// Stop at the first failing sample, as a serial loop that raises there: the result is that
    /// loop's (failed = 1, the first failure in index order whatever the split, a sample beyond
    /// limits only before it) and every row after the failure is NaN (not computed). A chunk
    /// stops at its own first failure and at any sample after an earlier failure already found.
    bool stop_at_failure = false;
};

/// Inverse dynamics of N samples: (p, dp, ddp), N x d each -> u, du, ddu, tau, N x n each.
/// BatchResult: the failures counted, the first in index order and its Status (what
/// inverseDynamics returns for that sample), and with check_limits the first computed sample
/// beyond a limit. Throws nocdyn::Error when the arrays' sizes disagree (before any sample is
/// computed) or a worker thread cannot start.
BatchResult inverseDynamicsBatch(const Model& model, const BatchInput& p, const BatchInput& dp, const BatchInput& ddp,
                                 BatchOutput u, BatchOutput du, BatchOutput ddu, BatchOutput tau,
                                 const BatchOptions& options = {});

}  // namespace nocdyn::spatial
