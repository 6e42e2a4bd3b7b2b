// Counts the floating-point operations of one sample of the batch kernel (batch.hpp) by
// running it on a counting scalar, and prints them with the bound they imply.
#include <cstdio>

#include "fixture.hpp"
#include "nocdyn/prr3/batch.hpp"

namespace counting {

struct Counts {
    long add = 0, mul = 0, div = 0, sqrt = 0, neg = 0, abs = 0, cmp = 0, select = 0;
};
inline Counts counts;

/// A double that counts every operation done on it.
struct Counted {
    double v = 0.0;
    Counted() = default;
    Counted(double x) : v(x) {}  // NOLINT: constants mix freely, as with double
};
inline Counted operator+(Counted a, Counted b) {
    ++counts.add;
    return a.v + b.v;
}
inline Counted operator-(Counted a, Counted b) {
    ++counts.add;
    return a.v - b.v;
}
inline Counted operator*(Counted a, Counted b) {
    ++counts.mul;
    return a.v * b.v;
}
inline Counted operator/(Counted a, Counted b) {
    ++counts.div;
    return a.v / b.v;
}
inline Counted operator-(Counted a) {
    ++counts.neg;
    return -a.v;
}
inline bool operator<(Counted a, Counted b) {
    ++counts.cmp;
    return a.v < b.v;
}
inline bool operator>(Counted a, Counted b) {
    ++counts.cmp;
    return a.v > b.v;
}
inline bool operator<=(Counted a, Counted b) {
    ++counts.cmp;
    return a.v <= b.v;
}
inline bool operator>=(Counted a, Counted b) {
    ++counts.cmp;
    return a.v >= b.v;
}
inline bool operator==(Counted a, Counted b) {
    ++counts.cmp;
    return a.v == b.v;
}
inline Counted sqrtOf(Counted a) {
    ++counts.sqrt;
    return std::sqrt(a.v);
}
inline Counted absOf(Counted a) {
    ++counts.abs;
    return std::abs(a.v);
}
inline Counted select(bool c, Counted a, Counted b) {
    ++counts.select;
    return c ? a : b;
}

}  // namespace counting

int main() {
    using counting::Counted;
    const auto& f = nocdyn::bench::fixture();
    const auto k = nocdyn::prr3::batch_detail::constants(f.model);
    const auto& s = f.samples[123];
    Counted in[9], out[12];
    for (int i = 0; i < 3; ++i) in[i] = s.p(i), in[3 + i] = s.dp(i), in[6 + i] = s.ddp(i);
    counting::counts = {};
    const bool ok = nocdyn::prr3::batch_detail::sample(k, in, out);
    const auto& c = counting::counts;
    std::printf("one sample of the batch kernel (valid=%d, tau_1 = %.6f N, per-sample path %.6f N)\n", ok, out[9].v,
                s.tau(0));
    std::printf("  add/sub %ld, mul %ld, div %ld, sqrt %ld, neg %ld, abs %ld, compare %ld, select %ld\n", c.add, c.mul,
                c.div, c.sqrt, c.neg, c.abs, c.cmp, c.select);
    std::printf("  of which sin+cos (one call each, polynomial): see README; no other transcendental\n");
    const long arith = c.add + c.mul + c.neg + c.abs + c.cmp + c.select;
    std::printf("  arithmetic (add, mul, neg, abs, compare, select) %ld + div %ld + sqrt %ld\n", arith, c.div, c.sqrt);
    // sin/cos alone
    counting::counts = {};
    Counted sn, cs;
    nocdyn::prr3::batch_detail::sinCos(Counted(0.3), sn, cs);
    std::printf("  sinCos alone: add/sub %ld, mul %ld, neg %ld, compare %ld, select %ld\n", counting::counts.add,
                counting::counts.mul, counting::counts.neg, counting::counts.cmp, counting::counts.select);
    return ok ? 0 : 1;
}
