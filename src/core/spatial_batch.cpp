// Batch inverse dynamics of a spatial robot (spatial_batch.hpp): the per-sample path over
// contiguous chunks of samples, one Data per chunk, the chunks over threads (parallel.hpp).
#include "nocdyn/spatial_batch.hpp"

#include <atomic>
#include <limits>
#include <string>
#include <vector>

#include "nocdyn/error.hpp"
#include "nocdyn/parallel.hpp"
#include "nocdyn/spatial_limits.hpp"

namespace nocdyn::spatial {

namespace {

struct Arrays {
    const BatchInput& p;
    const BatchInput& dp;
    const BatchInput& ddp;
    BatchOutput& u;
    BatchOutput& du;
    BatchOutput& ddu;
    BatchOutput& tau;
};

void requireShape(const char* name, Eigen::Index rows, Eigen::Index cols, Eigen::Index n, Eigen::Index m) {
    if (rows != n || cols != m) {
        std::string message = "spatial::inverseDynamicsBatch: ";
        message += name;
        message += " is " + std::to_string(rows);
        message += " x " + std::to_string(cols);
        message += ", expected " + std::to_string(n);
        message += " x " + std::to_string(m);
        throw Error(message);
    }
}

void nanRows(const Arrays& a, Eigen::Index begin, Eigen::Index end) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    a.u.middleRows(begin, end - begin).setConstant(nan);
    a.du.middleRows(begin, end - begin).setConstant(nan);
    a.ddu.middleRows(begin, end - begin).setConstant(nan);
    a.tau.middleRows(begin, end - begin).setConstant(nan);
}

/// Samples [begin, end) on one Data. `earliest`: the lowest failing sample any chunk has found
/// so far (stop_at_failure: nothing after it is computed).
BatchResult chunk(const Model& model, const Arrays& a, Eigen::Index begin, Eigen::Index end,
                  const BatchOptions& options, std::atomic<Eigen::Index>& earliest) {
    const int d = model.task_dimension, n = model.actuators;
    Data data(model);
    TaskVector p(d), dp(d), ddp(d);  // fixed capacity: no allocation per sample
    BatchResult r;
    for (Eigen::Index k = begin; k < end; ++k) {
        if (options.stop_at_failure && k > earliest.load(std::memory_order_relaxed)) break;
        for (int i = 0; i < d; ++i) p(i) = a.p(k, i), dp(i) = a.dp(k, i), ddp(i) = a.ddp(k, i);
        const Status status = inverseDynamics(model, data, p, dp, ddp);
        if (!status) {
            nanRows(a, k, k + 1);
            if (r.failed++ == 0) {
                r.first_failure = k;
                r.status = status;
            }
            if (options.stop_at_failure) {
                // lower the shared earliest failure to k unless another chunk found one before it
                Eigen::Index seen = earliest.load(std::memory_order_relaxed);
                while (k < seen && !earliest.compare_exchange_weak(seen, k, std::memory_order_relaxed)) {
                }
                break;
            }
            continue;
        }
        for (int c = 0; c < n; ++c) {
            a.u(k, c) = data.u(c);
            a.du(k, c) = data.du(c);
            a.ddu(k, c) = data.ddu(c);
            a.tau(k, c) = data.tau(c);
        }
        if (options.check_limits && r.first_beyond_limits == BatchResult::npos) {
            if (const Status limits = checkLimits(model, data); !limits) {
                r.first_beyond_limits = k;
                r.limits = limits;
            }
        }
    }
    return r;
}

}  // namespace

BatchResult inverseDynamicsBatch(const Model& model, const BatchInput& p, const BatchInput& dp, const BatchInput& ddp,
                                 BatchOutput u, BatchOutput du, BatchOutput ddu, BatchOutput tau,
                                 const BatchOptions& options) {
    const Eigen::Index N = p.rows();
    const int d = model.task_dimension, n = model.actuators;
    requireShape("p", p.rows(), p.cols(), N, d);
    requireShape("dp", dp.rows(), dp.cols(), N, d);
    requireShape("ddp", ddp.rows(), ddp.cols(), N, d);
    requireShape("u", u.rows(), u.cols(), N, n);
    requireShape("du", du.rows(), du.cols(), N, n);
    requireShape("ddu", ddu.rows(), ddu.cols(), N, n);
    requireShape("tau", tau.rows(), tau.cols(), N, n);
    const Arrays a{p, dp, ddp, u, du, ddu, tau};
    std::atomic<Eigen::Index> earliest{BatchResult::npos};
    // chunks of multiples of 8 samples: no two threads write the same cache line of a
    // C-ordered output
    const ParallelSplit split = splitRange(N, options.threads, 8);
    BatchResult result;
    if (split.workers == 1) {
        result = chunk(model, a, 0, N, options, earliest);
    } else {
        std::vector<BatchResult> results(split.workers);
        parallelFor("spatial::inverseDynamicsBatch", split, [&](unsigned w, Eigen::Index begin, Eigen::Index end) {
            results[w] = chunk(model, a, begin, end, options, earliest);
        });
        result = combineChunks(results);
    }
    if (options.stop_at_failure && !result.ok()) {
        // the serial loop's outcome: it stopped at the first failure, whatever later chunks found
        result.failed = 1;
        if (result.first_beyond_limits != BatchResult::npos && result.first_beyond_limits > result.first_failure) {
            result.first_beyond_limits = BatchResult::npos;
            result.limits = Status{};
        }
        nanRows(a, result.first_failure + 1, N);
    }
    return result;
}

}  // namespace nocdyn::spatial
