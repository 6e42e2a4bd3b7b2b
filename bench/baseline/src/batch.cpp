// Batch inverse dynamics (see batch.hpp): a sample-major loop over structure-of-arrays
// columns that the compiler vectorises across samples, a scalar fix-up pass through the
// per-sample path for the rare samples the vector kernel does not handle, and a std::thread
// split over the cores.
#include "nocdyn/prr3/batch.hpp"

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "nocdyn/prr3/dynamics.hpp"

namespace nocdyn::prr3 {
namespace batch_detail {

Constants constants(const Model& model) {
    Constants k{};
    for (int j = 0; j < kLimbs; ++j) {
        for (int i = 0; i < 2; ++i) {
            k.e[j][i] = model.e[j](i);
            k.n[j][i] = model.n[j](i);
            k.Ml[j][i] = model.M_local[j](i);
        }
        k.nB[j] = model.n[j].dot(model.B[j]);
        k.eB[j] = model.e[j].dot(model.B[j]) + model.s_ref[j];
    }
    k.l = model.l;
    k.inv_l = 1.0 / model.l;
    k.rho = model.l_c / model.l;
    k.m_s = model.M[sliderBody(0)].mass;
    k.m_L = model.M[linkBody(0)].mass;
    k.I_L = model.M[linkBody(0)].inertia;
    k.m_P = model.M[kPlatformBody].mass;
    k.I_P = model.M[kPlatformBody].inertia;
    k.r = model.r;
    k.max_condition = model.parameters.max_condition;
    return k;
}

}  // namespace batch_detail

namespace {

/// |theta| beyond which the kernel's Cody-Waite reduction is no longer exact.
constexpr double kTrigLimit = 1.0e6;

struct Columns {
    const double* in[9];
    double* out[12];
};

Columns columns(SampleBatch& b) {
    Columns c{};
    const Eigen::ArrayX3d* inputs[3] = {&b.p, &b.dp, &b.ddp};
    Eigen::ArrayX3d* outputs[4] = {&b.u, &b.du, &b.ddu, &b.tau};
    for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) c.in[3 * a + i] = inputs[a]->col(i).data();
    for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) c.out[3 * a + i] = outputs[a]->col(i).data();
    return c;
}

// The vector loop. On x86-64 with GCC, an AVX2+FMA clone is built beside the baseline one and
// chosen at load time when the CPU supports it (4 samples per instruction instead of 2).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(NOCDYN_NO_TARGET_CLONES)
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
void kernelLoop(const batch_detail::Constants& constants, const Columns& c, Eigen::Index begin, Eigen::Index end) {
    const batch_detail::Constants k = constants;  // a local copy: no store below can alias it
    const double* __restrict in0 = c.in[0];
    const double* __restrict in1 = c.in[1];
    const double* __restrict in2 = c.in[2];
    const double* __restrict in3 = c.in[3];
    const double* __restrict in4 = c.in[4];
    const double* __restrict in5 = c.in[5];
    const double* __restrict in6 = c.in[6];
    const double* __restrict in7 = c.in[7];
    const double* __restrict in8 = c.in[8];
    double* __restrict o[12];
    for (int i = 0; i < 12; ++i) o[i] = c.out[i];
    double* __restrict o0 = o[0];
    double* __restrict o1 = o[1];
    double* __restrict o2 = o[2];
    double* __restrict o3 = o[3];
    double* __restrict o4 = o[4];
    double* __restrict o5 = o[5];
    double* __restrict o6 = o[6];
    double* __restrict o7 = o[7];
    double* __restrict o8 = o[8];
    double* __restrict o9 = o[9];
    double* __restrict o10 = o[10];
    double* __restrict o11 = o[11];
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // the columns are distinct arrays: no sample reads what another writes
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
    for (Eigen::Index s = begin; s < end; ++s) {
        const double in[9] = {in0[s], in1[s], in2[s], in3[s], in4[s], in5[s], in6[s], in7[s], in8[s]};
        double out[12];
        const bool valid = batch_detail::sample(k, in, out);
        // a failed sample's tau is NaN, so that the fix-up pass below finds it
        o0[s] = out[0];
        o1[s] = out[1];
        o2[s] = out[2];
        o3[s] = out[3];
        o4[s] = out[4];
        o5[s] = out[5];
        o6[s] = out[6];
        o7[s] = out[7];
        o8[s] = out[8];
        o9[s] = valid ? out[9] : nan;
        o10[s] = out[10];
        o11[s] = out[11];
    }
}

}  // namespace

BatchStatus inverseDynamicsBatch(const Model& model, SampleBatch& batch, Eigen::Index begin, Eigen::Index end) {
    const batch_detail::Constants& k = model.kernel;
    const Columns c = columns(batch);
    kernelLoop(k, c, begin, end);

    // Fix-up: samples the kernel flagged (tau_1 NaN) or whose angle is beyond its exact range
    // take the per-sample path, which gives their Status (and values, for huge angles).
    BatchStatus result;
    Data data;
    const double* theta = c.in[0];
    const double* tau_0 = c.out[9];
    for (Eigen::Index s = begin; s < end; ++s) {
        if (!std::isnan(tau_0[s]) && std::abs(theta[s]) < kTrigLimit) continue;
        const Status status = inverseDynamics(model, data, batch.p.row(s).transpose(), batch.dp.row(s).transpose(),
                                              batch.ddp.row(s).transpose());
        if (status) {
            batch.u.row(s) = data.u.transpose();
            batch.du.row(s) = data.du.transpose();
            batch.ddu.row(s) = data.ddu.transpose();
            batch.tau.row(s) = data.tau.transpose();
            continue;
        }
        for (Eigen::ArrayX3d* a : {&batch.u, &batch.du, &batch.ddu, &batch.tau})
            a->row(s).setConstant(std::numeric_limits<double>::quiet_NaN());
        if (result.failed++ == 0) {
            result.first_failure = s;
            result.status = status;
        }
    }
    return result;
}

BatchStatus inverseDynamicsBatch(const Model& model, SampleBatch& batch) {
    return inverseDynamicsBatch(model, batch, 0, batch.size());
}

BatchStatus inverseDynamicsBatchParallel(const Model& model, SampleBatch& batch, unsigned threads) {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    const Eigen::Index n = batch.size();
    // contiguous chunks, multiples of 8 samples so that no two threads share a cache line
    const Eigen::Index per = ((n + threads - 1) / threads + 7) / 8 * 8;
    std::vector<BatchStatus> results(threads);
    std::vector<std::thread> workers;
    workers.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t) {
        const Eigen::Index begin = std::min(n, t * per), end = std::min(n, (t + 1) * per);
        workers.emplace_back([&, t, begin, end] { results[t] = inverseDynamicsBatch(model, batch, begin, end); });
    }
    results[0] = inverseDynamicsBatch(model, batch, 0, std::min(n, per));
    for (std::thread& w : workers) w.join();

    BatchStatus total;
    for (const BatchStatus& r : results) {  // chunks are in sample order: the first failure wins
        if (r.failed > 0 && total.failed == 0) {
            total.first_failure = r.first_failure;
            total.status = r.status;
        }
        total.failed += r.failed;
    }
    return total;
}

}  // namespace nocdyn::prr3
