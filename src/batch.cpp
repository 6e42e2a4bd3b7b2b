// Batch inverse dynamics of the general model (batch.hpp): the lean kernel over a range of
// samples, the full path for the rare samples it rejects, and a std::thread split.
#include "nocdyn/batch.hpp"

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "lean_kernel.hpp"
#include "nocdyn/dynamics.hpp"
#include "nocdyn/error.hpp"
#include "nocdyn/prr3/batch.hpp"

namespace nocdyn {

namespace {

using ConstRef = BatchInput;
using Ref = BatchOutput;

struct Arrays {
    const ConstRef& p;
    const ConstRef& dp;
    const ConstRef& ddp;
    Ref& u;
    Ref& du;
    Ref& ddu;
    Ref& tau;
};

/// A sample the kernel rejected (or with a non-finite input): the full path's Status and,
/// should it accept the sample (within rounding of a threshold), its values.
#if defined(__GNUC__)
__attribute__((noinline, cold))
#endif
Status
fullPath(const Model& model, Data& data, const Arrays& a, Eigen::Index k) {
    const Status status =
        inverseDynamics(model, data, a.p.row(k).transpose(), a.dp.row(k).transpose(), a.ddp.row(k).transpose());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int i = 0; i < model.actuators; ++i) {
        a.u(k, i) = status ? data.u(i) : nan;
        a.du(k, i) = status ? data.du(i) : nan;
        a.ddu(k, i) = status ? data.ddu(i) : nan;
        a.tau(k, i) = status ? data.tau(i) : nan;
    }
    return status;
}

// On x86-64 with GCC an AVX2+FMA clone is built beside the baseline one (as for
// inverseDynamicsFast).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(NOCDYN_NO_TARGET_CLONES)
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
BatchResult
chunk(const Model& model, const Arrays& a, Eigen::Index begin, Eigen::Index end) {
    BatchResult result;
    Data data(model);  // for rejected samples only: fixed capacity, no allocation
    const std::ptrdiff_t stride = a.u.outerStride();
    for (Eigen::Index k = begin; k < end; ++k) {
        const double p[3] = {a.p(k, 0), a.p(k, 1), a.p(k, 2)};
        const double dp[3] = {a.dp(k, 0), a.dp(k, 1), a.dp(k, 2)};
        const double ddp[3] = {a.ddp(k, 0), a.ddp(k, 1), a.ddp(k, 2)};
        // x - x is 0 for a finite x and NaN otherwise: one test for the nine inputs
        double zero = 0.0;
        for (int i = 0; i < 3; ++i) zero += (p[i] - p[i]) + (dp[i] - dp[i]) + (ddp[i] - ddp[i]);
        const double dtheta = p[0] - model.home(0);
        bool ok = false;
        if (zero == 0.0 && std::abs(dtheta) < 1.0e6) [[likely]] {
            double s, c;
            prr3::batch_detail::sinCos(dtheta, s, c);  // branch-free, exact below 1.6e6 rad
            const detail::lean::Out out{&a.u(k, 0), &a.du(k, 0), &a.ddu(k, 0), &a.tau(k, 0), stride};
            detail::lean::V3 W;
            ok = detail::lean::sample(model, c, s, p, dp, ddp, out, W);
        }
        if (ok) [[likely]]
            continue;
        if (const Status status = fullPath(model, data, a, k); !status && result.failed++ == 0) {
            result.first_failure = k;
            result.status = status;
        }
    }
    return result;
}

void requireShape(const char* name, Eigen::Index rows, Eigen::Index cols, Eigen::Index n, Eigen::Index m) {
    if (rows != n || cols != m) {
        throw Error(std::string("inverseDynamicsBatch: ") + name + " is " + std::to_string(rows) + " x " +
                    std::to_string(cols) + ", expected " + std::to_string(n) + " x " + std::to_string(m));
    }
}

}  // namespace

BatchResult inverseDynamicsBatch(const Model& model, const ConstRef& p, const ConstRef& dp, const ConstRef& ddp, Ref u,
                                 Ref du, Ref ddu, Ref tau, unsigned threads) {
    const Eigen::Index n = p.rows();
    requireShape("p", p.rows(), p.cols(), n, 3);
    requireShape("dp", dp.rows(), dp.cols(), n, 3);
    requireShape("ddp", ddp.rows(), ddp.cols(), n, 3);
    requireShape("u", u.rows(), u.cols(), n, model.actuators);
    requireShape("du", du.rows(), du.cols(), n, model.actuators);
    requireShape("ddu", ddu.rows(), ddu.cols(), n, model.actuators);
    requireShape("tau", tau.rows(), tau.cols(), n, model.actuators);
    if (u.outerStride() != du.outerStride() || u.outerStride() != ddu.outerStride() ||
        u.outerStride() != tau.outerStride()) {
        throw Error("inverseDynamicsBatch: u, du, ddu and tau must have the same layout");
    }
    const Arrays a{p, dp, ddp, u, du, ddu, tau};
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    if (threads == 1 || n < 2) return chunk(model, a, 0, n);

    // contiguous chunks, multiples of 8 samples so that no two threads share a cache line
    const Eigen::Index per = ((n + threads - 1) / threads + 7) / 8 * 8;
    std::vector<BatchResult> results(threads);
    std::vector<std::thread> workers;
    workers.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t) {
        const Eigen::Index begin = std::min(n, t * per), end = std::min(n, (t + 1) * per);
        workers.emplace_back([&, t, begin, end] { results[t] = chunk(model, a, begin, end); });
    }
    results[0] = chunk(model, a, 0, std::min(n, per));
    for (std::thread& w : workers) w.join();

    BatchResult total;
    for (const BatchResult& r : results) {  // chunks are in sample order: the first failure wins
        if (r.failed > 0 && total.failed == 0) {
            total.first_failure = r.first_failure;
            total.status = r.status;
        }
        total.failed += r.failed;
    }
    return total;
}

}  // namespace nocdyn
