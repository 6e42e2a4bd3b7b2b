// Branch-free elementary functions for the lean and batch kernels, on a double or on a
// packet of four or eight samples (GCC/Clang vector extension), so that one kernel runs per
// sample and vectorised across samples. Robot-independent; not part of the API.
#pragma once

#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <type_traits>

#if defined(__x86_64__) || defined(_M_X64)
#include <emmintrin.h>
#if defined(__AVX__)
#include <immintrin.h>
#endif
#endif

// Kernels must be inlined into their loops (and into the loops' AVX2 clones).
#if defined(__GNUC__)
#define NOCDYN_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define NOCDYN_ALWAYS_INLINE inline
#endif
#ifndef NOCDYN_INLINE_LAMBDA
#if defined(__GNUC__)
#define NOCDYN_INLINE_LAMBDA __attribute__((always_inline))
#else
#define NOCDYN_INLINE_LAMBDA
#endif
#endif

// A packet is passed in registers only where its functions are inlined (always here): the
// note that a 32-byte vector argument's ABI depends on AVX does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace nocdyn::fastmath {

/// Four samples of one scalar, lane l = sample l; one AVX2 register, two SSE2 ones.
using Pack = double __attribute__((vector_size(32)));
/// A lane-wise truth value of a Pack comparison: all bits set (true) or clear (false).
using PackMask = std::int64_t __attribute__((vector_size(32)));
inline constexpr int kLanes = 4;
/// Eight samples: one AVX-512 register (the batch where the CPU has it), two AVX2 ones.
using Pack8 = double __attribute__((vector_size(64)));
using Pack8Mask = std::int64_t __attribute__((vector_size(64)));

/// The truth value of a comparison of S: bool for double, a lane mask for a packet.
template <class S>
struct MaskOf {
    using type = bool;
};
template <>
struct MaskOf<Pack> {
    using type = PackMask;
};
template <>
struct MaskOf<Pack8> {
    using type = Pack8Mask;
};
template <class S>
using Mask = typename MaskOf<S>::type;

/// A packet of samples (four or eight lanes) and its lane masks.
template <class S>
concept Packet = std::is_same_v<S, Pack> || std::is_same_v<S, Pack8>;
/// (Clang's comparisons give vectors of long long, GCC's of int64_t: any integer vector of a
/// packet's size.)
template <class M>
concept PacketMask = (sizeof(M) == sizeof(Pack) || sizeof(M) == sizeof(Pack8)) && !std::is_class_v<M> &&
                     !std::is_array_v<M> && requires(const M& m) {
    { m[0] } -> std::convertible_to<std::int64_t>;
};
/// The number of samples in an S.
template <class S>
inline constexpr int kLanesOf = static_cast<int>(sizeof(S) / sizeof(double));

/// x as an S (every lane x).
template <class S>
NOCDYN_ALWAYS_INLINE S splat(double x) {
    if constexpr (sizeof(S) == sizeof(double)) {
        return x;
    } else {
        return S{} + x;
    }
}

NOCDYN_ALWAYS_INLINE double select(bool c, double a, double b) { return c ? a : b; }
template <Packet P>
NOCDYN_ALWAYS_INLINE P select(const Mask<P>& c, const P& a, const P& b) {
    return c ? a : b;
}
NOCDYN_ALWAYS_INLINE double sqrtOf(double x) { return std::sqrt(x); }
/// Lane-wise sqrt (NaN for a negative lane, no errno): one instruction where the file is
/// built for AVX (AVX-512 for eight lanes), else SSE2 on x86-64 two lanes at a time, libm
/// elsewhere.
template <Packet P>
NOCDYN_ALWAYS_INLINE P sqrtOf(const P& x) {
#if defined(__AVX512F__)
    // (the masked form with every lane set: _mm512_sqrt_pd's undefined pass-through value
    // draws GCC 12's maybe-uninitialized warning)
    if constexpr (kLanesOf<P> == 8) return _mm512_mask_sqrt_pd(x, static_cast<__mmask8>(0xFF), x);
#endif
#if defined(__AVX__)
    if constexpr (kLanesOf<P> == 4) return _mm256_sqrt_pd(x);
#endif
    P r;
#if defined(__NO_MATH_ERRNO__)
    // no errno to set: lane by lane, which GCC's SLP vectoriser merges into the widest sqrt
    // of the target (or of a target_clones clone)
    for (int i = 0; i < kLanesOf<P>; ++i) r[i] = __builtin_sqrt(x[i]);
#elif defined(__x86_64__) || defined(_M_X64)
    for (int i = 0; i < kLanesOf<P>; i += 2) {
        const __m128d v = _mm_sqrt_pd(__m128d{x[i], x[i + 1]});
        r[i] = v[0], r[i + 1] = v[1];
    }
#else
    for (int i = 0; i < kLanesOf<P>; ++i) r[i] = std::sqrt(x[i]);
#endif
    return r;
}
NOCDYN_ALWAYS_INLINE double absOf(double x) { return std::abs(x); }
/// |x|: the sign bit cleared (one AND).
template <Packet P>
NOCDYN_ALWAYS_INLINE P absOf(const P& x) {
    return std::bit_cast<P>(std::bit_cast<Mask<P>>(x) & (Mask<P>{} + INT64_MAX));
}
/// max and min as std::max and std::min (a NaN in b is ignored, in a is kept).
NOCDYN_ALWAYS_INLINE double maxOf(double a, double b) { return a < b ? b : a; }
template <Packet P>
NOCDYN_ALWAYS_INLINE P maxOf(const P& a, const P& b) {
    return b > a ? b : a;
}
/// copysign(x, y) for x >= 0.
NOCDYN_ALWAYS_INLINE double withSignOf(double x, double y) { return std::copysign(x, y); }
template <Packet P>
NOCDYN_ALWAYS_INLINE P withSignOf(const P& x, const P& y) {
    const Mask<P> sign = std::bit_cast<Mask<P>>(y) & (Mask<P>{} + INT64_MIN);
    return std::bit_cast<P>(std::bit_cast<Mask<P>>(x) | sign);
}
NOCDYN_ALWAYS_INLINE bool notOf(bool m) { return !m; }
template <PacketMask M>
NOCDYN_ALWAYS_INLINE M notOf(const M& m) {
    return ~m;
}
/// Whether every lane (any lane) is true.
NOCDYN_ALWAYS_INLINE bool all(bool m) { return m; }
template <PacketMask M>
NOCDYN_ALWAYS_INLINE bool all(const M& m) {
    std::int64_t r = m[0];
    for (int i = 1; i < kLanesOf<M>; ++i) r &= m[i];
    return r != 0;
}
template <PacketMask M>
NOCDYN_ALWAYS_INLINE bool any(const M& m) {
    std::int64_t r = m[0];
    for (int i = 1; i < kLanesOf<M>; ++i) r |= m[i];
    return r != 0;
}

/// sin x and cos x without branches or calls, so that a loop over samples vectorises:
/// Cody-Waite reduction by pi/2 in three parts (exact for |x| < 1.6e6; callers hand larger
/// angles to libm) and the fdlibm minimax polynomials on [-pi/4, pi/4].
template <class S>
NOCDYN_ALWAYS_INLINE void sinCos(const S& x, S& s, S& c) {
    const double magic = 6755399441055744.0;                   // 1.5 * 2^52: (v + magic) - magic rounds v
    const S q = (x * 0.63661977236758134308 + magic) - magic;  // nearest integer to x / (pi/2)
    const S rr =
        ((x - q * 1.57079632673412561417e+00) - q * 6.07710050630396597660e-11) - q * 2.02226624871116645580e-21;
    const S z = rr * rr;
    const S sin_r = rr + rr * z *
                             (-1.66666666666666324348e-01 +
                              z * (8.33333333332248946124e-03 +
                                   z * (-1.98412698298579493134e-04 +
                                        z * (2.75573137070700676789e-06 +
                                             z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10)))));
    const S cos_r =
        (1.0 - 0.5 * z) + z * z *
                              (4.16666666666666019037e-02 +
                               z * (-1.38888888888741095749e-03 +
                                    z * (2.48015872894767294178e-05 +
                                         z * (-2.75573143513906633035e-07 +
                                              z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
    // quadrant m = q mod 4 in {0, 1, 2, 3}: floor(q / 4) by the same rounding trick
    const S m = q - 4.0 * ((q * 0.25 - 0.375 + magic) - magic);
    const auto odd = (m == 1.0) | (m == 3.0);
    const S s0 = select(odd, cos_r, sin_r);
    const S c0 = select(odd, sin_r, cos_r);
    s = select(m >= 2.0, -s0, s0);
    c = select((m == 1.0) | (m == 2.0), -c0, c0);
}

/// v[k] lane by lane, k = b1 + b2 + b3 + b4 for b1 >= b2 >= b3 >= b4.
template <class S, class M>
NOCDYN_ALWAYS_INLINE S pick(const M& b1, const M& b2, const M& b3, const M& b4, const double* v) {
    S r = splat<S>(v[0]);
    r = select(b1, splat<S>(v[1]), r);
    r = select(b2, splat<S>(v[2]), r);
    r = select(b3, splat<S>(v[3]), r);
    return select(b4, splat<S>(v[4]), r);
}

/// The angle from its cosine and sine: atan2(y, x) for (x, y) != (0, 0), finite.
/// Branch-free and within 2 ulp of libm's (tested), about a third of its cost. fdlibm's
/// atan (s_atan.c): t = |y| / |x| is reduced by the breakpoints 7/16, 11/16, 19/16, 39/16
/// to r = (a t + b) / (c t + d) with |r| <= 7/16, so atan t = atan(t_k) + atan r, the latter
/// by an odd polynomial of degree 23; here r takes one division, (a|y| + b|x|) / (c|y| + d|x|).
/// Then the quadrant: pi - atan t for x < 0, the sign of y. On a double the interval's
/// constants are looked up, on a Pack selected lane by lane (the same values).
template <class S>
NOCDYN_ALWAYS_INLINE S atan2Of(const S& y, const S& x) {
    const S ay = absOf(y), ax = absOf(x);
    // r = (a t + b) / (c t + d): t; (2t - 1) / (2 + t); (t - 1) / (t + 1); (t - 1.5) / (1 + 1.5 t); -1 / t
    static constexpr double kA[5] = {1.0, 2.0, 1.0, 1.0, 0.0}, kB[5] = {0.0, -1.0, -1.0, -1.5, -1.0};
    static constexpr double kC[5] = {0.0, 1.0, 1.0, 1.5, 1.0}, kD[5] = {1.0, 2.0, 1.0, 1.0, 0.0};
    // atan(t_k) in two parts (hi + lo): 0, atan 0.5, atan 1, atan 1.5, pi / 2
    static constexpr double kHi[5] = {0.0, 4.63647609000806093515e-01, 7.85398163397448278999e-01,
                                      9.82793723247329054082e-01, 1.57079632679489655800e+00};
    static constexpr double kLo[5] = {0.0, 2.26987774529616870924e-17, 3.06161699786838301793e-17,
                                      1.39033110312309984516e-17, 6.12323399573676603587e-17};
    // interval k of t = ay / ax, by comparisons free of division (t = inf when ax = 0)
    const auto b1 = ay >= 0.4375 * ax, b2 = ay >= 0.6875 * ax, b3 = ay >= 1.1875 * ax, b4 = ay >= 2.4375 * ax;
    S a, b, c, d, hi, lo;
    if constexpr (sizeof(S) == sizeof(double)) {
        const int k = static_cast<int>(b1) + static_cast<int>(b2) + static_cast<int>(b3) + static_cast<int>(b4);
        a = kA[k], b = kB[k], c = kC[k], d = kD[k], hi = kHi[k], lo = kLo[k];
    } else {
        a = pick<S>(b1, b2, b3, b4, kA), b = pick<S>(b1, b2, b3, b4, kB), c = pick<S>(b1, b2, b3, b4, kC);
        d = pick<S>(b1, b2, b3, b4, kD), hi = pick<S>(b1, b2, b3, b4, kHi), lo = pick<S>(b1, b2, b3, b4, kLo);
    }
    const S r = (a * ay + b * ax) / (c * ay + d * ax);
    const S z = r * r, w = z * z;
    const S s1 = z * (3.33333333333329318027e-01 +
                      w * (1.42857142725034663711e-01 +
                           w * (9.09088713343650656196e-02 +
                                w * (6.66107313738753120669e-02 +
                                     w * (4.97687799461593236017e-02 + w * 1.62858201153657823623e-02)))));
    const S s2 =
        w *
        (-1.99999999998764832476e-01 +
         w * (-1.11111104054623557880e-01 +
              w * (-7.69187620504482999495e-02 + w * (-5.83357013379057348645e-02 + w * -3.65315727442169155270e-02))));
    const S t = hi - ((r * (s1 + s2) - lo) - r);  // atan(ay / ax) in [0, pi / 2]
    // x < 0: pi - t, pi = pi_hi + pi_lo
    const S q = select(x < 0.0, 3.1415926535897931160e+00 - (t - 1.2246467991473531772e-16), t);
    return withSignOf(q, y);
}

}  // namespace nocdyn::fastmath

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
