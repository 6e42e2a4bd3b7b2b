// The batch's packet loop (batch.cpp): samples [begin, end) of the lean kernel in packets of
// four or eight samples, the full path for the samples it rejects, the limits checked on the
// values in registers. Included by batch.cpp (four-sample packets, an AVX2+FMA clone beside the
// baseline) and batch_avx512.cpp (eight, built for x86-64-v4). Everything here but the
// arrays' struct (data only) and chunk8's declaration has internal linkage: each file compiles
// its own copy for its own instruction set, and no inline function of one can stand in for the
// other's. Internal (not installed).
#pragma once

#include <algorithm>

#include "nocdyn/detail/sanitizer.hpp"
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

#include "lean_kernel.hpp"
#include "limb_lanes.hpp"
#include "nocdyn/batch.hpp"
#include "nocdyn/detail/fast_math.hpp"
#include "nocdyn/dynamics.hpp"

// A packet lives in registers inside chunkOf (everything it calls is inlined): the note that a
// vector's ABI depends on AVX does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace nocdyn {

namespace detail {

/// The arrays of one batch call (inverseDynamicsBatch's arguments).
struct BatchArrays {
    const BatchInput& p;
    const BatchInput& dp;
    const BatchInput& ddp;
    BatchOutput& u;
    BatchOutput& du;
    BatchOutput& ddu;
    BatchOutput& tau;
    PoseColumns order;
    ActuatorLimits limits;
};

/// Samples [begin, end) in packets of eight (batch_avx512.cpp; only where the CPU has
/// x86-64-v4).
BatchResult chunk8(const Model& model, const BatchArrays& a, Eigen::Index begin, Eigen::Index end);

}  // namespace detail

namespace {

using ConstRef = BatchInput;
using Ref = BatchOutput;

using Arrays = detail::BatchArrays;

/// The actuated joints' limits in checkJointLimits' order, then the actuators' efforts.
struct LimitTable {
    int count = 0;
    std::array<int, kMaxActuators> actuator{};                       ///< limb by limb, joint by joint
    std::array<double, kMaxActuators> effort{};                      ///< by actuator
    std::array<double, kMaxActuators> lower{}, upper{}, velocity{};  ///< of actuator a's joint

    explicit LimitTable(const Model& model) {
        for (int j = 0; j < model.limbs; ++j)
            for (std::size_t k = 0; k < 3; ++k)
                if (const int a = model.limb[static_cast<std::size_t>(j)].actuator[k]; a >= 0) actuator[count++] = a;
        for (int a = 0; a < model.actuators; ++a) {
            const auto aa = static_cast<std::size_t>(a);
            const JointLimits& lim = model.limb[static_cast<std::size_t>(model.actuator_limb[aa])]
                                         .limits[static_cast<std::size_t>(model.actuator_joint[aa])];
            effort[aa] = lim.effort;
            lower[aa] = lim.lower;
            upper[aa] = lim.upper;
            velocity[aa] = lim.velocity;
        }
    }

    /// The first limit sample (u(a), du(a), tau(a)) exceeds, or ok.
    template <class Value>
    [[nodiscard]] Status check(const Model& model, const Value& u, const Value& du, const Value& tau) const {
        for (int i = 0; i < count; ++i) {
            const auto a = static_cast<std::size_t>(actuator[static_cast<std::size_t>(i)]);
            const int j = model.actuator_limb[a], k = model.actuator_joint[a];
            const JointLimits& lim = model.limb[static_cast<std::size_t>(j)].limits[static_cast<std::size_t>(k)];
            const double q = u(static_cast<int>(a)), dq = du(static_cast<int>(a));
            if (!(q >= lim.lower && q <= lim.upper)) return limitStatus(StatusCode::joint_limit_exceeded, j, k, q);
            if (!(std::abs(dq) <= lim.velocity)) return limitStatus(StatusCode::velocity_exceeded, j, k, dq);
        }
        for (int a = 0; a < model.actuators; ++a) {
            const auto aa = static_cast<std::size_t>(a);
            if (!(std::abs(tau(a)) <= effort[aa])) {
                return limitStatus(StatusCode::effort_exceeded, model.actuator_limb[aa], model.actuator_joint[aa],
                                   tau(a));
            }
        }
        return {};
    }

    static Status limitStatus(StatusCode code, int limb, int joint, double value) {
        Status s{code, limb, value};
        s.joint = joint;
        return s;
    }
};

/// Row k of a pose array in the core's order (batch.hpp's poseRow, with internal linkage: see
/// the top of this file).
Vector3 poseAt(const BatchInput& a, Eigen::Index k, PoseColumns order) {
    return {a(k, poseColumn(order, 0)), a(k, poseColumn(order, 1)), a(k, poseColumn(order, 2))};
}

/// A sample the kernel rejected (or with a non-finite input): the full path's Status and,
/// should it accept the sample (within rounding of a threshold), its values.
#if defined(__GNUC__)
__attribute__((noinline, cold))
#endif
Status
fullPath(const Model& model, Data& data, const Arrays& a, Eigen::Index k) {
    Status status =
        inverseDynamics(model, data, poseAt(a.p, k, a.order), poseAt(a.dp, k, a.order), poseAt(a.ddp, k, a.order));
    // finite input whose results overflow (huge rates or accelerations): a failed sample, as
    // an actuator effort that is not finite, never a non-finite number in the outputs
    for (int i = 0; status && i < model.actuators; ++i) {
        const double values[4] = {data.tau(i), data.u(i), data.du(i), data.ddu(i)};
        for (const double v : values) {
            if (!std::isfinite(v)) {
                status = {StatusCode::effort_exceeded, model.actuator_limb[static_cast<std::size_t>(i)], v};
                status.joint = model.actuator_joint[static_cast<std::size_t>(i)];
                break;
            }
        }
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int i = 0; i < model.actuators; ++i) {
        a.u(k, i) = status ? data.u(i) : nan;
        a.du(k, i) = status ? data.du(i) : nan;
        a.ddu(k, i) = status ? data.ddu(i) : nan;
        a.tau(k, i) = status ? data.tau(i) : nan;
    }
    return status;
}

/// Every lane of `l` the limb's constant (detail::lean::SplatLimb): once per chunk.
template <int kN>
void splatLimb(const LimbModel& limb, LimbLanesOf<kN>& l) {
    for (std::size_t lane = 0; lane < kN; ++lane) detail::fillLane(l, lane, limb);
}

/// packets(make<kCode>()) with the terms of the robot's uniform limbs, kind * 3 + actuated
/// joint = model.uniform_limbs; false when its limbs are not uniform.
template <class Packets, class Make, int... kCodes>
NOCDYN_ALWAYS_INLINE bool uniformPackets(const Model& model, const Make& make, const Packets& packets,
                                         std::integer_sequence<int, kCodes...> /*codes*/) {
    return ((model.uniform_limbs == kCodes && (packets(make.template operator()<kCodes>()), true)) || ...);
}

/// NumPy's C order of an N x 3 array: a packet's kLanes rows are 3 kLanes values side by side,
/// three packets A, B, C of the flat values v_f, f = 3 l + i for lane l and column i. Column i
/// is two shuffles (vpermt2pd on AVX-512): lanes whose f falls in A
/// or B from the pair (A, B), then the rest from C. fromRows: the first shuffle's indices
/// (first = true) or the second's for column i; toRows: the same for output packet v of
/// columns c_0, c_1 (first) then c_2.
template <int N>
constexpr std::array<std::int64_t, N> fromRows(int i, bool first) {
    std::array<std::int64_t, N> m{};
    for (int l = 0; l < N; ++l) {
        const int f = 3 * l + i;
        m[static_cast<std::size_t>(l)] = first ? (f < 2 * N ? f : 0) : (f < 2 * N ? l : N + f - 2 * N);
    }
    return m;
}
template <int N>
constexpr std::array<std::int64_t, N> toRows(int v, bool first) {
    std::array<std::int64_t, N> m{};
    for (int q = 0; q < N; ++q) {
        const int f = v * N + q, l = f / 3, i = f % 3;
        m[static_cast<std::size_t>(q)] = first ? (i < 2 ? i * N + l : 0) : (i < 2 ? q : N + l);
    }
    return m;
}
/// Column kI of the kLanes rows of 3 values in A, B, C (fromRows' indices), or output packet
/// kI of columns A, B, C (toRows'): two shuffles with constant indices (__builtin_shufflevector).
template <bool kToRows, int kI, class P, std::size_t... kL>
NOCDYN_ALWAYS_INLINE P shuffled(const P& A, const P& B, const P& C, std::index_sequence<kL...> /*lanes*/) {
    constexpr int kN = fastmath::kLanesOf<P>;
    if constexpr (kToRows) {
        return __builtin_shufflevector(__builtin_shufflevector(A, B, toRows<kN>(kI, true)[kL]...), C,
                                       toRows<kN>(kI, false)[kL]...);
    } else {
        return __builtin_shufflevector(__builtin_shufflevector(A, B, fromRows<kN>(kI, true)[kL]...), C,
                                       fromRows<kN>(kI, false)[kL]...);
    }
}
/// Columns 0, 1, 2 of the kLanes rows of 3 values at `at`.
template <class P>
NOCDYN_ALWAYS_INLINE void columnsOfRows(const double* at, P (&c)[3]) {
    constexpr int kN = fastmath::kLanesOf<P>;
    constexpr auto kLanes = std::make_index_sequence<kN>{};
    P A, B, C;
    std::memcpy(&A, at, sizeof(P));
    std::memcpy(&B, at + kN, sizeof(P));
    std::memcpy(&C, at + 2 * static_cast<std::ptrdiff_t>(kN), sizeof(P));
    c[0] = shuffled<false, 0>(A, B, C, kLanes);
    c[1] = shuffled<false, 1>(A, B, C, kLanes);
    c[2] = shuffled<false, 2>(A, B, C, kLanes);
}
/// The kLanes rows of 3 values at `at` from columns c_0, c_1, c_2 (columnsOfRows inverted).
template <class P>
NOCDYN_ALWAYS_INLINE void rowsOfColumns(const P& c0, const P& c1, const P& c2, double* at) {
    constexpr int kN = fastmath::kLanesOf<P>;
    constexpr auto kLanes = std::make_index_sequence<kN>{};
    const P v[3] = {shuffled<true, 0>(c0, c1, c2, kLanes), shuffled<true, 1>(c0, c1, c2, kLanes),
                    shuffled<true, 2>(c0, c1, c2, kLanes)};
    std::memcpy(at, v, sizeof v);
}

/// NumPy's C order of an N x 4 array (a robot of four actuators): output packet v holds rows
/// v kLanes/4 ... (v + 1) kLanes/4 - 1, row by row. Each is three shuffles: the pairs
/// (c_0, c_1) and (c_2, c_3) of its rows side by side (pairsOfRows' indices), then the two
/// interleaved row by row (rowsOfPairs').
template <int N>
constexpr std::array<std::int64_t, N> pairsOfRows(int v) {
    std::array<std::int64_t, N> m{};  // past the packet's rows: unused (lane 0)
    for (int i = 0; i < N / 4; ++i) {
        const int row = v * (N / 4) + i;
        m[2 * static_cast<std::size_t>(i)] = row;
        m[2 * static_cast<std::size_t>(i) + 1] = N + row;
    }
    return m;
}
template <int N>
constexpr std::array<std::int64_t, N> rowsOfPairs() {
    std::array<std::int64_t, N> m{};
    for (int q = 0; q < N; ++q) {
        const int i = q / 4, column = q % 4;
        m[static_cast<std::size_t>(q)] = (column < 2 ? 0 : N) + 2 * i + column % 2;
    }
    return m;
}
template <int kV, class P, std::size_t... kL>
NOCDYN_ALWAYS_INLINE P rowsOf4(const P* c, std::index_sequence<kL...> /*lanes*/) {
    constexpr int kN = fastmath::kLanesOf<P>;
    return __builtin_shufflevector(__builtin_shufflevector(c[0], c[1], pairsOfRows<kN>(kV)[kL]...),
                                   __builtin_shufflevector(c[2], c[3], pairsOfRows<kN>(kV)[kL]...),
                                   rowsOfPairs<kN>()[kL]...);
}
/// The kLanes rows of 4 values at `at` from columns c[0..3].
template <class P>
NOCDYN_ALWAYS_INLINE void rowsOfColumns4(const P* c, double* at) {
    constexpr auto kLanes = std::make_index_sequence<fastmath::kLanesOf<P>>{};
    const P v[4] = {rowsOf4<0>(c, kLanes), rowsOf4<1>(c, kLanes), rowsOf4<2>(c, kLanes), rowsOf4<3>(c, kLanes)};
    std::memcpy(at, v, sizeof v);
}

/// Samples [begin, end) in packets of P (four or eight samples, fastmath::Pack or Pack8).
template <class P>
NOCDYN_ALWAYS_INLINE BatchResult chunkOf(const Model& model, const Arrays& a, Eigen::Index begin, Eigen::Index end) {
    using PackMask = fastmath::Mask<P>;
    constexpr int kLanes = fastmath::kLanesOf<P>;
    BatchResult result;
    Data data(model);  // for rejected samples only: fixed capacity, no allocation
    const int n = model.actuators;
    const LimitTable limits(model);
    bool check_limits = a.limits == ActuatorLimits::check;
    // Eigen's default (column-major) layout: a packet's samples are adjacent in each column
    const bool contiguous_in = a.p.innerStride() == 1 && a.dp.innerStride() == 1 && a.ddp.innerStride() == 1;
    // NumPy's C order of N x 3 arrays (rows of 3 adjacent values)
    const bool rows_of_3_in = a.p.innerStride() == 3 && a.dp.innerStride() == 3 && a.ddp.innerStride() == 3 &&
                              a.p.outerStride() == 1 && a.dp.outerStride() == 1 && a.ddp.outerStride() == 1;
    // the outputs in C order, rows of n = 3 or 4 adjacent values (transposed in packets)
    const bool rows_out = (n == 3 || n == 4) && a.u.outerStride() == 1 && a.u.innerStride() == n &&
                          a.du.innerStride() == n && a.ddu.innerStride() == n && a.tau.innerStride() == n;
    const bool contiguous_out =
        a.u.innerStride() == 1 && a.du.innerStride() == 1 && a.ddu.innerStride() == 1 && a.tau.innerStride() == 1;
    // pointers and strides read once: a packet's stores (memcpy) may alias any object, and
    // would make the compiler read them again from the arrays at every store
    // (element (k, i) at data[k * step + i * stride]: step 1 for Eigen's layout, the row's
    // length for NumPy's C order)
    const double *const in_p = a.p.data(), *const in_dp = a.dp.data(), *const in_ddp = a.ddp.data();
    const Eigen::Index stride_p = a.p.outerStride(), stride_dp = a.dp.outerStride(), stride_ddp = a.ddp.outerStride();
    const Eigen::Index step_p = a.p.innerStride(), step_dp = a.dp.innerStride(), step_ddp = a.ddp.innerStride();
    // the column of the core's coordinate i (theta, x, y): the pose order of the caller's arrays
    // taken by the gathers' index mapping, no pass or copy of its own
    const int column[3] = {poseColumn(a.order, 0), poseColumn(a.order, 1), poseColumn(a.order, 2)};
    double *const out_u = a.u.data(), *const out_du = a.du.data(), *const out_ddu = a.ddu.data(),
                  *const out_tau = a.tau.data();
    const Eigen::Index stride_out = a.u.outerStride();  // the same for the four (checked)
    const Eigen::Index step_u = a.u.innerStride(), step_du = a.du.innerStride(), step_ddu = a.ddu.innerStride(),
                       step_tau = a.tau.innerStride();
    // the packet's samples of column i of an array with rows `step` apart
    const auto gather = [](const double* at, Eigen::Index step) NOCDYN_INLINE_LAMBDA {
        P v;
        for (int l = 0; l < kLanes; ++l) v[l] = at[l * step];
        return v;
    };
    const auto scatter = [](double* at, Eigen::Index step, const P& v) NOCDYN_INLINE_LAMBDA {
        for (int l = 0; l < kLanes; ++l) at[l * step] = v[l];
    };
    // the packets, compiled for the robot's limbs (`terms`: the kind and actuated joint of a
    // uniform robot, or the kind read per limb), their constants splatted into packets once
    // (the pointers, strides and limits by value: a store to the outputs may alias any object
    // whose address is taken, and would make the compiler read them again at every store)
    const auto packets = [=, &model, &result, &check_limits, &data](const auto terms) NOCDYN_INLINE_LAMBDA {
        for (Eigen::Index k = begin; k < end; k += kLanes) {
            // lane l = sample k + l; past the end, the last sample again (not written)
            const int lanes = static_cast<int>(std::min<Eigen::Index>(kLanes, end - k));
            P p[3], dp[3], ddp[3];
            if (lanes == kLanes && contiguous_in) [[likely]] {
                // column i of each input holds the packet's samples side by side
                for (int i = 0; i < 3; ++i) {
                    std::memcpy(&p[i], in_p + k + column[i] * stride_p, sizeof(P));
                    std::memcpy(&dp[i], in_dp + k + column[i] * stride_dp, sizeof(P));
                    std::memcpy(&ddp[i], in_ddp + k + column[i] * stride_ddp, sizeof(P));
                }
            } else if (lanes == kLanes && rows_of_3_in) {
                // NumPy's C order: a packet's rows of 3 values side by side, transposed
                P cols[3];
                columnsOfRows(in_p + k * 3, cols);
                for (int i = 0; i < 3; ++i) p[i] = cols[column[i]];
                columnsOfRows(in_dp + k * 3, cols);
                for (int i = 0; i < 3; ++i) dp[i] = cols[column[i]];
                columnsOfRows(in_ddp + k * 3, cols);
                for (int i = 0; i < 3; ++i) ddp[i] = cols[column[i]];
            } else if (lanes == kLanes) {
                // any other layout (a strided view)
                for (int i = 0; i < 3; ++i) {
                    p[i] = gather(in_p + k * step_p + column[i] * stride_p, step_p);
                    dp[i] = gather(in_dp + k * step_dp + column[i] * stride_dp, step_dp);
                    ddp[i] = gather(in_ddp + k * step_ddp + column[i] * stride_ddp, step_ddp);
                }
            } else {
                for (int l = 0; l < kLanes; ++l) {
                    const Eigen::Index s = k + std::min(l, lanes - 1);
                    for (int i = 0; i < 3; ++i) {
                        p[i][l] = a.p(s, column[i]), dp[i][l] = a.dp(s, column[i]), ddp[i][l] = a.ddp(s, column[i]);
                    }
                }
            }
            // 0 x is 0 for a finite x and NaN otherwise: one test for the nine inputs; beyond
            // 1e6 rad the branch-free sinCos is no longer exact (the full path takes libm's)
            P zero = P{};
            for (int i = 0; i < 3; ++i) zero += p[i] * 0.0 + dp[i] * 0.0 + ddp[i] * 0.0;
            const P dtheta = p[0] - model.home(0);
            P s, c;
            fastmath::sinCos(dtheta, s, c);
            P u[kMaxActuators], du[kMaxActuators], ddu[kMaxActuators], tau[kMaxActuators];
            const detail::lean::Out<P> out{u, du, ddu, tau, 1};
            detail::lean::V3<P> W;
            PackMask ok = (zero == 0.0) & (fastmath::absOf(dtheta) < 1.0e6) &
                          detail::lean::sampleWith(model, c, s, p, dp, ddp, out, W, terms);
            // the outputs finite (finite input can overflow): the same 0 x test, fused here so
            // that no caller needs a second pass over the outputs
            P zero_out = P{};
            for (int i = 0; i < n; ++i) zero_out += u[i] * 0.0 + du[i] * 0.0 + ddu[i] * 0.0 + tau[i] * 0.0;
            ok &= zero_out == 0.0;
            // the packet's samples against every limit at once (NaN compares false: beyond);
            // the rare packet with a lane beyond one is then taken lane by lane, in sample order
            PackMask beyond = PackMask{};
            if (check_limits) {
                for (int i = 0; i < n; ++i) {
                    const auto ii = static_cast<std::size_t>(i);
                    beyond |= ~((u[i] >= limits.lower[ii]) & (u[i] <= limits.upper[ii]) &
                                (fastmath::absOf(du[i]) <= limits.velocity[ii]) &
                                (fastmath::absOf(tau[i]) <= limits.effort[ii]));
                }
            }
            if (fastmath::any(beyond & ok)) [[unlikely]] {
                for (int l = 0; l < lanes && check_limits; ++l) {
                    if (ok[l] == 0) continue;
                    const auto at = [l](const P* v) { return [v, l](int i) { return v[i][l]; }; };
                    if (const Status s = limits.check(model, at(u), at(du), at(tau)); !s) {
                        result.first_beyond_limits = k + l;
                        result.limits = s;
                        check_limits = false;
                    }
                }
            }
            if (lanes == kLanes && fastmath::all(ok)) [[likely]] {
                if (contiguous_out) {
                    for (int i = 0; i < n; ++i) {
                        const Eigen::Index at = k + i * stride_out;
                        std::memcpy(out_u + at, &u[i], sizeof(P));
                        std::memcpy(out_du + at, &du[i], sizeof(P));
                        std::memcpy(out_ddu + at, &ddu[i], sizeof(P));
                        std::memcpy(out_tau + at, &tau[i], sizeof(P));
                    }
                } else if (rows_out && n == 3) {
                    rowsOfColumns(u[0], u[1], u[2], out_u + k * 3);
                    rowsOfColumns(du[0], du[1], du[2], out_du + k * 3);
                    rowsOfColumns(ddu[0], ddu[1], ddu[2], out_ddu + k * 3);
                    rowsOfColumns(tau[0], tau[1], tau[2], out_tau + k * 3);
                } else if (rows_out) {
                    rowsOfColumns4(u, out_u + k * 4);
                    rowsOfColumns4(du, out_du + k * 4);
                    rowsOfColumns4(ddu, out_ddu + k * 4);
                    rowsOfColumns4(tau, out_tau + k * 4);
                } else {
                    for (int i = 0; i < n; ++i) {
                        scatter(out_u + k * step_u + i * stride_out, step_u, u[i]);
                        scatter(out_du + k * step_du + i * stride_out, step_du, du[i]);
                        scatter(out_ddu + k * step_ddu + i * stride_out, step_ddu, ddu[i]);
                        scatter(out_tau + k * step_tau + i * stride_out, step_tau, tau[i]);
                    }
                }
                continue;
            }
            for (int l = 0; l < lanes; ++l) {
                const Eigen::Index row = k + l;
                if (ok[l] != 0) [[likely]] {
                    for (int i = 0; i < n; ++i) {
                        a.u(row, i) = u[i][l];
                        a.du(row, i) = du[i][l];
                        a.ddu(row, i) = ddu[i][l];
                        a.tau(row, i) = tau[i][l];
                    }
                } else if (const Status status = fullPath(model, data, a, row); !status) {
                    if (result.failed++ == 0) {
                        result.first_failure = row;
                        result.status = status;
                    }
                } else if (a.limits == ActuatorLimits::check && row < result.first_beyond_limits) {
                    // a sample the kernel rejected and the full path accepted: its limits too
                    if (const Status s = limits.check(model, data.u, data.du, data.tau); !s) {
                        result.first_beyond_limits = row;
                        result.limits = s;
                        check_limits = false;
                    }
                }
            }
        }
    };
    // the limbs' constants splatted into packets once per chunk: an arithmetic operand from
    // memory, no broadcast in the limb loop
    std::array<LimbLanesOf<kLanes>, kMaxLimbs> limb_lanes;
    for (int j = 0; j < model.limbs; ++j)
        splatLimb(model.limb[static_cast<std::size_t>(j)], limb_lanes[static_cast<std::size_t>(j)]);
#if !NOCDYN_ASAN()
    // one dispatch per chunk: kind * 3 + actuated joint of a uniform robot (PPP excluded);
    // under the sanitizers every robot takes the per-limb dispatch (the fewest instantiations)
    const auto uniform = [lanes = limb_lanes.data()]<int kCode>()
                             NOCDYN_INLINE_LAMBDA { return detail::lean::UniformLimb<kCode, kLanes>{lanes}; };
    if (!uniformPackets(model, uniform, packets,
                        std::make_integer_sequence<int, 3 * static_cast<int>(LimbKind::PPP)>{}))
#endif
        packets(detail::lean::SplatAny<kLanes>{limb_lanes.data()});
    return result;
}

}  // namespace

}  // namespace nocdyn

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
