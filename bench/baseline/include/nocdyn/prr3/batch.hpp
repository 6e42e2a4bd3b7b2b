// Batch inverse dynamics of the 3-PRR: many pose-space samples at once, vectorised across
// samples (structure of arrays), and a multi-threaded variant that uses every core.
//
// The batch computes what inverseDynamics (dynamics.hpp) computes per sample, u, du, ddu and
// tau, without storing the intermediate matrices. It needs no I or C: by eqs. 16 and 20-21,
//   tau = I ddu + C du = T^T M (T ddu + dT du) = T^T M dt = sum_i T_i^T M_i dt_i,
// the NOC applied to the inertia wrenches M_i dt_i of the seven bodies, whose accelerations
// dt_i follow from the limb kinematics (eqs. 3-5 and their time derivatives). The link and
// platform terms reach the actuators through T_{j+3} = U_{j+3} J_j^{-1} T_7 (eq. 30) and
// T_7 = H^{-1} D (eq. 31), i.e. tau = m_s ddu + g + D H^{-T} W with one 3 x 3 solve per sample
// (W: the platform-side wrench at C, g: the links' direct share on their sliders).
// Derivation and operation count: bench/README.md.
//
// Layout: Eigen::ArrayX3d is column-major, so column c holds coordinate c of every sample
// contiguously (theta of all samples, then x, then y): a structure of arrays. Row k is
// sample k.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include <Eigen/Core>

#include "nocdyn/detail/fast_math.hpp"
#include "nocdyn/prr3/model.hpp"
#include "nocdyn/prr3/status.hpp"

namespace nocdyn::prr3 {

/// Inputs and outputs of n samples, structure of arrays (row k = sample k).
struct SampleBatch {
    SampleBatch() = default;
    explicit SampleBatch(Eigen::Index n) { resize(n); }
    /// Sizes every array for n samples (allocates; not for the real-time path).
    void resize(Eigen::Index n) {
        for (Eigen::ArrayX3d* a : {&p, &dp, &ddp, &u, &du, &ddu, &tau}) a->resize(n, 3);
    }
    [[nodiscard]] Eigen::Index size() const { return p.rows(); }

    Eigen::ArrayX3d p;    ///< input: pose [theta, x_c, y_c] (eq. 1) [rad, m, m]
    Eigen::ArrayX3d dp;   ///< input: platform twist dp/dt (eq. 2)
    Eigen::ArrayX3d ddp;  ///< input: d2p/dt2
    Eigen::ArrayX3d u;    ///< output: actuator displacements [m]
    Eigen::ArrayX3d du;   ///< output: actuator rates [m/s]
    Eigen::ArrayX3d ddu;  ///< output: actuator accelerations [m/s^2]
    Eigen::ArrayX3d tau;  ///< output: actuator forces (eq. 20) [N]
};

/// Outcome of a batch: how many samples failed, the first of them and its Status (exactly
/// what inverseDynamics returns for that sample). Failed samples' outputs are NaN.
struct BatchStatus {
    static constexpr Eigen::Index npos = std::numeric_limits<Eigen::Index>::max();
    Eigen::Index failed = 0;
    Eigen::Index first_failure = npos;
    Status status;  ///< of sample first_failure; ok when failed == 0
    [[nodiscard]] bool ok() const { return failed == 0; }
};

/// Samples [begin, end) of the batch on the calling thread, vectorised across samples
/// (AVX2/FMA code chosen at run time on x86-64 when the CPU has it). Allocation-free.
BatchStatus inverseDynamicsBatch(const Model& model, SampleBatch& batch, Eigen::Index begin, Eigen::Index end);

/// The whole batch on the calling thread.
BatchStatus inverseDynamicsBatch(const Model& model, SampleBatch& batch);

/// The whole batch split into contiguous chunks over `threads` std::threads (0: one per
/// hardware thread, std::thread::hardware_concurrency()); the calling thread runs one chunk.
/// Starts its threads on every call (tens of microseconds): worth it for large batches.
BatchStatus inverseDynamicsBatchParallel(const Model& model, SampleBatch& batch, unsigned threads = 0);

}  // namespace nocdyn::prr3

namespace nocdyn::prr3::batch_detail {

// The kernel must be inlined into the batch loop for that loop to vectorise.
#if defined(__GNUC__)
#define NOCDYN_KERNEL_INLINE inline __attribute__((always_inline))
#define NOCDYN_UNROLL _Pragma("GCC unroll 3")
#else
#define NOCDYN_KERNEL_INLINE inline
#define NOCDYN_UNROLL
#endif

/// The kernel's constants of a model, computed from its geometry and inertia (the Model's
/// constructor stores them in Model::kernel; read those rather than calling this per sample).
Constants constants(const Model& model);

/// Scalar operations the kernel needs beyond + - * / and comparisons; overloaded for
/// bench/flop_count.cpp's counting scalar.
NOCDYN_KERNEL_INLINE double sqrtOf(double x) { return std::sqrt(x); }
NOCDYN_KERNEL_INLINE double absOf(double x) { return std::abs(x); }
NOCDYN_KERNEL_INLINE double select(bool c, double a, double b) { return c ? a : b; }

/// sin x and cos x without branches or calls (detail/fast_math.hpp).
using fastmath::sinCos;

/// One sample given s = sin theta and c = cos theta: in = [p, dp, ddp] (9, in[0] = theta is
/// not read), out = [u, du, ddu, tau] (12). Returns false when the per-sample path would fail
/// (pose out of reach, D or H too ill-conditioned). The one kernel of the batch (through
/// sample() below) and of the lean per-sample entry (fast.hpp, with libm's sin and cos).
template <class S>
NOCDYN_KERNEL_INLINE bool sampleGivenSinCos(const Constants& k, const S& s, const S& c, const S* in, S* out) {
    const S &x = in[1], &y = in[2];
    const S &omega = in[3], &vx = in[4], &vy = in[5];
    const S &alpha = in[6], &ax = in[7], &ay = in[8];
    bool valid = true;

    S h[kLimbs][3];                                    // rows of H (eq. 7): [a_j x f_j, f_j]
    S cos_A[kLimbs];                                   // d_j = cos phi_Aj (eq. 6)
    S direct[kLimbs];                                  // m_s ddu_j + the links' share acting on slider j directly
    S W[3] = {alpha * k.I_P, ax * k.m_P, ay * k.m_P};  // platform side: M_7 dt_7 to start
    NOCDYN_UNROLL
    for (int j = 0; j < kLimbs; ++j) {
        // position (eqs. 37-42): a = M_j - C, d_j^M, phi_Aj, f_j = m_j / l, u_j
        const S a_x = c * k.Ml[j][0] - s * k.Ml[j][1];
        const S a_y = s * k.Ml[j][0] + c * k.Ml[j][1];
        const S M_x = x + a_x, M_y = y + a_y;
        const S d = k.n[j][0] * M_x + k.n[j][1] * M_y - k.nB[j];
        valid = valid & (d > 0.0) & (d < k.l);
        const S sin_A = d * k.inv_l;
        const S cA = sqrtOf((1.0 - sin_A) * (1.0 + sin_A));
        const S f_x = cA * k.e[j][0] + sin_A * k.n[j][0];
        const S f_y = cA * k.e[j][1] + sin_A * k.n[j][1];
        out[j] = k.e[j][0] * M_x + k.e[j][1] * M_y - k.l * cA - k.eB[j];  // u_j = e_j . A_j - ...
        // velocity: the link is rigid, (v_M - du_j e_j) . f_j = 0 with v_M = dc + omega E a,
        // i.e. row j of eq. 5, du_j = h_j . t_M / d_j; the link turns at dphi_Aj
        const S inv_cA = 1.0 / cA;
        const S vM_x = vx - omega * a_y, vM_y = vy + omega * a_x;
        const S du = (f_x * vM_x + f_y * vM_y) * inv_cA;
        const S vr_x = vM_x - du * k.e[j][0], vr_y = vM_y - du * k.e[j][1];
        const S phi_A_dot = (f_x * vr_y - f_y * vr_x) * k.inv_l;  // (E f) . v_rel / l
        // acceleration: d/dt of the same, a_M = ddc + alpha E a - omega^2 a
        const S w2 = omega * omega;
        const S aM_x = ax - alpha * a_y - w2 * a_x, aM_y = ay + alpha * a_x - w2 * a_y;
        const S ddu = (f_x * aM_x + f_y * aM_y + k.l * phi_A_dot * phi_A_dot) * inv_cA;
        const S ar_x = aM_x - ddu * k.e[j][0], ar_y = aM_y - ddu * k.e[j][1];
        const S phi_A_ddot = (f_x * ar_y - f_y * ar_x) * k.inv_l;
        out[3 + j] = du;
        out[6 + j] = ddu;
        // link inertia wrench (eq. 12): F = m_L a_G with a_G = ddu e + (l_c/l) a_rel, N = I_L ddphi_A
        const S F_x = k.m_L * (ddu * k.e[j][0] + k.rho * ar_x);
        const S F_y = k.m_L * (ddu * k.e[j][1] + k.rho * ar_y);
        const S N = k.I_L * phi_A_ddot;
        // its power under t_{j+3} = U_{j+3} gamma_dot_j (eq. 28): v_G = (1 - l_c/l) v_A + (l_c/l) v_M,
        // omega_link = E f . (v_M - v_A) / l: a force g at M_j on the platform side, and
        // (1 - l_c/l) F . e_j + N sin phi_Aj / l directly on slider j (plus m_s ddu_j, eq. 24)
        const S N_l = N * k.inv_l;
        const S g_x = k.rho * F_x - N_l * f_y;
        const S g_y = k.rho * F_y + N_l * f_x;
        direct[j] = k.m_s * ddu + (1.0 - k.rho) * (F_x * k.e[j][0] + F_y * k.e[j][1]) + N_l * sin_A;
        W[0] = W[0] + (a_x * g_y - a_y * g_x);
        W[1] = W[1] + g_x;
        W[2] = W[2] + g_y;
        h[j][0] = a_x * f_y - a_y * f_x;
        h[j][1] = f_x;
        h[j][2] = f_y;
        cos_A[j] = cA;
    }
    // eq. 31: tau = ... + T_7^T W = D H^{-T} W. H^{-1} has columns (h_{j+1} x h_{j+2}) / det H.
    S adj[kLimbs][3];
    NOCDYN_UNROLL
    for (int j = 0; j < kLimbs; ++j) {
        const S* p = h[(j + 1) % 3];
        const S* q = h[(j + 2) % 3];
        adj[j][0] = p[1] * q[2] - p[2] * q[1];
        adj[j][1] = p[2] * q[0] - p[0] * q[2];
        adj[j][2] = p[0] * q[1] - p[1] * q[0];
    }
    const S det = h[0][0] * adj[0][0] + h[0][1] * adj[0][1] + h[0][2] * adj[0][2];
    const S inv_det = 1.0 / det;
    NOCDYN_UNROLL
    for (int j = 0; j < kLimbs; ++j) {
        const S lambda = (W[0] * adj[j][0] + W[1] * adj[j][1] + W[2] * adj[j][2]) * inv_det;
        out[9 + j] = direct[j] + cos_A[j] * lambda;
    }
    // the per-sample path's conditioning checks (kinematics.cpp): cond D = max d / min d, and
    // the 1-norm condition number of H diag(1/r, 1, 1), both at most max_condition
    S d_max = cos_A[0], d_min = cos_A[0];
    NOCDYN_UNROLL
    for (int j = 1; j < kLimbs; ++j) {
        d_max = select(cos_A[j] > d_max, cos_A[j], d_max);
        d_min = select(cos_A[j] < d_min, cos_A[j], d_min);
    }
    valid = valid & (d_max <= k.max_condition * d_min);
    S norm_H = (absOf(h[0][0]) + absOf(h[1][0]) + absOf(h[2][0])) * (1.0 / k.r);
    S norm_inv = 0.0;
    NOCDYN_UNROLL
    for (int i = 1; i < 3; ++i) {
        const S col = absOf(h[0][i]) + absOf(h[1][i]) + absOf(h[2][i]);
        norm_H = select(col > norm_H, col, norm_H);
    }
    NOCDYN_UNROLL
    for (int j = 0; j < kLimbs; ++j) {
        const S col = k.r * absOf(adj[j][0]) + absOf(adj[j][1]) + absOf(adj[j][2]);
        norm_inv = select(col > norm_inv, col, norm_inv);
    }
    valid = valid & (norm_H * norm_inv <= k.max_condition * absOf(det));
    return valid;
}

/// One sample: in = [p, dp, ddp] (9), out = [u, du, ddu, tau] (12), with the branch-free
/// sinCos above (exact for |theta| < 1.6e6). Returns false as sampleGivenSinCos.
template <class S>
NOCDYN_KERNEL_INLINE bool sample(const Constants& k, const S* in, S* out) {
    S s, c;
    sinCos(in[0], s, c);
    return sampleGivenSinCos(k, s, c, in, out);
}

}  // namespace nocdyn::prr3::batch_detail
