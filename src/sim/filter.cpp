// Zero-phase Butterworth filters (filter.hpp).
#include "nocdyn/sim/filter.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "nocdyn/error.hpp"
#include "nocdyn/text.hpp"

namespace nocdyn {

namespace {

/// One section run over x (in place) in the direction of `index`, from the past inputs x_past
/// and outputs y_past.
template <typename Index>
void runSection(const SecondOrderSection& s, Eigen::Ref<Eigen::VectorXd> x, Index index, double x_past, double y_past) {
    double x1 = x_past, x2 = x_past, y1 = y_past, y2 = y_past;
    const Eigen::Index N = x.size();
    for (Eigen::Index k = 0; k < N; ++k) {
        const double xk = x(index(k));
        const double yk = s.b0 * xk + s.b1 * x1 + s.b2 * x2 - s.a1 * y1 - s.a2 * y2;
        x2 = x1;
        x1 = xk;
        y2 = y1;
        y1 = yk;
        x(index(k)) = yk;
    }
}

/// The sections forward then backward; each pass from steady state or from rest.
void forwardBackward(const ButterworthFilter& filter, Eigen::Ref<Eigen::VectorXd> x, bool steady) {
    const Eigen::Index N = x.size();
    const auto forward = [](Eigen::Index k) { return k; };
    const auto backward = [N](Eigen::Index k) { return N - 1 - k; };
    for (const SecondOrderSection& s : filter.sections) {
        const double x0 = steady ? x(0) : 0.0;
        runSection(s, x, forward, x0, steady ? s.dc_gain * x0 : 0.0);
    }
    for (const SecondOrderSection& s : filter.sections) {
        const double x0 = steady ? x(N - 1) : 0.0;
        runSection(s, x, backward, x0, steady ? s.dc_gain * x0 : 0.0);
    }
}

}  // namespace

ButterworthFilter butterworth(FilterKind kind, int order, double cutoff, double rate) {
    if (!(std::isfinite(rate) && rate > 0.0 && std::isfinite(cutoff) && cutoff > 0.0 && cutoff < 0.5 * rate)) {
        throw Error(text::format("filter: the cut-off %.6g Hz must be above 0 and below half the sampling rate %.6g Hz",
                                 cutoff, rate));
    }
    if (order < 2 || order > 16 || order % 2 != 0) {
        throw Error(text::format("filter: the order must be even and in [2, 16], got %d", order));
    }
    ButterworthFilter filter;
    filter.kind = kind;
    filter.cutoff = cutoff;
    filter.rate = rate;
    // bilinear transform with the cut-off prewarped
    const double K = std::tan(std::numbers::pi * cutoff / rate);
    for (int k = 0; k < order / 2; ++k) {
        // 1 / Q_k (sqrt 2 for the second order)
        const double c = 2.0 * std::cos((2.0 * k + 1.0) * std::numbers::pi / (2.0 * order));
        const double norm = 1.0 / (1.0 + c * K + K * K);
        SecondOrderSection s;
        if (kind == FilterKind::low_pass) {
            s.b0 = K * K * norm;
            s.b1 = 2.0 * s.b0;
            s.dc_gain = 1.0;
        } else {
            s.b0 = norm;
            s.b1 = -2.0 * s.b0;
            s.dc_gain = 0.0;
        }
        s.b2 = s.b0;
        s.a1 = 2.0 * (K * K - 1.0) * norm;
        s.a2 = (1.0 - c * K + K * K) * norm;
        filter.sections.push_back(s);
    }
    return filter;
}

void filterZeroPhase(const ButterworthFilter& filter, Eigen::Ref<Eigen::VectorXd> x, FilterEdges edges) {
    const Eigen::Index n = x.size();
    if (n < 2) return;
    if (edges == FilterEdges::steady_state) {
        forwardBackward(filter, x, true);
        return;
    }
    // odd reflection padding at both ends
    const auto pad = static_cast<Eigen::Index>(
        std::min<double>(static_cast<double>(n - 1), std::ceil(3.0 * filter.rate / filter.cutoff)));
    Eigen::VectorXd y(n + 2 * pad);
    for (Eigen::Index i = 0; i < pad; ++i) {
        y(i) = 2.0 * x(0) - x(pad - i);
        y(n + pad + i) = 2.0 * x(n - 1) - x(n - 2 - i);
    }
    y.segment(pad, n) = x;
    forwardBackward(filter, y, false);
    x = y.segment(pad, n);
}

}  // namespace nocdyn
