// Our model against the independent engines for any robot: the same robot description and
// trajectory through the general NOC model, Simbody (the reference) and MuJoCo, and the
// differences measured. Shared by `nocdyn validate`, `nocdyn reproduce` and the tests.
#pragma once

#include <string>
#include <vector>

#include "nocdyn/description.hpp"
#include "nocdyn/io/csv.hpp"
#include "nocdyn/analysis/sampling.hpp"
#include "nocdyn/trajectory.hpp"
#include "nocdyn/validation/mechanism_sample.hpp"

namespace nocdyn::validation {

/// Largest differences of one engine's actuator forces and motion from ours.
struct EngineAgreement {
    std::string engine;
    std::vector<double> max_abs;       ///< per actuator, max_t |tau_a - tau_a^engine| [N or N m]
    std::vector<double> max_rel_peak;  ///< the same over max_t |tau_a| (our peak)
    double max_u_abs = 0.0;            ///< max over a, t of |u_a - u_a^engine| [m or rad]
    [[nodiscard]] double worstRelative() const;
};

struct EngineComparison {
    int actuators = 0;
    InverseDynamicsSeries ours;
    std::vector<MechanismSample> simbody, mujoco;
    EngineAgreement simbody_agreement, mujoco_agreement;
};

/// Runs our model (limits recorded, not enforced), Simbody and MuJoCo at the given times.
/// Throws nocdyn::Error for a pose out of reach or a singular posture (ours is run first, so
/// the message names the time and the limb).
[[nodiscard]] EngineComparison compareWithEngines(const RobotDescription& robot, const PoseTrajectory& trajectory,
                                                  const std::vector<double>& times);

/// t,u1..un,tau1..taun,simbody_u1..n,simbody_tau1..n,mujoco_u1..n,mujoco_tau1..n, then the
/// differences simbody_dtau1..n and mujoco_dtau1..n (engine minus ours) [SI].
[[nodiscard]] io::Table toTable(const EngineComparison& comparison);

/// A Markdown table of the largest differences per actuator and engine.
[[nodiscard]] std::string agreementTable(const EngineComparison& comparison);

/// The Markdown table of agreementTable for these engines' agreements alone (header and one
/// row per engine and actuator), for a comparison made elsewhere (a spatial robot's).
[[nodiscard]] std::string agreementRows(const std::vector<const EngineAgreement*>& engines);

}  // namespace nocdyn::validation
