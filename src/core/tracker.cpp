// The Newton tracker of the working mode (direct_kinematics.hpp): Newton (Gauss-Newton when
// n > 3) on the locked limbs' equations (locked_limbs.hpp) from a predicted pose, then
// inverse displacement on the home branches at the converged pose as the verification.
#include <algorithm>
#include <cmath>
#include <limits>

#include "locked_limbs.hpp"
#include "nocdyn/direct_kinematics.hpp"
#include "stages.hpp"

namespace nocdyn {

namespace {

using namespace detail::locked;

/// The equations are O(1) (lengths over L): a residual at this level needs no further step.
constexpr double kRoundOff = 1e-15;
/// Newton converges quadratically: after a step of s (phi [rad], C over L) the error is about
/// s^2 times the equations' curvature over their slope, O(1) away from singularities; a step
/// below this leaves round-off, so the iterate is taken without evaluating the equations again
/// (the verification by inverse displacement checks it, and Newton resumes when it fails).
constexpr double kLastStep = 1e-8;

/// Outcome of the tracker's Newton iteration.
struct CorrectorResult {
    double residual = std::numeric_limits<double>::infinity();  ///< max |F_i| at the last evaluation
    int iterations = 0;
    bool step_too_large = false;  ///< a step beyond max_step (phi [rad], C over L)
    bool singular = false;        ///< rank-deficient Jacobian
    bool unevaluated = false;     ///< stopped after a round-off-sized step (kLastStep)
};

/// One equation's value and gradient in z = (phi, C / L) at cos phi, sin phi.
struct Row {
    double f = 0.0;
    Vector3 g = Vector3::Zero();
};

inline Row evaluate(const Equation& e, double phi, double cs, double sn, double x, double y) {
    Row r;
    if (e.orientation) {
        r.f = wrapAngle(phi - e.phi0);
        r.g = Vector3(1.0, 0.0, 0.0);
        return r;
    }
    const double ax = e.ax.at(cs, sn), ay = e.ay.at(cs, sn);
    r.f = e.kappa * (x * x + y * y) + ax * x + ay * y + e.b.at(cs, sn);
    r.g = Vector3(e.ax.derivative(cs, sn) * x + e.ay.derivative(cs, sn) * y + e.b.derivative(cs, sn),
                  2.0 * e.kappa * x + ax, 2.0 * e.kappa * y + ay);
    return r;
}

/// Newton (three equations: J step = F by cofactors) or Gauss-Newton (more: the normal
/// equations J^T J step = J^T F, 3 x 3) from z, fixed sizes throughout. With `last_step`, stops
/// without a further evaluation after a step below it.
CorrectorResult newton(const Equations& eqs, Vector3& z, int max_iterations, double max_step, double last_step) {
    CorrectorResult out;
    const int n = eqs.count;
    for (;;) {
        double cs = 1.0, sn = 0.0;
        cosSin(z(0), cs, sn);
        Vector3 step;
        double residual = 0.0;
        if (n == 3) {
            const Row r0 = evaluate(eqs.eq[0], z(0), cs, sn, z(1), z(2));
            const Row r1 = evaluate(eqs.eq[1], z(0), cs, sn, z(1), z(2));
            const Row r2 = evaluate(eqs.eq[2], z(0), cs, sn, z(1), z(2));
            residual = std::max({std::abs(r0.f), std::abs(r1.f), std::abs(r2.f)});
            out.residual = std::isfinite(residual) ? residual : std::numeric_limits<double>::infinity();
            if (!(residual > kRoundOff) || out.iterations >= max_iterations) break;
            // J^-1 = adj J / det J, the columns of adj J the cross products of J's rows (a
            // singular J gives a non-finite step: the mode is lost)
            const Vector3 c0 = detail::cross3(r1.g, r2.g), c1 = detail::cross3(r2.g, r0.g),
                          c2 = detail::cross3(r0.g, r1.g);
            step = (r0.f * c0 + r1.f * c1 + r2.f * c2) / r0.g.dot(c0);
        } else {
            Matrix3 JtJ = Matrix3::Zero();
            Vector3 JtF = Vector3::Zero();
            for (int i = 0; i < n; ++i) {
                const Row r = evaluate(eqs.eq[static_cast<std::size_t>(i)], z(0), cs, sn, z(1), z(2));
                residual = std::max(residual, std::abs(r.f));
                if (!std::isfinite(r.f)) residual = std::numeric_limits<double>::infinity();
                JtJ.noalias() += r.g * r.g.transpose();
                JtF += r.f * r.g;
            }
            out.residual = residual;
            if (!(residual > kRoundOff) || out.iterations >= max_iterations) break;
            // J^T J is symmetric positive definite unless J loses rank: its determinant
            // against the cube of its scale, then the inverse by cofactors
            Matrix3 adj;
            const double det = detail::symmetricAdjugate(JtJ, adj);
            const double scale = JtJ.norm();
            if (!(det > 1e-14 * scale * scale * scale)) {
                out.singular = true;
                break;
            }
            step = adj * JtF / det;
        }
        const double size = step.cwiseAbs().maxCoeff();
        if (!(size <= max_step)) {
            out.step_too_large = true;
            break;
        }
        z -= step;
        ++out.iterations;
        if (size <= last_step * (1.0 + z.cwiseAbs().maxCoeff())) {
            out.unevaluated = true;
            break;
        }
        // a step at round-off of z: the residual cannot fall further
        if (!(size > 1e-15 * (1.0 + z.cwiseAbs().maxCoeff()))) {
            out.residual = kRoundOff;
            break;
        }
    }
    return out;
}

/// Why the tracker found no pose, from the velocity stage at its last iterate: a singular
/// limb or actuation, or next to a limb singularity (the edge of the workspace, where u turns
/// back), or otherwise a lost mode.
Status notTracked(const Model& model, Data& data, const Pose& p, int worst, double residual) {
    if (const Status status = inverseDisplacement(model, data, p); !status) return status;
    if (const Status status = velocityFromPlatformTwist(model, data, Twist::Zero()); !status) return status;
    int limb = -1;
    double largest = 0.1 * model.max_condition;
    for (int j = 0; j < model.limbs; ++j) {
        if (data.limb[static_cast<std::size_t>(j)].cond > largest) {
            largest = data.limb[static_cast<std::size_t>(j)].cond;
            limb = j;
        }
    }
    if (limb >= 0) return {StatusCode::workspace_edge, limb, largest};
    return {StatusCode::assembly_mode_lost, worst, residual};
}

/// Inverse displacement on the home branches at p (passive R angles left to their cos and
/// sin): the largest scaled |u_a(p) - u_a| and the limb of that actuator.
Status verify(const Model& model, Data& data, const ActuatorVector& u, const Pose& p, double& residual, int& worst) {
    if (const Status status = detail::positionStage(model, data, p, false); !status) return status;
    worst = -1;
    residual = 0.0;
    for (int a = 0; a < model.actuators; ++a) {
        const auto aa = static_cast<std::size_t>(a);
        const LimbModel& limb = model.limb[static_cast<std::size_t>(model.actuator_limb[aa])];
        const auto k = static_cast<std::size_t>(model.actuator_joint[aa]);
        double d = data.u(a) - u(a);
        // R joints modulo 2 pi (the remainder only when it can change d)
        if (limb.type[k] == JointType::revolute && !(std::abs(d) <= kPi)) d = wrapAngle(d);
        if (const double e = std::abs(d) * limb.inv_joint_scale[k]; worst < 0 || e > residual) {
            residual = e;
            worst = model.actuator_limb[aa];
        }
    }
    return {};
}

/// The tracker from `start` (p: the previous pose, for the diagnosis; on success the pose).
Status track(const Model& model, Data& data, const ActuatorVector& u, const Pose& start, Pose& p,
             const TrackerOptions& options, TrackerReport& out) {
    const int n = model.actuators;
    for (int a = 0; a < n; ++a) {
        if (!std::isfinite(u(a)))
            return {StatusCode::not_finite, model.actuator_limb[static_cast<std::size_t>(a)], u(a)};
    }
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(start(i))) return {StatusCode::not_finite, -1, start(i)};
    }
    // Newton on the locked limbs' equations (F(p) = 0 exactly where u(p) = u on some branches)
    Equations eqs;
    lockedLimbEquations(model, u, eqs);
    const double L = model.length_scale;
    const double inv_L = 1.0 / L;
    Vector3 z(start(0) - model.home(0), start(1) * inv_L, start(2) * inv_L);
    const double accepted = model.coordinates == Coordinates::platform ? options.max_residual : options.tolerance;
    int worst = -1;
    // at most twice: after a stop on a round-off-sized step that the verification rejects,
    // Newton resumes until the residual itself is at round-off
    for (int pass = 0; pass < 2; ++pass) {
        const CorrectorResult result =
            newton(eqs, z, options.max_iterations - out.iterations, options.max_step, pass == 0 ? kLastStep : 0.0);
        out.iterations += result.iterations;
        const Pose next(model.home(0) + z(0), L * z(1), L * z(2));
        if (result.step_too_large || result.singular || !next.allFinite()) {
            return notTracked(model, data, p, -1, result.residual);
        }
        p = next;
        // inverse displacement on the home branches: the pose is the working mode's if it
        // gives u back there
        if (const Status status = verify(model, data, u, p, out.residual, worst); !status) return status;
        if (out.residual <= accepted) return {};
        if (!result.unevaluated) break;
    }
    return notTracked(model, data, p, worst, out.residual);
}

}  // namespace

Status trackPose(const Model& model, Data& data, const ActuatorVector& u, Pose& p, const TrackerOptions& options,
                 TrackerReport* report) {
    TrackerReport local;
    TrackerReport& out = report != nullptr ? *report : local;
    out = {};
    const Pose start = p;
    return track(model, data, u, start, p, options, out);
}

void PoseTracker::reset(const Pose& p) {
    last_[0] = p;
    known_ = 1;
}

Pose PoseTracker::prediction() const {
    // the polynomial through the last poses at equal steps, one step ahead (finite differences)
    switch (known_) {
        case 1:
            return last_[0];
        case 2:
            return 2.0 * last_[0] - last_[1];
        case 3:
            return 3.0 * (last_[0] - last_[1]) + last_[2];
        default:
            return 4.0 * (last_[0] + last_[2]) - 6.0 * last_[1] - last_[3];
    }
}

Status PoseTracker::step(const Model& model, Data& data, const ActuatorVector& u, const TrackerOptions& options,
                         TrackerReport* report) {
    TrackerReport local;
    TrackerReport& out = report != nullptr ? *report : local;
    out = {};
    Pose p = last_[0];
    Status status = track(model, data, u, prediction(), p, options, out);
    if (!status && status.code != StatusCode::not_finite && known_ > 1) {
        // the extrapolation overshot (e.g. u jumped): from the previous pose, as trackPose
        const int predicted = out.iterations;
        out = {};
        p = last_[0];
        status = track(model, data, u, last_[0], p, options, out);
        out.iterations += predicted;
    }
    if (!status) {
        known_ = 1;
        return status;
    }
    for (std::size_t i = last_.size() - 1; i > 0; --i) last_[i] = last_[i - 1];
    last_[0] = p;
    known_ = std::min(known_ + 1, static_cast<int>(last_.size()));
    return {};
}

}  // namespace nocdyn
