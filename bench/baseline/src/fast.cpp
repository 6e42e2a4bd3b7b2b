// The lean per-sample inverse dynamics (see fast.hpp): the batch kernel on one sample, and
// the full path's stages for the Status of the rare samples the kernel rejects.
#include "nocdyn/prr3/fast.hpp"

#include <cmath>
#include <limits>

#include "nocdyn/prr3/dynamics.hpp"
#include "nocdyn/prr3/kinematics.hpp"

namespace nocdyn::prr3 {

namespace {

/// |theta| below which the kernel's branch-free sinCos is exact (batch.hpp: Cody-Waite
/// reduction, exact for |theta| < 1.6e6); beyond it libm's sin and cos are used.
constexpr double kTrigLimit = 1.0e6;

/// A sample the kernel rejected: the full path's position and velocity stages give its exact
/// Status. Should they accept it (the sample is within rounding of a conditioning threshold,
/// where the kernel's division-free checks and the full path's ratios may differ), the full
/// path gives the values too. Kept out of line so that the common path stays short.
#if defined(__GNUC__)
__attribute__((noinline, cold))
#endif
Status
rejected(const Model& model, FastData& out, const Pose& p, const Twist& dp, const Twist& ddp) noexcept {
    Data data;  // fixed size, on the stack: no allocation
    Status status = inverseDynamics(model, data, p, dp, ddp);
    if (status) {
        out.u = data.u;
        out.du = data.du;
        out.ddu = data.ddu;
        out.tau = data.tau;
        return status;
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (JointVector* v : {&out.u, &out.du, &out.ddu, &out.tau}) v->setConstant(nan);
    return status;
}

}  // namespace

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(NOCDYN_NO_TARGET_CLONES)
__attribute__((target_clones("arch=x86-64-v3", "default")))
#endif
Status
inverseDynamicsFast(const Model& model, FastData& data, const Pose& p, const Twist& dp, const Twist& ddp) noexcept {
    const double in[9] = {p(0), p(1), p(2), dp(0), dp(1), dp(2), ddp(0), ddp(1), ddp(2)};
    double s, c;
    if (std::abs(p(0)) < kTrigLimit) [[likely]] {
        batch_detail::sinCos(p(0), s, c);
    } else {
        s = std::sin(p(0));
        c = std::cos(p(0));
    }
    double out[12];
    // u (eqs. 37-42), du (eq. 5), ddu (its derivative), tau (eqs. 16, 20-21, 28-31) and the
    // workspace and conditioning checks of the full path: batch.hpp, sampleGivenSinCos
    if (!batch_detail::sampleGivenSinCos(model.kernel, s, c, in, out)) [[unlikely]]
        return rejected(model, data, p, dp, ddp);
    for (int j = 0; j < kLimbs; ++j) {
        data.u(j) = out[j];
        data.du(j) = out[3 + j];
        data.ddu(j) = out[6 + j];
        data.tau(j) = out[9 + j];
    }
    return {};
}

}  // namespace nocdyn::prr3
