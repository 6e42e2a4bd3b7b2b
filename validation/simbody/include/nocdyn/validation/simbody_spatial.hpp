// Independent Simbody model of a spatial parallel robot (SpatialRobotDescription: a Delta as
// 3-RUU, a 6-UPS or 6-RUS hexapod, ...), the spatial counterpart of SimbodyMechanism.
//
// Each limb is a tree from Ground through every listed joint but the last (R a Pin, P a
// Slider, U two Pins through its point with a massless body between them, S three Pins along
// the base axes with two massless bodies), every body frame coinciding with Ground's at home
// so that the description's home data go in unchanged and every mobility is 0 at home. The
// last joint closes the loop on the platform: S a Constraint::Ball at its centre (3
// equations); U a Ball plus a Constraint::ConstantAngle keeping the angle between a1 (in the
// limb's last body) and a2 (in the platform) at its home value (4 equations). The platform
// hangs from Ground on a Translation mobilizer [x, y, z] and three Pins about z (yaw), the new
// y (pitch) and the new x (roll), massless bodies between them, so that its coordinates are
// nocdyn's pose and R = Rz(yaw) Ry(pitch) Rx(roll). Motion full prescribes all six; motion
// translation prescribes the Translation only and leaves the three angles to the limbs' U
// constraints (they come out 0 when the limbs keep the orientation).
//
// Inverse dynamics per sample, as SimbodyMechanism: positions by Simbody's Newton projection
// (projectQ) continued from home along the samples; with G the constraint Jacobian (calcG),
// split into the passive columns G_f and the prescribed ones G_p, the speeds v = N dp with
// N = [-G_f^-1 G_p; I], the accelerations from G v' = -bias (calcBiasForAccelerationConstraints)
// with the prescribed v' = ddp; h = M v' + c - Q_gravity (calcResidualForceIgnoringConstraints);
// the joint friction of every R and P joint -(damping q' + friction sign q') as a generalized
// force Q_f on its mobility; then N^T (h - Q_f) = A^T tau, A = the actuated mobilities' rows of
// N, and tau its minimum-norm solution.
// Shares only spatial_description.hpp with nocdyn; Simbody stays private (pimpl).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "nocdyn/spatial_description.hpp"

namespace nocdyn::validation {

class SimbodySpatialMechanism {
public:
    /// Builds the model. Throws nocdyn::Error for a limb whose last joint is an R or P (not
    /// modelled as a closure here) or when the model is not assembled at home.
    explicit SimbodySpatialMechanism(const SpatialRobotDescription& robot);
    ~SimbodySpatialMechanism();
    SimbodySpatialMechanism(SimbodySpatialMechanism&&) noexcept;
    SimbodySpatialMechanism& operator=(SimbodySpatialMechanism&&) noexcept;
    SimbodySpatialMechanism(const SimbodySpatialMechanism&) = delete;
    SimbodySpatialMechanism& operator=(const SimbodySpatialMechanism&) = delete;

    /// The actuator forces tau (one row per sample, file order) at the poses p with rates dp and
    /// accelerations ddp (each of size 6 [x, y, z, roll, pitch, yaw] or 3 [x, y, z], Euler-angle
    /// rates), friction and damping of the R and P joints included, gravity on. The samples are
    /// a path: each is assembled from the previous one (subdivided when a step fails), the first
    /// from home. Throws nocdyn::Error naming the sample when a pose cannot be assembled or the
    /// closure or actuation is singular.
    Eigen::MatrixXd actuatorForces(const std::vector<Eigen::VectorXd>& p, const std::vector<Eigen::VectorXd>& dp,
                                   const std::vector<Eigen::VectorXd>& ddp);

    /// Number of actuated joints n.
    [[nodiscard]] int actuatorCount() const;

private:
    class Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nocdyn::validation
