// Zero-phase Butterworth filters of sampled signals: the low-pass of the identification's
// measured motion and the high-pass of a ground record's baseline correction.
//
// Design: a Butterworth filter of even order N at cut-off f_c, sampled at f_s, is N / 2
// second-order sections k = 0 .. N/2 - 1, the bilinear transform of
//   low-pass   H_k(s) = w_c^2 / (s^2 + s w_c / Q_k + w_c^2),
//   high-pass  H_k(s) = s^2   / (s^2 + s w_c / Q_k + w_c^2),
// 1 / Q_k = 2 cos((2k + 1) pi / (2N)), with w_c prewarped: K = tan(pi f_c / f_s). Each section
//   y_t = b0 x_t + b1 x_(t-1) + b2 x_(t-2) - a1 y_(t-1) - a2 y_(t-2).
// Zero phase: the sections run forward over the signal, then backward over the result: no
// lag, magnitude |H|^2 (order 2N, -6 dB at f_c).
//
// Edges: each pass must begin somewhere.
//   steady_state:   each section starts as if its first input had been applied forever
//                   (past inputs x_0, past outputs H(1) x_0): no start transient for a
//                   low-pass (unit gain at DC) on a signal that begins at rest;
//   odd_reflection: each end is padded with the odd reflection x(-k) = 2 x(0) - x(k) of
//                   min(n - 1, 3 f_s / f_c) samples, the sections start from rest on the padded
//                   signal, and the padding is dropped (a level or a slope passes through).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace nocdyn {

enum class FilterKind { low_pass, high_pass };
enum class FilterEdges { steady_state, odd_reflection };

/// One second-order section y = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2) x.
struct SecondOrderSection {
    double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;
    double dc_gain = 1.0;  ///< H(1) by design: 1 for a low-pass section, 0 for a high-pass one
};

/// A Butterworth filter: its sections in the order they run, its cut-off and sampling rate.
struct ButterworthFilter {
    FilterKind kind = FilterKind::low_pass;
    double cutoff = 0.0;  ///< f_c [Hz]
    double rate = 0.0;    ///< f_s [Hz]
    std::vector<SecondOrderSection> sections;
};

/// The Butterworth filter of even order `order` (2 .. 16) at cutoff [Hz], sampled at rate [Hz].
/// Throws nocdyn::Error unless 0 < cutoff < rate / 2 (both finite) and the order is even and in
/// range.
[[nodiscard]] ButterworthFilter butterworth(FilterKind kind, int order, double cutoff, double rate);

/// Runs `filter` forward then backward over x in place (see the file header for `edges`).
/// Signals of fewer than two samples are left as they are.
void filterZeroPhase(const ButterworthFilter& filter, Eigen::Ref<Eigen::VectorXd> x, FilterEdges edges);

}  // namespace nocdyn
