// Zero-phase Butterworth filters (sim/filter.hpp): a sinusoid comes out in phase, scaled by
// the squared magnitude |H|^2 = 1 / (1 + r^(2N)) of the bilinear Butterworth design
// (r = tan(pi f / f_s) / tan(pi f_c / f_s); for the high-pass 1 / (1 + r^(-2N))); the edges
// keep a level (steady state) or a line (odd reflection); the identification's former
// hand-written second-order filter is reproduced bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/error.hpp"
#include "nocdyn/sim/filter.hpp"

namespace nocdyn {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRate = 1000.0;  // f_s [Hz]

Eigen::VectorXd sinusoid(double f, Eigen::Index n) {
    Eigen::VectorXd x(n);
    for (Eigen::Index k = 0; k < n; ++k) x(k) = std::sin(2.0 * kPi * f * static_cast<double>(k) / kRate + 0.3);
    return x;
}

/// |H|^2 of the zero-phase Butterworth at f.
double zeroPhaseGain(FilterKind kind, int order, double f, double cutoff) {
    const double r = std::tan(kPi * f / kRate) / std::tan(kPi * cutoff / kRate);
    const double p = std::pow(r, 2.0 * order);
    return kind == FilterKind::low_pass ? 1.0 / (1.0 + p) : p / (1.0 + p);
}

/// Largest |y - g x| over the samples at least `edge` from either end.
double interiorError(const Eigen::VectorXd& y, const Eigen::VectorXd& x, double g, Eigen::Index edge) {
    const Eigen::Index n = x.size();
    return (y.segment(edge, n - 2 * edge) - g * x.segment(edge, n - 2 * edge)).cwiseAbs().maxCoeff();
}

struct Case {
    FilterKind kind;
    int order;
    double cutoff, f;
    FilterEdges edges;
};

TEST(Filter, SinusoidComesOutInPhaseScaledBySquaredMagnitude) {
    const Case cases[] = {
        {FilterKind::low_pass, 2, 50.0, 5.0, FilterEdges::steady_state},       // pass band
        {FilterKind::low_pass, 2, 50.0, 200.0, FilterEdges::steady_state},     // stop band
        {FilterKind::low_pass, 4, 50.0, 50.0, FilterEdges::odd_reflection},    // at the cut-off: 1/2
        {FilterKind::high_pass, 4, 20.0, 100.0, FilterEdges::odd_reflection},  // pass band
        {FilterKind::high_pass, 4, 20.0, 5.0, FilterEdges::odd_reflection},    // stop band
        {FilterKind::high_pass, 6, 20.0, 20.0, FilterEdges::steady_state},     // at the cut-off
    };
    for (const Case& c : cases) {
        const ButterworthFilter filter = butterworth(c.kind, c.order, c.cutoff, kRate);
        ASSERT_EQ(filter.sections.size(), static_cast<std::size_t>(c.order / 2));
        const Eigen::VectorXd x = sinusoid(c.f, 4000);
        Eigen::VectorXd y = x;
        filterZeroPhase(filter, y, c.edges);
        const double g = zeroPhaseGain(c.kind, c.order, c.f, c.cutoff);
        // the start and end transients die out within 1000 samples (at least 2 cut-off periods)
        EXPECT_LT(interiorError(y, x, g, 1000), 1e-9)
            << "order " << c.order << (c.kind == FilterKind::low_pass ? " low" : " high") << "-pass, f_c " << c.cutoff
            << " Hz, f " << c.f << " Hz, gain " << g;
    }
    // the stop band's gain is what the design says, not merely small: 200 Hz at f_c 50 Hz
    EXPECT_NEAR(zeroPhaseGain(FilterKind::low_pass, 2, 200.0, 50.0), 0.0022537, 1e-6);
}

TEST(Filter, SteadyStateEdgesKeepALevelExactlyAndALowPassHasNoStartTransient) {
    const ButterworthFilter low = butterworth(FilterKind::low_pass, 2, 10.0, kRate);
    Eigen::VectorXd level = Eigen::VectorXd::Constant(300, 2.5);
    filterZeroPhase(low, level, FilterEdges::steady_state);
    EXPECT_LT((level.array() - 2.5).abs().maxCoeff(), 1e-12);
    // a high-pass removes it, from the first sample on
    const ButterworthFilter high = butterworth(FilterKind::high_pass, 4, 10.0, kRate);
    Eigen::VectorXd offset = Eigen::VectorXd::Constant(300, 2.5);
    filterZeroPhase(high, offset, FilterEdges::steady_state);
    EXPECT_LT(offset.cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Filter, OddReflectionEdgesPassALineThroughALowPass) {
    const ButterworthFilter low = butterworth(FilterKind::low_pass, 4, 20.0, kRate);
    Eigen::VectorXd line(500);
    for (Eigen::Index k = 0; k < line.size(); ++k) line(k) = 1.0 + 0.01 * static_cast<double>(k);
    Eigen::VectorXd y = line;
    filterZeroPhase(low, y, FilterEdges::odd_reflection);
    // the padding (3 f_s / f_c = 150 samples, three cut-off periods) lets the start-from-rest
    // transient of the slowest pole (decay rate 0.383 w_c) die to about e^-7 of the step into the
    // padding: a few thousandths, at the ends only
    const double range = line(line.size() - 1) - line(0);
    EXPECT_LT((y - line).cwiseAbs().maxCoeff(), 2e-3 * range);
    EXPECT_LT((y - line).segment(200, 100).cwiseAbs().maxCoeff(), 1e-6 * range);  // and is gone inside
    // steady-state edges instead bend a line at both ends (a level is assumed before the start)
    Eigen::VectorXd bent = line;
    filterZeroPhase(low, bent, FilterEdges::steady_state);
    EXPECT_GT(std::abs(bent(0) - line(0)), 10.0 * std::abs(y(0) - line(0)));
}

TEST(Filter, ShortSignalsAreLeftAsTheyAre) {
    const ButterworthFilter low = butterworth(FilterKind::low_pass, 2, 10.0, kRate);
    Eigen::VectorXd one = Eigen::VectorXd::Constant(1, 3.0);
    filterZeroPhase(low, one, FilterEdges::odd_reflection);
    EXPECT_EQ(one(0), 3.0);
    Eigen::VectorXd none(0);
    filterZeroPhase(low, none, FilterEdges::steady_state);
    EXPECT_EQ(none.size(), 0);
    // two samples: the reflection is one sample long
    Eigen::VectorXd two(2);
    two << 1.0, 1.0;
    filterZeroPhase(low, two, FilterEdges::odd_reflection);
    EXPECT_TRUE(two.allFinite());
}

TEST(Filter, RejectsACutoffOutsideTheBandAndAnOddOrder) {
    EXPECT_THROW((void)butterworth(FilterKind::low_pass, 2, 0.0, kRate), Error);
    EXPECT_THROW((void)butterworth(FilterKind::low_pass, 2, 500.0, kRate), Error);
    EXPECT_THROW((void)butterworth(FilterKind::low_pass, 2, std::nan(""), kRate), Error);
    EXPECT_THROW((void)butterworth(FilterKind::high_pass, 2, 10.0, std::numeric_limits<double>::infinity()), Error);
    EXPECT_THROW((void)butterworth(FilterKind::high_pass, 3, 10.0, kRate), Error);
    EXPECT_THROW((void)butterworth(FilterKind::high_pass, 18, 10.0, kRate), Error);
}

/// The identification's filter as it was written by hand: one second-order low-pass section,
/// each pass started at the steady state of its first value.
void handWrittenLowPass(Eigen::Ref<Eigen::VectorXd> x, double cutoff, double rate) {
    const double K = std::tan(std::numbers::pi * cutoff / rate);
    const double norm = 1.0 / (1.0 + std::numbers::sqrt2 * K + K * K);
    const double b0 = K * K * norm, b1 = 2.0 * b0, b2 = b0;
    const double a1 = 2.0 * (K * K - 1.0) * norm, a2 = (1.0 - std::numbers::sqrt2 * K + K * K) * norm;
    const Eigen::Index N = x.size();
    const auto pass = [&](auto index) {
        double x1 = x(index(0)), x2 = x1, y1 = x1, y2 = x1;
        for (Eigen::Index k = 0; k < N; ++k) {
            const double xk = x(index(k));
            const double yk = b0 * xk + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
            x2 = x1;
            x1 = xk;
            y2 = y1;
            y1 = yk;
            x(index(k)) = yk;
        }
    };
    pass([](Eigen::Index k) { return k; });
    pass([N](Eigen::Index k) { return N - 1 - k; });
}

TEST(Filter, SecondOrderLowPassEqualsTheIdentificationsFormerFilterBitForBit) {
    Eigen::VectorXd x = sinusoid(7.0, 1500) + 0.2 * sinusoid(180.0, 1500);
    for (Eigen::Index k = 0; k < x.size(); ++k) x(k) += 0.001 * static_cast<double>(k % 17);
    Eigen::VectorXd expected = x, y = x;
    handWrittenLowPass(expected, 50.0, kRate);
    filterZeroPhase(butterworth(FilterKind::low_pass, 2, 50.0, kRate), y, FilterEdges::steady_state);
    for (Eigen::Index k = 0; k < x.size(); ++k) ASSERT_EQ(y(k), expected(k)) << "sample " << k;
}

}  // namespace
}  // namespace nocdyn
