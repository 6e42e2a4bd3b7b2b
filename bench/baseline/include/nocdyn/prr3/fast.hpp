// The lean per-sample inverse dynamics of the 3-PRR, for control loops: pose-space sample
// (p, dp, ddp) -> u, du, ddu, tau and a Status, nothing else.
//
// It runs the batch kernel (batch.hpp, batch_detail::sampleGivenSinCos) on one sample: the
// same eqs. 3-7, 16 and 20-21 and 28-31, but without forming T_i, dT_i, J_j^-1, H^-1, I or C
// and without phi_A's asin:
//   tau = sum_i T_i^T M_i dt_i = m_s ddu + g + D H^{-T} W     (one 3 x 3 solve),
// with W the wrench at C of the platform's and links' inertia forces and g the links' direct
// share on their sliders. The values equal prr3::inverseDynamics's to rounding (~1e-15 relative;
// tests/fast_test.cpp asks 1e-12 of value + column peak).
//
// Status: the kernel checks the same conditions as the full path (d_j^M in (0, l), cond D and
// the 1-norm cond of H diag(1/r, 1, 1) at most max_condition, in a division-free form). When a
// check fails, the sample is handed to the full path's position and velocity stages, so the
// returned Status (code, limb and value) is exactly the full path's. Only a sample within
// rounding of a conditioning threshold (cond D or cond H equal to max_condition to ~1e-15) can
// be judged differently by the two formulations.
//
// Never allocates, never throws. The stages that store intermediate quantities (kinematics.hpp,
// dynamics.hpp) remain the entry for callers that read T_i, I, C, J_j^-1, phi_A, ...
#pragma once

#include "nocdyn/prr3/batch.hpp"
#include "nocdyn/prr3/model.hpp"
#include "nocdyn/prr3/status.hpp"

namespace nocdyn::prr3 {

/// Outputs of the lean entry. Holds no model constants (those live in Model::kernel), so one
/// FastData serves any number of models.
struct FastData {
    FastData() = default;
    /// Same as FastData(): kept so that code written when FastData cached a model's constants
    /// still compiles; the argument is not stored.
    explicit FastData(const Model& /*model*/) {}

    JointVector u = JointVector::Zero();    ///< actuator displacements [m]
    JointVector du = JointVector::Zero();   ///< actuator rates [m/s]
    JointVector ddu = JointVector::Zero();  ///< actuator accelerations [m/s^2]
    JointVector tau = JointVector::Zero();  ///< actuator forces on the sliders (eq. 20) [N]
};

/// The lean per-sample path: (p, dp, ddp) -> u, du, ddu, tau (equal to inverseDynamics's).
/// Returns exactly inverseDynamics's Status; on failure u, du, ddu and tau are NaN.
/// Allocation-free and non-throwing.
Status inverseDynamicsFast(const Model& model, FastData& data, const Pose& p, const Twist& dp,
                           const Twist& ddp) noexcept;

}  // namespace nocdyn::prr3
