// Our model against the independent engines (Simbody, the reference; MuJoCo, the second):
// the same robot file and trajectory through all three, and the differences measured.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "nocdyn/io/csv.hpp"
#include "nocdyn/sampling.hpp"
#include "nocdyn/robot.hpp"
#include "nocdyn/trajectory.hpp"

namespace nocdyn::cli {

/// Largest differences of one engine's actuator forces from ours.
struct EngineAgreement {
    std::string engine;
    std::array<double, 3> max_abs{};       ///< max_t |tau_j - tau_j^engine| [N]
    std::array<double, 3> max_rel_peak{};  ///< the same over max_t |tau_j| (our peak force)
    double max_u_abs = 0.0;                ///< max over j, t of |u_j - u_j^engine| [m]
};

struct EngineComparison {
    InverseDynamicsSeries ours;  ///< our model: the robot expanded to the general form
    std::vector<Eigen::Vector3d> simbody_u, simbody_tau, mujoco_u, mujoco_tau;
    EngineAgreement simbody, mujoco;
};

/// Runs our model (limits recorded, not enforced), Simbody and MuJoCo at the given times.
/// Throws nocdyn::Error for a pose outside the workspace or a singular posture (ours is
/// run first, so the message names the time and the limb).
[[nodiscard]] EngineComparison compareWithEngines(const RobotParameters& robot, const PoseTrajectory& trajectory,
                                                  const std::vector<double>& times);

/// t,u1..u3,tau1..tau3,simbody_u1..3,simbody_tau1..3,mujoco_u1..3,mujoco_tau1..3,
/// then the differences simbody_dtau1..3 and mujoco_dtau1..3 (engine minus ours) [SI].
[[nodiscard]] io::Table toTable(const EngineComparison& comparison);

/// A plain-text (and Markdown) table of the largest differences per actuator and engine.
[[nodiscard]] std::string agreementTable(const EngineComparison& comparison);

}  // namespace nocdyn::cli
